"""Compiling parsed requests into plans: floors, label matches, landmarks, steps."""

from __future__ import annotations

import pytest

from inherit_sg.retrieval import FloorConstraint, parse_rules
from inherit_sg.retrieval.match import is_kind_of
from inherit_sg.retrieval.plan import (
    CYPHER_OBJECTS_BY_LABEL,
    CYPHER_OBJECTS_IN_ROOMS,
    LANDMARK_ROOM_WEIGHT,
    SHARED_ROOM_WEIGHT,
    Compiler,
    QueryPlan,
    resolve_levels,
)
from tests.unit.retrieval_fixtures import hash_similarity, small_snapshot


def compile_text(text: str) -> QueryPlan:
    return Compiler(small_snapshot(), hash_similarity()).compile(parse_rules(text))


@pytest.mark.parametrize(
    ("kwargs", "levels", "expected"),
    [
        ({"level": 1}, [0, 1, 2], {1}),
        ({"level": 5}, [0, 1], set()),
        ({"relative": "upstairs"}, [0, 1, 2], {1, 2}),
        ({"relative": "downstairs"}, [0, 1, 2], {0}),
        ({"relative": "top"}, [0, 1, 2], {2}),
        ({"relative": "bottom"}, [0, 1], {0}),
        ({"level": 0, "negated": True}, [0, 1, 2], {1, 2}),
    ],
)
def test_floor_words_resolve_to_levels(kwargs: dict, levels: list[int], expected: set[int]) -> None:
    assert resolve_levels(FloorConstraint(**kwargs), levels) == expected


def test_kind_of_by_head_noun() -> None:
    assert is_kind_of("dining table", "table")
    assert is_kind_of("bookshelf", "shelf")
    assert is_kind_of("armchair", "chair")
    assert not is_kind_of("table lamp", "table")
    assert not is_kind_of("chair", "chair")
    assert not is_kind_of("tv", "v")


def test_plan_resolves_labels_and_landmarks() -> None:
    plan = compile_text("the mug on the table next to the window")
    target = plan.target
    assert target.layer == "object"
    label = next(c for c in target.constraints if c.kind == "label")
    assert target.matches[label.id]["mug"][0] == 1.0
    # the chain: mug -on-> table -next_to-> window, each landmark with its own spec
    rel = next(c for c in target.constraints if c.kind == "relation")
    table = target.landmarks[rel.id]
    assert table.key == f"{rel.id}.landmark"
    assert any(c.kind == "label" for c in table.constraints)  # implied by its noun
    window = next(iter(table.landmarks.values()))
    assert window.key == f"{rel.id}.1.landmark"  # nested ids: c2.1 is the table's relation
    steps = plan.steps
    # landmarks are planned (and executed) before what depends on them
    assert steps.index(window.steps[0]) < steps.index(table.steps[0]) < steps.index(target.steps[0])
    first = target.steps[0]
    assert first.op == "cypher" and first.cypher == CYPHER_OBJECTS_BY_LABEL
    assert "mug" in first.params["labels"]
    text = plan.explain()
    assert all(s.op != "floor" for s in steps)  # no floor constraint, no filter step
    assert "relation on" in text and "cypher:" in text


def test_plan_floor_filter_and_room_scope() -> None:
    plan = compile_text("something to sit on in the kitchen on the ground floor")
    target = plan.target
    assert target.levels == frozenset({0})
    ops = [s.op for s in target.steps]
    assert "floor" in ops and ops[-1] == "score"
    room = next(c for c in target.constraints if c.kind == "room")
    assert set(target.matches[room.id]) == {"room:kitchen"}
    plan = compile_text("take me to anything in the bedroom")
    scope = plan.target.steps[0]
    assert scope.cypher == CYPHER_OBJECTS_IN_ROOMS and scope.params == {"rooms": ["room:bedroom"]}


