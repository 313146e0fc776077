"""Over-segmented rooms: two touching geometric rooms that say the same type through a
wide passage (no known door) become one room with a stable id; rooms apart by a door,
a narrow passage, different types or an implausible total size stay apart.

Object labels come from the room vocabulary's evidence, so the tests follow
``rooms.toml`` rather than a word list of their own.
"""

from __future__ import annotations

import numpy as np

from inherit_sg.mapping.room_merge import (
    merge_over_segmented_rooms,
    merged_type,
    plan_merges,
    union_mask,
)
from inherit_sg.model import (
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    RoomMask,
    RoomNode,
    SceneGraph,
)
from inherit_sg.vocab import rooms as room_vocab

RES = 0.1


def strongest(room_type: str, n: int) -> list[str]:
    """The ``n`` kinds that say ``room_type`` most strongly (and no other type as much)."""
    table = room_vocab.room_type_table()
    own = table[room_type].evidence
    kinds = sorted(own, key=lambda k: (-own[k], k))
    chosen = [
        k
        for k in kinds
        if all(t.evidence.get(k, 0.0) < own[k] for name, t in table.items() if name != room_type)
    ]
    assert len(chosen) >= n
    return chosen[:n]


def rect(x0: float, y0: float, w: float, d: float) -> RoomMask:
    return RoomMask(x0, y0, RES, np.ones((round(d / RES), round(w / RES)), dtype=bool))


def obj(i: int, label: str, x: float, y: float, room: str) -> ObjectNode:
    box = BBox3D((x - 0.2, y - 0.2, 0.0), (x + 0.2, y + 0.2, 0.8))
    node = ObjectNode(f"obj:{i}", label, (x, y, 0.4), box)
    node.room_id = room
    return node


def two_rooms(
    a_type: str | None,
    b_type: str | None,
    width: float = 1.3,
    source: str = "passage",
    depth: float = 1.4,
) -> tuple[SceneGraph, dict[str, list[ObjectNode]]]:
    """Two 1.4 m wide rooms side by side (x 0..d and d..2d), joined by a CONNECTS edge of
    ``width`` and ``source``; each holds two of its type's strongest kinds (none for
    None), and a third room far away holds one more object."""
    g = SceneGraph()
    g.add_or_update(FloorNode("floor:0", 0, "floor 0", 0.0, 3.0))
    rooms = {
        "room:3": rect(0.0, 0.0, depth, 1.4),
        "room:8": rect(depth, 0.0, depth, 1.4),
        "room:9": rect(10.0, 0.0, 3.0, 3.0),
    }
    for rid, mask in rooms.items():
        g.add_or_update(RoomNode(rid, "room", "floor:0", (0.0, 0.0, 0.0), mask=mask))
        g.add_edge(Edge.make(EdgeKind.HAS_ROOM, "floor:0", rid))
    g.add_edge(
        Edge.make(
            EdgeKind.CONNECTS,
            "room:3",
            "room:8",
            door=[depth, 0.7, 0.0],
            width=width,
            source=source,
        )
    )
    g.add_edge(
        Edge.make(
            EdgeKind.CONNECTS,
            "room:8",
            "room:9",
            door=[9.0, 0.7, 0.0],
            width=0.8,
            source="semantic",
        )
    )
    by_room: dict[str, list[ObjectNode]] = {"room:3": [], "room:8": [], "room:9": []}
    n = 0
    for rid, rtype, x0 in (("room:3", a_type, 0.3), ("room:8", b_type, depth + 0.3)):
        if rtype is None:
            continue
        for k, label in enumerate(strongest(rtype, 2)):
            n += 1
            by_room[rid].append(obj(n, label, x0 + 0.5 * k, 0.7, rid))
    by_room["room:9"].append(obj(99, strongest("bedroom", 1)[0], 11.0, 1.0, "room:9"))
    for members in by_room.values():
        for o in members:
            g.add_or_update(o)
    return g, by_room


def test_union_mask_covers_both_masks() -> None:
    a = rect(0.0, 0.0, 1.0, 0.5)
    b = rect(0.5, 0.3, 1.0, 1.0)
    u = union_mask([a, b])
    assert (u.origin_x, u.origin_y) == (0.0, 0.0)
    assert u.cells.shape == (13, 15)
    assert np.isclose(u.area_m2, (50 + 100 - 10) * RES**2)  # 10 cells overlap
    for x, y in ((0.05, 0.05), (1.45, 1.25), (0.95, 0.45)):
        assert u.contains_xy(x, y)
    assert not u.contains_xy(1.45, 0.05)


