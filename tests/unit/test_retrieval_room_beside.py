"""People tell rooms of one type apart by what they lie next to: "the bathroom off the
entry hall", "the bathroom by the front door", "the bedroom next to the kitchen"."""

from __future__ import annotations

from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.constraints import RoomConstraint
from inherit_sg.retrieval.snapshot import MapSnapshot
from tests.unit.retrieval_fixtures import floor_snapshot
from tests.unit.retrieval_rank import rank

# room key → (label, x of its centre)
ROOMS = {
    "hall": ("entryway", 0.0),
    "bath_a": ("bathroom", 3.0),
    "bed": ("bedroom", -4.0),
    "bath_b": ("bathroom", -8.0),
}
# the rooms that open onto each other
DOORS = [("hall", "bath_a"), ("hall", "bed"), ("bed", "bath_b")]
# (key, label, x, y, room key)
OBJECTS = [
    ("front", "exterior door", 0.0, 0.0, "hall"),
    ("towel_a", "towel", 3.5, 0.0, "bath_a"),
    ("towel_b", "towel", -8.5, 0.0, "bath_b"),
]


def _snap() -> MapSnapshot:
    return floor_snapshot(OBJECTS, ROOMS, DOORS)


def test_the_parser_keeps_what_a_room_lies_next_to() -> None:
    parsed = parse_rules(
        "Is there something to dry my hands on in the bathroom off the entry hall?"
    )
    rooms = [c for c in parsed.constraints if isinstance(c, RoomConstraint)]
    assert [(r.type, r.beside) for r in rooms] == [("bathroom", "entryway")]
    parsed = parse_rules("Bring me a towel from the bathroom by the front door.")
    rooms = [c for c in parsed.constraints if isinstance(c, RoomConstraint)]
    assert [(r.type, r.beside) for r in rooms] == [("bathroom", "front door")]
    assert not parsed.of_kind("relation")


def test_a_room_next_to_another_room() -> None:
    ranked, _ = rank(_snap(), parse_rules("a towel from the bathroom off the entry hall"))
    assert ranked[0].id == "obj:towel_a"
    ranked, _ = rank(_snap(), parse_rules("the towel in the bathroom next to the bedroom"))
    assert ranked[0].id == "obj:towel_b"


def test_a_room_next_to_a_thing() -> None:
    ranked, _ = rank(_snap(), parse_rules("Bring me a towel from the bathroom by the front door."))
    assert ranked[0].id == "obj:towel_a"
    other = next(c for c in ranked if c.id == "obj:towel_b")
    why = " ".join(t.why for t in other.terms.values())
    assert "by the front door is meant" in why


def test_the_hall_is_the_entryway_when_the_map_has_no_hallway() -> None:
    # the map took the hall bathroom for a toilet and has no room it calls a hallway
    rooms = {**ROOMS, "bath_a": ("toilet", 3.0)}
    snap = floor_snapshot(OBJECTS, rooms, DOORS)
    ranked, _ = rank(snap, parse_rules("bring me the towels from the bathroom off the hall"))
    assert ranked[0].id == "obj:towel_a"
    # no qualifier: the room the map calls a bathroom comes first
    ranked, _ = rank(snap, parse_rules("the towel in the bathroom"))
    assert ranked[0].id == "obj:towel_b"


def test_just_off_the_hall_is_off_the_hall() -> None:
    parsed = parse_rules("the mirror in the bathroom just off the front hall")
    rooms = [c for c in parsed.constraints if isinstance(c, RoomConstraint)]
    assert [(r.type, r.beside) for r in rooms] == [("bathroom", "entryway")]


def test_the_room_entered_from_another_is_the_one_beside_it() -> None:
    parsed = parse_rules(
        "As you walk into the little bathroom from the front hall, the towel on your left."
    )
    assert parsed.viewpoint is not None
    (room,) = [c for c in parsed.viewpoint.landmark.constraints if isinstance(c, RoomConstraint)]
    assert (room.type, room.name, room.beside) == ("bathroom", "small bathroom", "entryway")
    ranked, _ = rank(_snap(), parsed)
    assert ranked[0].id == "obj:towel_a"
