"""Open-plan rooms: a large room whose object groups say different room types is split
into parts with stable ids; a coherent room stays whole.

Object labels are taken from the room vocabulary's evidence (the strongest kinds of a
type), so the tests follow ``rooms.toml`` rather than a word list of their own.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest
from scipy import ndimage

from inherit_sg.mapping.object_map import ObjectMap
from inherit_sg.mapping.open_plan import (
    SplitParams,
    is_part_id,
    part_room_id,
    split_open_plan_rooms,
    split_room,
)
from inherit_sg.mapping.room_semantics import type_evidence
from inherit_sg.mapping.update import HierarchyBuilder, RoomLocator
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
    """The ``n`` object kinds that say ``room_type`` most strongly (and no other type as
    much), from ``rooms.toml``."""
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


def rect_mask(width_m: float, depth_m: float) -> RoomMask:
    """A rectangular room from (0, 0) to (width, depth)."""
    cells = np.ones((round(depth_m / RES), round(width_m / RES)), dtype=bool)
    return RoomMask(0.0, 0.0, RES, cells)


def obj(i: int, label: str, x: float, y: float, size: float = 0.6) -> ObjectNode:
    h = size / 2
    box = BBox3D((x - h, y - h, 0.0), (x + h, y + h, 0.8))
    return ObjectNode(f"obj:{i}", label, (x, y, 0.4), box)


def row(labels: list[str], x0: float, y: float, first: int, step: float = 0.9) -> list[ObjectNode]:
    return [obj(first + k, lab, x0 + k * step, y) for k, lab in enumerate(labels)]


def open_plan_objects() -> list[ObjectNode]:
    """A 12 m × 4 m room: a kitchen group at the west end, a living group at the east."""
    kitchen = row(strongest("kitchen", 4), 0.6, 0.5, 1)
    living = row(strongest("living room", 3), 8.5, 2.0, 10)
    return kitchen + living


def test_kitchen_and_living_groups_split_the_room() -> None:
    mask = rect_mask(12.0, 4.0)
    objects = open_plan_objects()
    split = split_room(mask, objects)
    assert split is not None
    assert [p.room_type for p in split.parts] == ["kitchen", "living room"]
    # every cell to exactly one part, each part one connected piece
    total = np.zeros(mask.cells.shape, dtype=int)
    for p in split.parts:
        r0, c0 = round(p.mask.origin_y / RES), round(p.mask.origin_x / RES)
        h, w = p.mask.cells.shape
        total[r0 : r0 + h, c0 : c0 + w] += p.mask.cells
    assert np.array_equal(total, mask.cells.astype(int))
    assert np.array_equal(split.labels > 0, mask.cells)
    for part in split.parts:
        assert ndimage.label(part.mask.cells)[1] == 1
    west, east = split.parts
    assert west.centroid[0] < east.centroid[0]
    assert {o.id for o in west.objects} == {o.id for o in objects[:4]}
    assert {o.id for o in east.objects} == {o.id for o in objects[4:]}


def test_single_bedroom_stays_whole() -> None:
    bedroom = row(strongest("bedroom", 3), 1.0, 1.0, 1) + row(strongest("bedroom", 2), 7.0, 3.0, 5)
    assert split_room(rect_mask(10.0, 4.0), bedroom) is None


def test_small_room_stays_whole() -> None:
    assert split_room(rect_mask(6.0, 4.0), open_plan_objects()) is None


def test_weak_groups_do_not_split() -> None:
    """Two single objects say too little to make rooms."""
    kitchen, living = strongest("kitchen", 1), strongest("living room", 1)
    objects = [obj(1, kitchen[0], 1.0, 1.0), obj(2, living[0], 10.0, 3.0)]
    assert split_room(rect_mask(12.0, 4.0), objects) is None


class ZeroEmbedder:
    """Label embedder returning zero vectors (the hierarchy only stores them)."""

    def embed(self, texts: list[str]) -> np.ndarray:
        return np.zeros((len(texts), 8), dtype=np.float32)


def publish_geometry(graph: SceneGraph, mask: RoomMask) -> None:
    """What the geometric stream writes before every update: the floor, the room (back
    after a split removed it) and a neighbour through a door at the east end."""
    if "floor:0" not in graph:
        graph.add_or_update(FloorNode("floor:0", 0, "floor 0", 0.0, 3.0))
    graph.add_or_update(RoomNode("room:1", "room", floor_id="floor:0", mask=mask))
    graph.add_or_update(
        RoomNode(
            "room:2", "room", floor_id="floor:0", mask=rect_mask(2.0, 2.0), position=(13, 1, 0)
        )
    )
    graph.add_edge(Edge.make(EdgeKind.HAS_ROOM, "floor:0", "room:1"))
    graph.add_edge(Edge.make(EdgeKind.HAS_ROOM, "floor:0", "room:2"))
    graph.add_edge(Edge.make(EdgeKind.CONNECTS, "room:1", "room:2", door=[11.95, 1.0, 0.0]))


def same_label(a: str, b: str) -> float:
    return 1.0 if a == b else 0.0


@pytest.fixture
def mapped() -> Iterator[tuple[SceneGraph, ObjectMap, HierarchyBuilder, RoomMask]]:
    mask = rect_mask(12.0, 4.0)
    graph = SceneGraph()
    objects = ObjectMap(same_label)
    for o in open_plan_objects():
        objects.adopt(o, "floor:0")
    yield graph, objects, HierarchyBuilder(ZeroEmbedder()), mask


def locate(mask: RoomMask) -> RoomLocator:
    return lambda x, y, _floor: "room:1" if mask.contains_xy(x, y) else None


def room_ids(graph: SceneGraph) -> set[str]:
    return {n.id for n in graph.nodes(Layer.ROOM)}


def test_global_update_makes_part_rooms(
    mapped: tuple[SceneGraph, ObjectMap, HierarchyBuilder, RoomMask],
) -> None:
    graph, objects, builder, mask = mapped
    publish_geometry(graph, mask)
    builder.rebuild(graph, objects, locate(mask))
    west, east = part_room_id("room:1", 1), part_room_id("room:1", 2)
    assert room_ids(graph) == {west, east, "room:2"}
    assert all(is_part_id(r) for r in (west, east)) and not is_part_id("room:2")
    labels = {r: graph.get(r).label for r in (west, east)}
    assert labels == {west: "kitchen", east: "living room"}
    # hierarchy: floor -> parts, parts -> areas -> objects, objects in their part
    assert {e.dst for e in graph.out_edges("floor:0", EdgeKind.HAS_ROOM)} == room_ids(graph)
    for o in graph.objects():
        part = west if o.position[0] < 6 else east
        assert o.room_id == part
        assert o.area_id is not None and graph.parent(o.area_id) == part
    # adjacency: the parts touch, the door to room:2 is on the east part
    connects = {(e.src, e.dst): e for e in graph.edges(EdgeKind.CONNECTS)}
    assert set(connects) == {(west, east), (east, "room:2")}
    assert connects[(west, east)].prop("source") == "open plan"


def test_repeated_updates_keep_the_part_ids(
    mapped: tuple[SceneGraph, ObjectMap, HierarchyBuilder, RoomMask],
) -> None:
    graph, objects, builder, mask = mapped
    publish_geometry(graph, mask)
    builder.rebuild(graph, objects, locate(mask))
    first = {r: graph.get(r).label for r in room_ids(graph)}
    graph.flush_changes()
    publish_geometry(graph, mask)
    builder.rebuild(graph, objects, locate(mask))
    assert {r: graph.get(r).label for r in room_ids(graph)} == first
    changes = graph.flush_changes()
    rooms = {n for n in changes.new_nodes | changes.removed_nodes if n.startswith("room:")}
    assert rooms == set()  # the room published again and split again leaves no trace


def test_parts_go_when_the_room_is_whole_again(
    mapped: tuple[SceneGraph, ObjectMap, HierarchyBuilder, RoomMask],
) -> None:
    graph, objects, builder, mask = mapped
    publish_geometry(graph, mask)
    builder.rebuild(graph, objects, locate(mask))
    for tracked in list(objects.objects.values()):
        if tracked.node.position[0] > 6:
            objects.objects.pop(tracked.id)
            objects.removed.append(tracked.id)
    publish_geometry(graph, mask)
    builder.rebuild(graph, objects, locate(mask))
    assert room_ids(graph) == {"room:1", "room:2"}
    assert graph.get("room:1").label == "kitchen"
    assert all(o.room_id == "room:1" for o in graph.objects())


def test_split_can_be_switched_off(
    mapped: tuple[SceneGraph, ObjectMap, HierarchyBuilder, RoomMask],
) -> None:
    graph, objects, _, mask = mapped
    publish_geometry(graph, mask)
    HierarchyBuilder(ZeroEmbedder(), open_plan=None).rebuild(graph, objects, locate(mask))
    assert room_ids(graph) == {"room:1", "room:2"}


def test_split_open_plan_rooms_leaves_other_rooms() -> None:
    graph = SceneGraph()
    mask = rect_mask(12.0, 4.0)
    publish_geometry(graph, mask)
    bedroom = row(strongest("bedroom", 3), 1.0, 1.0, 1)
    for o in bedroom:
        graph.add_or_update(o)
    out = split_open_plan_rooms(graph, {"room:1": bedroom}, SplitParams())
    assert out == {"room:1": bedroom}
    assert room_ids(graph) == {"room:1", "room:2"}


def test_groups_of_one_type_at_both_ends_stay_one_room() -> None:
    kitchen = strongest("kitchen", 4)
    objects = row(kitchen[:2], 0.6, 0.5, 1) + row(kitchen[2:], 10.0, 3.0, 5)
    assert split_room(rect_mask(12.0, 4.0), objects) is None


def test_type_evidence_ignores_fixtures() -> None:
    fixtures = list(room_vocab.fixtures())[:5]
    assert not any(type_evidence(fixtures).values())
    kitchen = strongest("kitchen", 2)
    evidence = type_evidence(kitchen + fixtures)
    assert max(evidence, key=lambda t: evidence[t]) == "kitchen"
    assert evidence == type_evidence(kitchen)


def test_touching_groups_of_different_rooms_still_split() -> None:
    # the sofa group runs up against the kitchen run: footprints touch, yet a stove and
    # a sofa say nothing in common, so they do not chain into one group
    kitchen = row(strongest("kitchen", 4), 0.6, 0.5, 1, step=0.6)
    living = row(strongest("living room", 3), 3.0, 0.5, 10, step=0.6)
    split = split_room(rect_mask(12.0, 4.0), kitchen + living)
    assert split is not None
    assert [p.room_type for p in split.parts] == ["kitchen", "living room"]
