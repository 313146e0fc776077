"""What people ask for by purpose, by position and by extent: a wall cabinet is a
cabinet, so it is somewhere to put things away; "by the front door" is near the front
door, not near any door; "the picture hung highest" sits highest, "the widest TV" is the
widest."""

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
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from tests.unit.retrieval_fixtures import floor_snapshot
from tests.unit.retrieval_rank import rank

Box = tuple[tuple[float, float, float], tuple[float, float, float]]


def _boxes_snapshot(objects: list[tuple[str, str, Box]]) -> MapSnapshot:
    """One room on one storey whose floor is at 3 m, with ``(key, label, box)`` objects
    (box corners relative to that floor)."""
    g = SceneGraph()
    floor = FloorNode(make_id(Layer.FLOOR, 1), 1, "upstairs", 3.0, 5.8)
    room = RoomNode(make_id(Layer.ROOM, "r"), "living room", floor_id=floor.id)
    g.add_or_update(floor)
    g.add_or_update(room)
    g.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor.id, room.id))
    for key, label, (lo, hi) in objects:
        lo3 = (lo[0], lo[1], lo[2] + 3.0)
        hi3 = (hi[0], hi[1], hi[2] + 3.0)
        centre = tuple((a + b) / 2 for a, b in zip(lo3, hi3, strict=True))
        g.add_or_update(
            ObjectNode(
                make_id(Layer.OBJECT, key),
                label,
                centre,  # type: ignore[arg-type]
                BBox3D(lo3, hi3),
                room_id=room.id,
                floor_id=floor.id,
            )
        )
    return build_snapshot(g, (1,))


def test_a_kind_of_a_listed_kind_serves_the_function() -> None:
    snap = floor_snapshot(
        [
            ("wc", "wall cabinet", 0.0, 0.0, "k"),
            ("fridge", "refrigerator", 1.0, 0.0, "k"),
            ("robe", "wardrobe", 8.0, 0.0, "b"),
        ],
        {"k": ("kitchen", 0.5), "b": ("bedroom", 8.0)},
    )
    ranked, _ = rank(snap, parse_rules("somewhere I can put some things away in the kitchen"))
    assert ranked[0].id == "obj:wc"
    why = " ".join(t.why for t in ranked[0].terms.values())
    assert "is a cabinet" in why


def test_nearness_counts_the_best_landmarks_only() -> None:
    # the front door is the exterior door; a plain door elsewhere may not stand in for it
    snap = floor_snapshot(
        [
            ("front", "exterior door", 0.0, 0.0, None),
            ("inner", "door", 10.0, 0.0, None),
            ("t_far", "towel", 11.0, 0.0, None),
            ("t_hall", "towel", 3.0, 0.0, None),
        ]
    )
    ranked, _ = rank(snap, parse_rules("the towel by the front door"))
    assert ranked[0].id == "obj:t_hall"


def test_highest_is_how_high_it_sits_not_how_tall_it_is() -> None:
    snap = _boxes_snapshot(
        [
            ("tall", "painting", ((0, 0, 0.2), (1, 0.05, 1.8))),  # tall, centre 1.0 m
            ("high", "painting", ((2, 0, 1.6), (2.5, 0.05, 2.0))),  # small, centre 1.8 m
        ]
    )
    ranked, _ = rank(snap, parse_rules("the painting hung highest on the wall"))
    assert ranked[0].id == "obj:high"
    ranked, _ = rank(snap, parse_rules("the lowest painting"))
    assert ranked[0].id == "obj:tall"
    ranked, _ = rank(snap, parse_rules("the tallest painting"))
    assert ranked[0].id == "obj:tall"


def test_widest_compares_the_longer_side_of_the_footprint() -> None:
    snap = _boxes_snapshot(
        [
            ("deep", "tv", ((0, 0, 0.5), (1.0, 0.9, 1.2))),  # bulky old set, 1.0 m wide
            ("wide", "tv", ((3, 0, 0.5), (4.6, 0.1, 1.4))),  # flat screen, 1.6 m wide
        ]
    )
    ranked, _ = rank(snap, parse_rules("the widest TV"))
    assert ranked[0].id == "obj:wide"
    ranked, _ = rank(snap, parse_rules("the narrowest TV"))
    assert ranked[0].id == "obj:deep"
