"""Scoring S(n) = H_floor · Σ p_i w_i Sim(n, c_i) on the oracle graph of small_scene,
with candidates given directly (candidate generation against a real store is covered by
the integration tests)."""

from __future__ import annotations

import pytest

from inherit_sg.perception.colour_names import NEIGHBOUR_MAX, name_similarity
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.candidates import Candidates
from inherit_sg.retrieval.constraints import AttributeConstraint
from inherit_sg.retrieval.graph_checks import GraphChecker, Landmarks
from inherit_sg.retrieval.plan import Compiler, NodeSpec
from inherit_sg.retrieval.scoring import (
    MATERIAL_MISMATCH_SIM,
    UNKNOWN_SIM,
    Scored,
    Scorer,
    attribute_sim,
    landmark_quality,
)
from inherit_sg.retrieval.snapshot import MapSnapshot
from tests.unit.retrieval_fixtures import hash_similarity, small_snapshot


def rank(snap: MapSnapshot, text: str) -> list[Scored]:
    """Score every object for the request (landmarks first, as the engine does)."""
    plan = Compiler(snap, hash_similarity()).compile(parse_rules(text))
    scorer = Scorer(snap, GraphChecker(snap))

    def evaluate(spec: NodeSpec) -> list[Scored]:
        marks: dict[str, Landmarks] = {
            k: landmark_quality(sub, evaluate(sub)) for k, sub in spec.landmarks.items()
        }
        cands = Candidates()
        for oid in snap.objects:
            cands.add(oid, "test")
        for oid in spec.exclude_ids:
            cands.found_by.pop(oid, None)
        return scorer.score(spec, cands, marks)[0]

    return evaluate(plan.target)


@pytest.fixture(scope="module")
def snap() -> MapSnapshot:
    return small_snapshot()


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("the mug on the coffee table", "obj:m3"),
        ("the mug on the counter", "obj:m2"),
        ("the chair next to the table", "obj:c1"),
        ("the lamp next to the table", "obj:l2"),
        ("the plant between the sofa and the armchair", "obj:p1"),
        ("the painting above the bed", "obj:pt1"),
        ("the sink under the mirror", "obj:sk1"),
        ("the table with a mug on it", "obj:t1"),
        ("the red chair", "obj:c3"),
        ("the mug in the living room", "obj:m3"),
        ("the chair upstairs", "obj:c3"),
        ("the mug on the table next to the chair", "obj:m1"),
    ],
)
def test_top_candidate(snap: MapSnapshot, text: str, expected: str) -> None:
    ranked = rank(snap, text)
    assert ranked[0].id == expected, [(c.id, round(c.score, 2)) for c in ranked[:4]]


def test_terms_are_kept_per_constraint(snap: MapSnapshot) -> None:
    top = rank(snap, "the mug on the counter in the kitchen")[0]
    kinds = {t.kind: t for t in top.terms.values()}
    assert set(kinds) == {"label", "relation", "room"}
    assert kinds["relation"].value == pytest.approx(0.8)
    assert "obj:k1" in kinds["relation"].why
    assert top.score == pytest.approx(sum(t.value for t in top.terms.values()))


def test_negation_penalises(snap: MapSnapshot) -> None:
    ranked = rank(snap, "a mug that is not in the kitchen")
    assert ranked[0].id == "obj:m3"
    kitchen = next(c for c in ranked if c.id == "obj:m1")
    room_term = next(t for t in kitchen.terms.values() if t.kind == "room")
    assert room_term.polarity == -1 and room_term.value < 0
    assert rank(snap, "a chair that is not red")[0].id != "obj:c3"


def test_floor_filter_and_global_fallback(snap: MapSnapshot) -> None:
    ranked = rank(snap, "a lamp on the second floor")
    assert ranked[0].id == "obj:l3" and ranked[0].h_floor == 1
    assert all(c.h_floor == 0 for c in ranked if snap.level_of(c.id) == 0)
    # no mug upstairs: the filter is lifted rather than answering nothing
    ranked = rank(snap, "a mug on the second floor")
    assert ranked[0].id in {"obj:m1", "obj:m2", "obj:m3"} and ranked[0].h_floor == 1
    # a weak look-alike upstairs does not count as a match: the sofa downstairs wins
    ranked = rank(snap, "the sofa on the second floor")
    assert ranked[0].id == "obj:s1" and ranked[0].h_floor == 1


