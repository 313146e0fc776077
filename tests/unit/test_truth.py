"""Ground-truth predicates and the constraint evaluator on a hand-built two-floor scene."""

from __future__ import annotations

from dataclasses import replace

import pytest

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.ingest.synthetic.truth import (
    AreaConstraint,
    AttributeConstraint,
    FloorConstraint,
    ObjectSpec,
    RelationConstraint,
    RoomConstraint,
    SceneIndex,
    evaluate,
)
from inherit_sg.ingest.synthetic.truth_predicates import (
    above,
    between,
    floor_levels,
    has_attribute,
    near,
    next_to,
    on,
    serves,
    superlative_score,
    supports,
    under,
)
from tests.fixtures_scenes import small_scene


@pytest.fixture(scope="module")
def scene() -> Scene:
    return small_scene()


def spec(*labels: str, **kw: object) -> ObjectSpec:
    return ObjectSpec(labels=list(labels), **kw)  # type: ignore[arg-type]


def rel(predicate: str, landmark: ObjectSpec, negated: bool = False) -> RelationConstraint:
    return RelationConstraint(predicate, landmark, negated=negated)


def test_on_uses_recorded_support_then_geometry(scene: Scene) -> None:
    o = scene.object
    assert on(o("m1"), o("t1")) and supports(o("t1"), o("m1"))
    assert not on(o("m1"), o("k1")) and not on(o("t1"), o("m1"))
    # The coffee table records no support: it rests on the rug's top (2 cm) geometrically.
    assert on(o("ct1"), o("r1"))
    assert not on(o("s1"), o("r1"))  # the sofa stands beside the rug
    assert not on(o("m1"), o("m1"))


def test_under_and_above_are_inverse(scene: Scene) -> None:
    o = scene.object
    assert under(o("r1"), o("ct1")) and above(o("ct1"), o("r1"))
    assert not under(o("ct1"), o("r1"))
    assert above(o("pt1"), o("bd1")) and under(o("bd1"), o("pt1"))  # painting over the bed
    assert above(o("mr1"), o("sk1"))  # mirror over the sink
    assert above(o("m1"), o("t1"))  # what stands on a table is also above it
    moved = replace(o("pt1"), floor=0)
    assert not above(moved, o("bd1"))  # different floors are never stacked


def test_next_to_needs_same_room_small_gap_and_no_stacking(scene: Scene) -> None:
    o = scene.object
    assert next_to(o("c1"), o("t1")) and next_to(o("t1"), o("c1"))
    assert not next_to(o("c2"), o("t1"))  # 1.2 m away
    assert not next_to(o("m1"), o("t1"))  # on it, not beside it
    assert next_to(o("k1"), o("w1"))  # the window sill is level with the counter top
    assert next_to(o("n1"), o("bd1"))
    elsewhere = replace(o("c1"), room_id="living")
    assert not next_to(elsewhere, o("t1"))
    assert near(elsewhere, o("t1"))


def test_near_is_same_floor_within_one_and_a_half_metres(scene: Scene) -> None:
    o = scene.object
    assert near(o("l1"), o("s1"))
    assert near(o("c2"), o("t1"))  # 1.17 m gap
    assert not near(o("l2"), o("s1"))  # 2.25 m gap
    assert not near(replace(o("l1"), floor=1), o("s1"))


def test_between_band_and_order(scene: Scene) -> None:
    o = scene.object
    assert between(o("p1"), o("s1"), o("a1"))
    assert between(o("p1"), o("a1"), o("s1"))
    assert not between(o("s1"), o("p1"), o("a1"))
    assert between(o("v1"), o("m3"), o("b1"))
    assert not between(o("m3"), o("v1"), o("b1"))
    assert not between(o("l2"), o("s1"), o("a1"))  # far off the segment


def test_floor_words(scene: Scene) -> None:
    assert floor_levels(scene, None, "upstairs") == {1}
    assert floor_levels(scene, None, "downstairs") == {0}
    assert floor_levels(scene, None, "ground") == {0}
    assert floor_levels(scene, None, "top") == {1}
    assert floor_levels(scene, 1, None) == {1}
    with pytest.raises(ValueError, match="basement"):
        floor_levels(scene, None, "basement")


def test_attributes_functions_and_measures(scene: Scene) -> None:
    o = scene.object
    assert has_attribute(o("m1"), "colour", "RED")
    assert not has_attribute(o("m1"), "colour", "blue")
    assert not has_attribute(o("w1"), "size", "large")  # no size recorded
    assert serves(o("c1"), "sit") and serves(o("s1"), "sit") and not serves(o("t1"), "sit")
    assert serves(o("sk1"), "wash hands")
    assert superlative_score(o("s1"), "largest") > superlative_score(o("a1"), "largest")
    assert superlative_score(o("l1"), "tallest") > superlative_score(o("s1"), "tallest")
    assert superlative_score(o("m3"), "smallest") > superlative_score(o("b1"), "smallest")


def test_evaluate_simple_relations(scene: Scene) -> None:
    table = spec("table", "dining table", noun="table")
    assert evaluate(scene, spec("mug", relations=[rel("on", table)])) == ["m1"]
    assert evaluate(scene, spec("rug", relations=[rel("under", spec("coffee table"))])) == ["r1"]
    assert evaluate(scene, spec("chair", relations=[rel("next_to", table)])) == ["c1"]
    assert evaluate(scene, spec("lamp", relations=[rel("near", spec("sofa"))])) == ["l1"]
    assert evaluate(scene, spec("table", relations=[rel("supports", spec("mug"))])) == ["t1"]
    between_rel = RelationConstraint("between", spec("mug"), spec("book"))
    assert evaluate(scene, spec("vase", relations=[between_rel])) == ["v1"]


