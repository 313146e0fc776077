"""Objects standing in a doorway belong to both rooms it joins: for retrieval ("the doors
in the hall" finds the door mapped in the kitchen) and for room typing (a hall is where
many doors open)."""

from __future__ import annotations

import numpy as np

from inherit_sg.mapping.update import _doorway_members
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
from inherit_sg.model.doorways import Doorway, doorway_rooms, doorways_of
from inherit_sg.retrieval.constraints import RoomConstraint
from inherit_sg.retrieval.snapshot import build_snapshot
from tests.unit.retrieval_rank import rank, request

HALL, KITCHEN, STUDY = (make_id(Layer.ROOM, k) for k in ("hall", "kitchen", "study"))


def _graph() -> SceneGraph:
    """Hall (x < 4), kitchen (4 < x < 8), study (x > 8) on one floor; the hall–kitchen
    doorway at x = 4, y = 1. The door in it is mapped in the kitchen; a second door
    stands inside the study, a chair in the kitchen 1 m from the doorway."""
    g = SceneGraph()
    floor = FloorNode(make_id(Layer.FLOOR, 0), 0, "ground", 0.0, 2.8)
    g.add_or_update(floor)
    for rid, label, x in (
        (HALL, "hallway", 2.0),
        (KITCHEN, "kitchen", 6.0),
        (STUDY, "office", 10.0),
    ):
        g.add_or_update(RoomNode(rid, label, floor_id=floor.id, position=(x, 1.0, 0.0)))
        g.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor.id, rid))
    g.add_edge(Edge.make(EdgeKind.CONNECTS, HALL, KITCHEN, door=[4.0, 1.0, 0.0]))
    g.add_edge(Edge.make(EdgeKind.CONNECTS, KITCHEN, STUDY))  # an opening with no door point
    objects = (
        ("door-a", "door", (4.05, 1.0), (0.05, 0.45), KITCHEN),
        ("door-b", "door", (9.0, 2.0), (0.05, 0.45), STUDY),
        ("chair", "chair", (5.0, 1.0), (0.25, 0.25), KITCHEN),
    )
    for key, label, (x, y), (hx, hy), room in objects:
        g.add_or_update(
            ObjectNode(
                make_id(Layer.OBJECT, key),
                label,
                (x, y, 1.0),
                BBox3D((x - hx, y - hy, 0.0), (x + hx, y + hy, 2.0)),
                room_id=room,
                floor_id=floor.id,
            )
        )
    return g


def test_only_objects_covering_a_doorway_point_join_its_other_room() -> None:
    lo = np.array([[3.9, 0.6], [3.9, 0.6], [5.0, 0.8], [3.9, 0.6]])
    hi = np.array([[4.1, 1.4], [4.1, 1.4], [5.4, 1.2], [4.1, 1.4]])
    door = Doorway(4.0, 1.0, ("hall", "kitchen"), "floor:0")
    found = doorway_rooms(
        lo,
        hi,
        ["floor:0", "floor:0", "floor:0", "floor:1"],
        ["kitchen", "study", "kitchen", "kitchen"],
        [door],
    )
    # row 0 stands in it; row 1 is mapped in a third room; row 2 is 0.6 m away (more
    # than the margin); row 3 is on another storey
    assert found == {0: ("hall",)}


def test_doorways_of_reads_the_door_point_of_connects_edges() -> None:
    g = _graph()
    doorways = doorways_of(g, lambda rid: "floor:0")
    assert doorways == [Doorway(4.0, 1.0, (HALL, KITCHEN), "floor:0")]


def test_snapshot_keys_a_door_in_a_doorway_by_both_rooms() -> None:
    snap = build_snapshot(_graph(), (1,))
    door_a, door_b, chair = (make_id(Layer.OBJECT, k) for k in ("door-a", "door-b", "chair"))
    assert snap.doorway_rooms == {door_a: (HALL,)}
    assert snap.place_key(door_a, "room") == f"{KITCHEN}|{HALL}"
    assert snap.place_key(chair, "room") == KITCHEN
    assert snap.place_key(door_b, "room") == STUDY
    assert snap.room_of[door_a] == KITCHEN  # the object's own room is unchanged


def test_the_door_in_the_hall_is_the_one_mapped_in_the_kitchen_doorway() -> None:
    snap = build_snapshot(_graph(), (1,))
    ranked, _ = rank(snap, request("door", RoomConstraint(type="hallway", name="hallway")))
    top = ranked[0]
    assert top.id == make_id(Layer.OBJECT, "door-a")
    room_term = next(t for t in top.terms.values() if t.kind == "room")
    assert "doorway" in room_term.why


def test_a_door_mapped_in_the_room_asked_for_beats_one_standing_in_its_doorway() -> None:
    g = _graph()
    g.add_or_update(
        ObjectNode(
            make_id(Layer.OBJECT, "door-k"),
            "door",
            (8.02, 1.0, 1.0),
            BBox3D((7.97, 0.6, 0.0), (8.07, 1.4, 2.0)),
            room_id=STUDY,
            floor_id="floor:0",
        )
    )
    # (one CONNECTS edge per pair of rooms: this one replaces the opening with no door)
    g.add_edge(Edge.make(EdgeKind.CONNECTS, KITCHEN, STUDY, door=[8.0, 1.0, 0.0]))
    snap = build_snapshot(g, (1,))
    door_a, door_b, door_k = (make_id(Layer.OBJECT, k) for k in ("door-a", "door-b", "door-k"))
    kitchen = RoomConstraint(type="kitchen", name="kitchen")
    assert [c.id for c in rank(snap, request("door", kitchen))[0][:2]] == [door_a, door_k]
    not_kitchen = RoomConstraint(type="kitchen", name="kitchen", negated=True)
    assert rank(snap, request("door", not_kitchen))[0][0].id == door_b


def test_room_typing_counts_doorway_objects_in_the_room_on_the_other_side() -> None:
    g = _graph()
    rooms = {r.id: r for r in g.nodes(Layer.ROOM) if isinstance(r, RoomNode)}
    by_room: dict[str, list[ObjectNode]] = {}
    for node in g.nodes(Layer.OBJECT):
        assert isinstance(node, ObjectNode) and node.room_id is not None
        by_room.setdefault(node.room_id, []).append(node)
    extra = _doorway_members(g, rooms, by_room)
    assert [o.id for o in extra[HALL]] == [make_id(Layer.OBJECT, "door-a")]
    assert set(extra) == {HALL}