def test_same_type_through_a_wide_passage_is_one_room() -> None:
    g, by_room = two_rooms("bathroom", "bathroom")
    out = merge_over_segmented_rooms(g, by_room)
    assert "room:8" not in g and "room:3" in g
    room = g.get("room:3")
    assert isinstance(room, RoomNode) and room.mask is not None
    assert np.isclose(room.mask.area_m2, 2 * 1.4 * 1.4)
    assert np.isclose(room.position[0], 1.4)
    assert sorted(o.id for o in out["room:3"]) == ["obj:1", "obj:2", "obj:3", "obj:4"]
    assert all(o.room_id == "room:3" for o in out["room:3"])
    assert "room:8" not in out
    # the absorbed room's door to room:9 now leaves the kept room
    assert [(e.src, e.dst) for e in g.edges(EdgeKind.CONNECTS)] == [("room:3", "room:9")]


def test_a_room_without_evidence_joins_its_neighbour() -> None:
    g, by_room = two_rooms(None, "bathroom")
    merge_over_segmented_rooms(g, by_room)
    assert "room:8" not in g and "room:3" in g


def test_repeated_update_keeps_the_first_id() -> None:
    g, by_room = two_rooms("bathroom", "bathroom")
    merge_over_segmented_rooms(g, by_room)
    # the geometry publishes room:8 again with its own mask before the next update
    g.add_or_update(
        RoomNode("room:8", "room", "floor:0", (0.0, 0.0, 0.0), mask=rect(1.4, 0, 1.4, 1.4))
    )
    g.get("room:3").mask = rect(0.0, 0.0, 1.4, 1.4)  # type: ignore[union-attr]
    g.add_edge(
        Edge.make(
            EdgeKind.CONNECTS, "room:3", "room:8", door=[1.4, 0.7, 0.0], width=1.3, source="passage"
        )
    )
    merge_over_segmented_rooms(g, by_room)
    assert sorted(r.id for r in g.nodes(Layer.ROOM)) == ["room:3", "room:9"]


def test_a_known_door_keeps_rooms_apart() -> None:
    g, by_room = two_rooms("bathroom", "bathroom", source="semantic")
    merge_over_segmented_rooms(g, by_room)
    assert "room:8" in g


def test_a_narrow_passage_keeps_rooms_apart() -> None:
    g, by_room = two_rooms("bathroom", "bathroom", width=0.8)
    merge_over_segmented_rooms(g, by_room)
    assert "room:8" in g


def test_different_types_stay_apart() -> None:
    g, by_room = two_rooms("bathroom", "bedroom")
    assert (
        plan_merges(
            {r.id: r for r in g.nodes(Layer.ROOM) if isinstance(r, RoomNode)},
            by_room,
            list(g.edges(EdgeKind.CONNECTS)),
        )
        == {}
    )


def test_rooms_without_evidence_stay_apart() -> None:
    g, by_room = two_rooms(None, None)
    merge_over_segmented_rooms(g, by_room)
    assert "room:8" in g


def test_union_too_large_for_the_type_stays_apart() -> None:
    hi = room_vocab.room_type_table()["toilet"].area
    assert hi is not None
    a, b = rect(0.0, 0.0, 1.4, 1.4), rect(1.4, 0.0, 1.4, 1.4)
    labels = strongest("toilet", 1)
    assert merged_type(labels, a, labels, b) == "toilet"
    big = rect(1.4, 0.0, hi[1], 1.4)
    assert merged_type(labels, a, labels, big) is None


def test_parts_of_a_split_room_are_left_to_the_split() -> None:
    g, by_room = two_rooms("bathroom", "bathroom")
    rooms = {r.id: r for r in g.nodes(Layer.ROOM) if isinstance(r, RoomNode)}
    rooms = {("room:3.1" if k == "room:3" else k): v for k, v in rooms.items()}
    by_room = {("room:3.1" if k == "room:3" else k): v for k, v in by_room.items()}
    edge = Edge.make(EdgeKind.CONNECTS, "room:3.1", "room:8", width=1.3, source="open plan")
    assert plan_merges(rooms, by_room, [edge]) == {}