def test_room_targets_match_room_nodes() -> None:
    plan = compile_text("take me to the kitchen")
    assert plan.target.layer == "room"
    label = next(c for c in plan.target.constraints if c.kind == "label")
    assert set(plan.target.matches[label.id]) == {"room:kitchen"}
    assert plan.target.steps[0].cypher == "MATCH (n:Room) RETURN n.id"


def test_a_landmark_shares_the_room_the_request_names() -> None:
    plan = compile_text("the cushion next to the sofa in the living room")
    (key,) = [k for k in plan.target.landmarks if k != "viewpoint"]
    rooms = [c for c in plan.target.landmarks[key].constraints if c.kind == "room"]
    assert len(rooms) == 1 and rooms[0].type == "living room"
    assert rooms[0].weight == pytest.approx(SHARED_ROOM_WEIGHT) and rooms[0].id.endswith("~room")
    assert "too" in rooms[0].text


@pytest.mark.parametrize(
    "text",
    [
        "the cushion next to the sofa",  # no room said
        "the cushion not next to the sofa in the living room",  # the relation ruled out
        "the cushion next to the sofa, not in the living room",  # the room ruled out
    ],
)
def test_no_shared_room_without_a_room_said_of_what_is_sought(text: str) -> None:
    plan = compile_text(text)
    for key, spec in plan.target.landmarks.items():
        assert not [c for c in spec.constraints if c.kind == "room"], (key, spec.constraints)


def test_what_is_under_or_on_a_landmark_is_in_its_room() -> None:
    plan = compile_text("the cupboards under the kitchen counter")
    rooms = [c for c in plan.target.constraints if c.kind == "room"]
    assert len(rooms) == 1 and rooms[0].type == "kitchen" and rooms[0].id.endswith("~room")
    assert rooms[0].weight == pytest.approx(LANDMARK_ROOM_WEIGHT)
    # a room said of what is sought wins; nearness says nothing of the room
    for text in ("the mug in the bedroom on the kitchen table", "the chair near the kitchen sink"):
        plan = compile_text(text)
        assert not [c for c in plan.target.constraints if c.id.endswith("~room")], text


def test_a_seated_viewpoint_and_what_it_looks_at_are_both_landmarks() -> None:
    plan = compile_text("sitting on the sofa facing the tv, the lamp on my left")
    assert plan.parsed.viewpoint is not None and plan.parsed.viewpoint.kind == "seated"
    assert {"viewpoint", "viewpoint/toward"} <= set(plan.target.landmarks)
    viewer = [s for s in plan.target.steps if s.op == "viewer"]
    assert viewer and "look at the best tv" in viewer[0].text


def test_a_superlative_landmark_takes_no_shared_room() -> None:
    # "the kitchen mug closest to the door": the door may be in any room
    plan = compile_text("the mug in the kitchen closest to the door")
    for spec in plan.target.landmarks.values():
        assert not [c for c in spec.constraints if c.kind == "room"]


def test_a_landmark_the_map_lacks_gives_the_room_its_name_says() -> None:
    from inherit_sg.retrieval.plan import COMPOUND_ROOM_WEIGHT, absent_landmark_rooms
    from tests.unit.retrieval_fixtures import floor_snapshot

    snap = floor_snapshot([("l1", "light", 0.0, 0.0, None), ("c1", "chair", 1.0, 0.0, None)])
    parsed = parse_rules("the light over the dining table")
    (room,) = absent_landmark_rooms(parsed.constraints, snap)
    assert room.kind == "room" and room.type == "dining room"  # type: ignore[attr-defined]
    assert room.weight == pytest.approx(COMPOUND_ROOM_WEIGHT) and room.id.endswith("~room")
    # a map that has a dining table measures from it; a room said wins; a word of
    # position names no room ("front door", though "front room" is a room)
    table = floor_snapshot([("t1", "dining table", 0.0, 0.0, None)])
    assert absent_landmark_rooms(parsed.constraints, table) == ()
    said = parse_rules("the light over the dining table in the kitchen")
    assert not [c for c in absent_landmark_rooms(said.constraints, snap)]
    assert absent_landmark_rooms(parse_rules("the light by the front door").constraints, snap) == ()
