"""People tell rooms of one type apart by what they lie next to: "the bathroom off the
entry hall", "the bathroom by the front door", "the bedroom next to the kitchen"."""

from __future__ import annotations

from inherit_sg.model import (
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    RoomNode,
    SceneGraph,
    make_id,
)
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.constraints import RoomConstraint
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from tests.unit.retrieval_rank import rank

# room key → (label, x of its centre, rooms it opens onto)
ROOMS = {
    "hall": ("entryway", 0.0, ("bath_a", "bed")),
    "bath_a": ("bathroom", 3.0, ()),
    "bed": ("bedroom", -4.0, ("bath_b",)),
    "bath_b": ("bathroom", -8.0, ()),
}
# (key, label, x, room key)
OBJECTS = [
    ("front", "exterior door", 0.0, "hall"),
    ("towel_a", "towel", 3.5, "bath_a"),
    ("towel_b", "towel", -8.5, "bath_b"),
]


def _snap() -> MapSnapshot:
    g = SceneGraph()
    floor = FloorNode(make_id(Layer.FLOOR, 0), 0, "ground", 0.0, 2.8)
    g.add_or_update(floor)
    for key, (label, x, _) in ROOMS.items():
        room = RoomNode(make_id(Layer.ROOM, key), label, floor_id=floor.id, position=(x, 0, 0))
        g.add_or_update(room)
        g.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor.id, room.id))
    for key, (_, _, doors) in ROOMS.items():
        for other in doors:
            g.add_edge(
                Edge.make(EdgeKind.CONNECTS, make_id(Layer.ROOM, key), make_id(Layer.ROOM, other))
            )
    for key, label, x, room_key in OBJECTS:
        g.add_or_update(
            ObjectNode(
                make_id(Layer.OBJECT, key),
                label,
                (x, 0.0, 0.5),
                BBox3D((x - 0.25, -0.25, 0.0), (x + 0.25, 0.25, 1.0)),
                room_id=make_id(Layer.ROOM, room_key),
                floor_id=floor.id,
            )
        )
    return build_snapshot(g, (1,))


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