def test_evaluate_structural_objects_as_landmark_and_target(scene: Scene) -> None:
    assert evaluate(scene, spec("counter", relations=[rel("next_to", spec("window"))])) == ["k1"]
    assert evaluate(scene, spec("window", relations=[rel("next_to", spec("counter"))])) == ["w1"]


def test_evaluate_chained_constraints(scene: Scene) -> None:
    counter_by_window = spec("counter", relations=[rel("next_to", spec("window"))])
    mug = spec(
        "mug",
        relations=[rel("on", counter_by_window)],
        room=RoomConstraint(type="kitchen"),
        floor=FloorConstraint(relative="downstairs"),
    )
    assert evaluate(scene, mug) == ["m2"]
    table_by_window = spec("table", relations=[rel("next_to", spec("window"))])
    assert evaluate(scene, spec("mug", relations=[rel("on", table_by_window)])) == []
    upstairs = replace(mug, floor=FloorConstraint(relative="upstairs"))
    assert evaluate(scene, upstairs) == []


def test_evaluate_negations(scene: Scene) -> None:
    no_table = rel("next_to", spec("table"), negated=True)
    assert evaluate(scene, spec("lamp", relations=[no_table])) == ["l1", "l3"]
    in_living = RoomConstraint(type="living room")
    assert evaluate(scene, spec("lamp", relations=[no_table], room=in_living)) == ["l1"]
    not_kitchen = RoomConstraint(type="kitchen", negated=True)
    assert evaluate(scene, spec("chair", room=not_kitchen)) == ["c3"]
    not_upstairs = FloorConstraint(relative="upstairs", negated=True)
    assert evaluate(scene, spec("chair", floor=not_upstairs)) == ["c1", "c2"]
    not_red = AttributeConstraint("colour", "red", negated=True)
    assert evaluate(scene, spec("mug", attributes=[not_red])) == ["m2", "m3"]
    no_mug = rel("supports", spec("mug"), negated=True)
    assert evaluate(scene, spec("table", relations=[no_mug])) == ["t2"]
    outside_area = AreaConstraint("breakfast area", negated=True)
    assert evaluate(scene, spec("mug", area=outside_area)) == ["m2", "m3"]


def test_evaluate_function_targets(scene: Scene) -> None:
    living = RoomConstraint(type="living room")
    assert evaluate(scene, ObjectSpec(function="sit", room=living)) == ["s1", "a1"]
    near_lamp = rel("near", spec("lamp"))
    seats = evaluate(scene, ObjectSpec(function="sit", relations=[near_lamp], room=living))
    assert seats == ["s1"]
    upstairs = FloorConstraint(relative="upstairs")
    assert evaluate(scene, ObjectSpec(function="wash hands", floor=upstairs)) == ["sk1"]


def test_evaluate_superlatives_apply_last(scene: Scene) -> None:
    living = RoomConstraint(type="living room")
    assert evaluate(scene, ObjectSpec(room=living, superlative="largest")) == ["s1"]
    assert evaluate(scene, ObjectSpec(room=living, superlative="smallest")) == ["m3"]
    assert evaluate(scene, ObjectSpec(room=living, superlative="tallest")) == ["l1", "l2"]
    kitchen = RoomConstraint(type="kitchen")
    assert evaluate(scene, spec("chair", room=kitchen, superlative="tallest")) == ["c1", "c2"]
    assert evaluate(scene, spec("chair", room=kitchen, superlative="largest")) == ["c1", "c2"]


def test_evaluate_rooms_by_name_and_exclusions(scene: Scene) -> None:
    by_name = spec("chair", room=RoomConstraint(name="Bedroom"))
    assert evaluate(scene, by_name) == ["c3"]
    assert evaluate(scene, spec("chair", exclude_ids=["c1", "c3"])) == ["c2"]


def test_index_reuse_gives_the_same_answers(scene: Scene) -> None:
    index = SceneIndex(scene)
    query = spec("lamp", relations=[rel("next_to", spec("table"), negated=True)])
    assert evaluate(scene, query, index) == evaluate(scene, query) == ["l1", "l3"]
    assert evaluate(scene, query, index) == ["l1", "l3"]  # cached


def test_spec_json_round_trip_and_positive_part() -> None:
    query = spec(
        "lamp",
        noun="lamp",
        attributes=[AttributeConstraint("colour", "black")],
        room=RoomConstraint(type="kitchen", negated=True),
        floor=FloorConstraint(level=0),
        relations=[
            rel("next_to", spec("table"), negated=True),
            RelationConstraint("between", spec("sofa"), spec("armchair")),
        ],
        superlative="tallest",
        exclude_ids=["x"],
    )
    data = query.to_dict()
    back = ObjectSpec.from_dict(data)
    assert back.to_dict() == data and back.key() == query.key()
    assert data["floor"] == {"level": 0}
    assert query.negation_count() == 2
    positive = query.positive()
    assert positive.negation_count() == 0 and positive.room is None
    assert [r.predicate for r in positive.relations] == ["between"]


@pytest.mark.parametrize(
    "bad",
    [
        {"labels": ["a"], "relations": [{"predicate": "inside", "landmark": {}}]},
        {"labels": ["a"], "relations": [{"predicate": "between", "landmark": {}}]},
        {"labels": ["a"], "floor": {"relative": "attic"}},
        {"labels": ["a"], "floor": {}},
        {"labels": ["a"], "superlative": "heaviest"},
        {"labels": ["a"], "room": {"colour": "red"}},
    ],
)
def test_malformed_specs_raise_dataset_errors(bad: dict[str, object]) -> None:
    with pytest.raises(DatasetError, match="gt_constraints"):
        ObjectSpec.from_dict(bad)
