"""Snapshot indexing and GraphRAG spatial checks on the oracle graph of small_scene."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.model import EdgeKind
from inherit_sg.retrieval.graph_checks import GraphChecker
from inherit_sg.retrieval.snapshot import build_snapshot, canonical_labels, map_version
from tests.unit.retrieval_fixtures import small_graph, small_snapshot


def test_snapshot_indexes_hierarchy_labels_and_floors() -> None:
    snap = small_snapshot()
    assert snap.levels == [0, 1]
    assert snap.room_of["obj:m1"] == "room:kitchen"
    assert snap.area_of["obj:m1"] == "area:a_breakfast"
    assert snap.level_of("obj:tl1") == 1
    assert snap.room_types["room:living"] == "living room"
    assert set(snap.objects_labelled({"mug"})) == {"obj:m1", "obj:m2", "obj:m3"}
    assert canonical_labels("Couch") == ("sofa",)
    # symmetric predicates are indexed both ways, directed ones only forward
    assert "on" in snap.related("obj:m1", "obj:t1")
    assert "on" not in snap.related("obj:t1", "obj:m1")
    assert "near" in snap.related("obj:c1", "obj:t1") and "near" in snap.related("obj:t1", "obj:c1")


def test_snapshot_without_areas_hangs_objects_under_rooms() -> None:
    snap = build_snapshot(small_graph(), (1,), use_areas=False)
    assert snap.areas == {} and not snap.use_areas
    assert snap.area_of["obj:m1"] is None and snap.room_of["obj:m1"] == "room:kitchen"
    assert snap.level_of("obj:tl1") == 1 and snap.node("area:a_breakfast") is None
    assert len(snap.objects) == len(small_snapshot().objects)


def test_map_version_changes_with_files(tmp_path: Path) -> None:
    (tmp_path / "map.json").write_text("{}")
    first = map_version(tmp_path)
    (tmp_path / "graph.kuzu").write_bytes(b"x" * 10)
    assert map_version(tmp_path) != first


@pytest.mark.parametrize(
    ("node", "predicate", "landmark", "expected"),
    [
        ("obj:m1", "on", "obj:t1", True),  # mug on the kitchen table
        ("obj:t1", "supports", "obj:m1", True),  # the table with a mug on it
        ("obj:t1", "on", "obj:m1", False),
        ("obj:pt1", "above", "obj:bd1", True),  # painting above the bed
        ("obj:bd1", "under", "obj:pt1", True),  # bed under the painting
        ("obj:c1", "next_to", "obj:t1", True),
        ("obj:c2", "next_to", "obj:t1", False),
        ("obj:l1", "near", "obj:s1", True),
        ("obj:m1", "inside", "obj:t1", False),
        ("obj:m1", "facing", "obj:t1", True),  # approximated by near
    ],
)
def test_relation_checks_walk_relation_edges(
    node: str, predicate: str, landmark: str, expected: bool
) -> None:
    checker = GraphChecker(small_snapshot())
    ok, why = checker.holds(node, landmark, predicate)
    assert ok is expected
    if ok:
        assert node in why and landmark in why


def test_relation_quality_is_the_best_landmark_and_approximations_count_half() -> None:
    checker = GraphChecker(small_snapshot())
    landmarks = [("obj:ct1", 0.9), ("obj:t1", 0.6)]
    sim, why = checker.relation("obj:m3", "on", landmarks)
    assert sim == pytest.approx(0.9) and "obj:ct1" in why
    sim, why = checker.relation("obj:m1", "on", landmarks)
    assert sim == pytest.approx(0.6)
    sim, why = checker.relation("obj:c1", "facing", [("obj:t1", 1.0)])
    assert sim == pytest.approx(0.5) and "approximated" in why
    assert checker.relation("obj:c2", "on", landmarks) == (0.0, "")


def test_geometry_answers_when_the_map_has_no_edge() -> None:
    graph = small_graph()
    for edge in list(graph.edges(EdgeKind.RELATION)):
        graph.remove_edge(EdgeKind.RELATION, edge.src, edge.dst, str(edge.prop("predicate")))
    checker = GraphChecker(build_snapshot(graph))
    ok, why = checker.holds("obj:m1", "obj:t1", "on")
    assert ok and "geometry" in why
    ok, _ = checker.holds("obj:c1", "obj:t1", "next_to")
    assert ok
    assert checker.holds("obj:c2", "obj:f1", "near")[0] is False


def test_near_crosses_room_boundaries_but_next_to_does_not() -> None:
    # the kitchen door d1 stands on the wall shared with the living room's table t2
    checker = GraphChecker(small_snapshot())
    snap = checker.snap
    assert snap.room_of["obj:d1"] != snap.room_of["obj:t2"]
    assert checker.holds("obj:d1", "obj:t2", "near")[0]
    assert not checker.holds("obj:d1", "obj:t2", "next_to")[0]


def test_between_two_landmarks() -> None:
    checker = GraphChecker(small_snapshot())
    # plant p1 stands between the sofa and the armchair
    sim, why = checker.between("obj:p1", [("obj:s1", 1.0)], [("obj:a1", 0.7)])
    assert sim == pytest.approx(0.7) and "between" in why
    assert checker.between("obj:c2", [("obj:s1", 1.0)], [("obj:a1", 1.0)])[0] == 0.0


def test_room_landmarks_use_the_hierarchy() -> None:
    checker = GraphChecker(small_snapshot())
    assert checker.holds("obj:m1", "room:kitchen", "inside")[0]
    assert not checker.holds("obj:m3", "room:kitchen", "inside")[0]
    assert checker.holds("room:living", "obj:s1", "contains")[0]


@pytest.mark.parametrize("predicate", ["on", "supports", "under", "above", "near", "next_to"])
def test_batched_checks_agree_with_pairwise_ones(predicate: str) -> None:
    checker = GraphChecker(small_snapshot())
    nodes = list(checker.snap.objects)
    landmarks = [("obj:t1", 1.0), ("obj:ct1", 0.8), ("obj:s1", 0.6), ("obj:k1", 0.5)]
    batched = checker.relation_all(nodes, predicate, landmarks)
    for node in nodes:
        best = next((q for lid, q in landmarks if checker.holds(node, lid, predicate)[0]), None)
        assert (batched[node][0] if node in batched else None) == best, node
    pairs = checker.between_all(nodes, [("obj:s1", 1.0)], [("obj:a1", 0.5), ("obj:l1", 0.9)])
    assert set(pairs) == {
        n
        for n in nodes
        if checker.between(n, [("obj:s1", 1.0)], [("obj:a1", 0.5), ("obj:l1", 0.9)])[0]
    }


def test_proximity_credit_ranks_the_nearer_object_when_no_relation_holds() -> None:
    from inherit_sg.retrieval.graph_checks import PROXIMITY_MAX

    snap = small_snapshot()
    checker = GraphChecker(snap)
    mugs = ["obj:m1", "obj:m2", "obj:m3"]
    credit = checker.proximity_all(mugs, [("obj:t1", 1.0)])
    assert set(credit) <= set(mugs) and credit
    assert all(0.0 < sim <= PROXIMITY_MAX for sim, _ in credit.values())
    # the mug on the kitchen table touches it: full proximity credit, the others less
    assert credit["obj:m1"][0] == pytest.approx(PROXIMITY_MAX)
    assert all(credit[m][0] <= credit["obj:m1"][0] for m in credit)
    assert "from obj:t1" in credit["obj:m1"][1]
    # a landmark of lower quality gives proportionally less; no object landmark, nothing
    half = checker.proximity_all(["obj:m1"], [("obj:t1", 0.5)])
    assert half["obj:m1"][0] == pytest.approx(PROXIMITY_MAX * 0.5)
    assert checker.proximity_all(mugs, [("room:kitchen", 1.0)]) == {}
    assert "obj:t1" not in checker.proximity_all(["obj:t1"], [("obj:t1", 1.0)])
