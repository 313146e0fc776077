"""Conversation history: follow-ups resolved against earlier turns (pure logic)."""

from __future__ import annotations

from inherit_sg.retrieval import FloorConstraint, RoomConstraint, parse_rules
from inherit_sg.retrieval.conversation import Conversation, merge_constraints
from inherit_sg.retrieval.query import ParsedQuery


def _ask(conv: Conversation, text: str, answer: str | None = None) -> ParsedQuery:
    resolved = conv.resolve(parse_rules(text))
    if answer is not None:
        conv.add_turn(resolved, answer, (answer, "obj:99"))
    return resolved


def test_request_without_reference_is_unchanged() -> None:
    conv = Conversation()
    _ask(conv, "the red chair", "obj:1")
    fresh = parse_rules("the lamp in the office")
    assert conv.resolve(fresh) == fresh


def test_follow_up_without_history_is_left_unresolved_with_a_note() -> None:
    conv = Conversation()
    parsed = conv.resolve(parse_rules("the other one"))
    assert parsed.reference == "other"
    assert parsed.target.is_empty
    assert any("no earlier turn" in n for n in parsed.notes)


def test_dialogue_chain() -> None:
    conv = Conversation()
    first = _ask(conv, "the blue mug in the bedroom on the second floor", "obj:1")
    assert first.exclude_ids == ()

    other = _ask(conv, "the other one", "obj:2")
    assert other.target.labels == ("mug",)
    assert other.exclude_ids == ("obj:1",)
    assert [c.kind for c in other.constraints] == ["label", "attribute", "room", "floor"]

    moved = _ask(conv, "not that one, the one in the kitchen", "obj:3")
    assert moved.exclude_ids == ("obj:1", "obj:2")
    rooms = moved.of_kind("room")
    assert len(rooms) == 1 and isinstance(rooms[0], RoomConstraint) and rooms[0].type == "kitchen"

    red = _ask(conv, "the red one", "obj:4")
    assert [(c.key, c.value) for c in red.of_kind("attribute")] == [("colour", "red")]  # type: ignore[union-attr]
    assert red.target.attributes == ("red",)

    up = _ask(conv, "what about upstairs?", "obj:5")
    floors = up.of_kind("floor")
    assert len(floors) == 1 and isinstance(floors[0], FloorConstraint)
    assert floors[0].relative == "upstairs"
    assert [c.id for c in up.constraints] == [f"c{i}" for i in range(1, len(up.constraints) + 1)]

    it = _ask(conv, "take me to it")
    assert it.target.node_ids == ("obj:5",) and not it.target.anaphor
    assert it.target.labels == ("mug",)


def test_anaphor_landmark_is_pinned_to_the_previous_answer() -> None:
    conv = Conversation()
    _ask(conv, "the sofa in the living room", "obj:7")
    near = _ask(conv, "what is next to it?")
    (rel,) = near.of_kind("relation")
    assert rel.landmark.target.node_ids == ("obj:7",)  # type: ignore[union-attr]
    assert rel.landmark.target.labels == ("sofa",)  # type: ignore[union-attr]
    assert near.reference == "none" and near.exclude_ids == ()


def test_new_label_replaces_the_old_one() -> None:
    conv = Conversation()
    _ask(conv, "a red chair in the office", "obj:1")
    stool = _ask(conv, "what about a stool")
    assert stool.target.labels == ("stool",)
    assert [c.kind for c in stool.constraints] == ["label", "attribute", "room"]
    another = _ask(conv, "another chair")
    assert another.target.labels == ("chair",)
    assert another.exclude_ids == ("obj:1",)


def test_merge_keeps_relations_and_replaces_slots() -> None:
    old = parse_rules("the red mug on the table in the kitchen").constraints
    new = parse_rules("a blue one next to the sink in the bedroom").constraints
    merged = merge_constraints(old, new)
    kinds = [(c.kind, getattr(c, "value", None) or getattr(c, "type", None)) for c in merged]
    assert ("attribute", "blue") in kinds and ("attribute", "red") not in kinds
    assert [c.kind for c in merged].count("relation") == 2
    assert [c.type for c in merged if isinstance(c, RoomConstraint)] == ["bedroom"]


def test_history_is_bounded_and_clearable() -> None:
    conv = Conversation(max_turns=3)
    for i in range(5):
        _ask(conv, f"the chair number {i}", f"obj:{i}")
    assert len(conv.turns) == 3
    assert conv.last is not None and conv.last.answer_id == "obj:4"
    assert conv.last.candidate_ids == ("obj:4", "obj:99")
    conv.clear()
    assert conv.last is None