def test_superlatives_rank_the_best_tier(snap: MapSnapshot) -> None:
    assert rank(snap, "the largest chair")[0].id == "obj:c1"  # blue, large
    assert rank(snap, "the smallest mug")[0].id in {"obj:m1", "obj:m2", "obj:m3"}
    assert rank(snap, "the tallest thing in the kitchen")[0].id == "obj:d1"
    assert rank(snap, "the lamp closest to the sofa")[0].id == "obj:l1"


def test_attribute_sim_prefers_measured_attributes(snap: MapSnapshot) -> None:
    red = AttributeConstraint(key="colour", value="red")
    assert attribute_sim(snap, "obj:c3", red)[0] == 1.0
    assert attribute_sim(snap, "obj:c1", red) == (0.0, "colour is blue")
    # a neighbouring name shares part of the credit: a red chair asked for as orange
    orange = AttributeConstraint(key="colour", value="orange")
    sim, why = attribute_sim(snap, "obj:c3", orange)
    assert 0.0 < sim <= NEIGHBOUR_MAX and why == "colour is red, close to orange"
    assert sim == name_similarity("red", "orange") < name_similarity("red", "red") == 1.0
    assert name_similarity("white", "black") == 0.0
    small = AttributeConstraint(key="size", value="small")
    assert attribute_sim(snap, "obj:m2", small)[0] == 1.0


def test_unobserved_attributes_are_neutral_not_mismatches() -> None:
    snap = small_snapshot()
    wood = AttributeConstraint(key="material", value="wood")
    assert attribute_sim(snap, "obj:t1", wood)[0] == 1.0
    # a material read from texture is a weak cue: a mismatch ranks below "not observed"
    # but is no contradiction
    assert attribute_sim(snap, "obj:c2", wood) == (MATERIAL_MISMATCH_SIM, "material is metal")
    assert 0.0 < MATERIAL_MISMATCH_SIM < UNKNOWN_SIM
    c2, c3 = snap.objects["obj:c2"], snap.objects["obj:c3"]
    c2.attributes.pop("material")  # the map could not tell these
    c2.description = "a chair"
    c3.attributes["colour"] = "unknown"
    c3.description = "a chair"
    sim, why = attribute_sim(snap, "obj:c2", wood)
    assert 0.0 < sim == UNKNOWN_SIM < 1.0 and why == "material not observed"
    red = AttributeConstraint(key="colour", value="red")
    assert attribute_sim(snap, "obj:c3", red) == (UNKNOWN_SIM, "colour not observed")
    # a wooden chair first, then the one of unknown material, the plastic one last
    spec = Compiler(snap, hash_similarity()).compile(parse_rules("the wooden chair")).target
    cands = Candidates(found_by={o: ["test"] for o in ("obj:c1", "obj:c2", "obj:c3")})
    ranked, _ = Scorer(snap, GraphChecker(snap)).score(spec, cands, {})
    assert [c.id for c in ranked] == ["obj:c1", "obj:c2", "obj:c3"]


def test_closest_measures_from_a_long_landmark_s_box() -> None:
    """A curtain 3 m long is near all along it: the cushion by its far end is closer to
    it than one that stands 1 m out from its middle, though farther from its centre."""
    from inherit_sg.model import (
        BBox3D,
        Edge,
        EdgeKind,
        FloorNode,
        Layer,
        ObjectNode,
        SceneGraph,
        make_id,
    )
    from inherit_sg.retrieval.snapshot import build_snapshot

    g = SceneGraph()
    floor = FloorNode(make_id(Layer.FLOOR, 0), 0, "ground", 0.0, 2.8)
    g.add_or_update(floor)
    boxes = {
        "curtain": ((0.0, -1.5, 0.2), (0.05, 1.5, 2.2)),  # along the wall x = 0
        "cushion_a": ((0.2, 1.3, 0.4), (0.6, 1.7, 0.6)),  # by the curtain's end
        "cushion_b": ((1.0, -0.2, 0.4), (1.4, 0.2, 0.6)),  # 1 m out from its middle
    }
    for key, (lo, hi) in boxes.items():
        label = key.split("_")[0]
        box = BBox3D(lo, hi)
        node = ObjectNode(make_id(Layer.OBJECT, key), label, tuple(box.center), box,
                          floor_id=floor.id)  # fmt: skip
        g.add_or_update(node)
        g.add_edge(Edge.make(EdgeKind.HAS_OBJECT, floor.id, node.id))
    snap = build_snapshot(g, (1,))
    assert rank(snap, "the cushion closest to the curtain")[0].id == "obj:cushion_a"
    assert rank(snap, "the cushion farthest from the curtain")[0].id == "obj:cushion_b"
