"""Exterior doors: a door with the floor's footprint on one side of its panel and
nothing on the other is an exterior door; the map names it so, the room vocabulary
reads it as an entrance, and an open-plan room with one far from its kitchen gets an
entryway part."""

from __future__ import annotations

import numpy as np

from inherit_sg.mapping.exterior import (
    EXTERIOR_DOOR,
    exterior_doors,
    floor_footprint,
    is_exterior,
)
from inherit_sg.mapping.object_map import ObjectMap
from inherit_sg.mapping.open_plan import split_room
from inherit_sg.mapping.update import HierarchyBuilder
from inherit_sg.model import BBox3D, FloorNode, Layer, ObjectNode, RoomMask, RoomNode, SceneGraph
from inherit_sg.retrieval.match import is_kind_of
from inherit_sg.vocab import objects as object_vocab

RES = 0.1


def mask_at(x0: float, y0: float, width: float, depth: float) -> RoomMask:
    cells = np.ones((round(depth / RES), round(width / RES)), dtype=bool)
    return RoomMask(x0, y0, RES, cells)


def door(i: int, x: float, y: float, across_x: bool, label: str = "door") -> ObjectNode:
    """A closed door panel 0.9 m wide and 5 cm thick; ``across_x``: the panel's normal
    points along x (the door is in a wall running along y)."""
    hx, hy = (0.025, 0.45) if across_x else (0.45, 0.025)
    box = BBox3D((x - hx, y - hy, 0.0), (x + hx, y + hy, 2.0))
    return ObjectNode(f"obj:{i}", label, (x, y, 1.0), box, floor_id="floor:0")


# Two rooms side by side: west (0..4, 0..4) and east (4..8, 0..4), wall at x = 4.
WEST, EAST = mask_at(0.0, 0.0, 4.0, 4.0), mask_at(4.0, 0.0, 4.0, 4.0)


def test_footprint_is_the_closed_union_of_the_rooms() -> None:
    foot = floor_footprint([WEST, EAST])
    assert foot is not None
    assert foot.contains(2.0, 2.0) and foot.contains(6.0, 2.0) and foot.contains(4.0, 2.0)
    assert not foot.contains(2.0, -1.0) and not foot.contains(9.0, 2.0)
    assert floor_footprint([]) is None


def test_a_door_in_the_outer_wall_is_exterior_and_one_between_rooms_is_not() -> None:
    foot = floor_footprint([WEST, EAST])
    assert foot is not None
    front = door(1, 2.0, 0.0, across_x=False)  # south wall of the west room
    inner = door(2, 4.0, 2.0, across_x=True)  # the wall between the rooms
    side = door(3, 8.0, 2.0, across_x=True)  # east wall of the east room
    assert is_exterior(foot, front) and is_exterior(foot, side)
    assert not is_exterior(foot, inner)
    found = exterior_doors([front, inner, side], {"floor:0": [WEST, EAST]})
    assert found == {"obj:1", "obj:3"}


def test_a_door_without_a_panel_direction_or_a_floor_is_not_exterior() -> None:
    foot = floor_footprint([WEST, EAST])
    assert foot is not None
    square = ObjectNode(
        "obj:4",
        "door",
        (2.0, 0.0, 1.0),
        BBox3D((1.6, -0.4, 0.0), (2.4, 0.4, 2.0)),
        floor_id="floor:0",
    )
    assert not is_exterior(foot, square)
    assert exterior_doors([door(5, 2.0, 0.0, across_x=False)], {}) == set()
    # only doors are tested
    assert (
        exterior_doors([door(6, 2.0, 0.0, across_x=False, label="window")], {"floor:0": [WEST]})
        == set()
    )


def test_the_vocabulary_reads_an_exterior_door_as_a_door_and_an_entrance() -> None:
    assert object_vocab.canonical_label("front door") == EXTERIOR_DOOR
    assert object_vocab.canonical_label("back door") == EXTERIOR_DOOR
    assert is_kind_of(EXTERIOR_DOOR, "door")
    assert not is_kind_of("door", EXTERIOR_DOOR)


def kitchen_objects() -> list[ObjectNode]:
    labels = ["stove", "refrigerator", "dishwasher", "kitchen cabinet"]
    out = []
    for k, lab in enumerate(labels):
        x = 8.6 + 0.9 * k
        out.append(
            ObjectNode(
                f"obj:{10 + k}", lab, (x, 3.5, 0.4), BBox3D((x - 0.3, 3.2, 0), (x + 0.3, 3.8, 0.9))
            )
        )
    return out


def test_an_open_plan_room_splits_off_an_entryway_at_its_exterior_door() -> None:
    """A 12 m x 4 m room: kitchen at the east end, the front door in the west end's
    south wall (already named by the exterior test)."""
    mask = mask_at(0.0, 0.0, 12.0, 4.0)
    objects = [door(1, 1.5, 0.0, across_x=False, label=EXTERIOR_DOOR), *kitchen_objects()]
    split = split_room(mask, objects)
    assert split is not None
    assert [p.room_type for p in split.parts] == ["entryway", "kitchen"]
    # a plain door alone seeds nothing
    plain = [door(1, 1.5, 0.0, across_x=False), *kitchen_objects()]
    assert split_room(mask, plain) is None


class ZeroEmbedder:
    def embed(self, texts: list[str]) -> np.ndarray:
        return np.zeros((len(texts), 8), dtype=np.float32)


def test_the_global_update_names_exterior_doors_and_gives_the_label_back() -> None:
    graph = SceneGraph()
    graph.add_or_update(FloorNode("floor:0", 0, "floor 0", 0.0, 3.0))
    graph.add_or_update(RoomNode("room:1", "room", floor_id="floor:0", mask=WEST))
    graph.add_or_update(RoomNode("room:2", "room", floor_id="floor:0", mask=EAST))
    objects = ObjectMap(lambda a, b: 1.0 if a == b else 0.0)
    objects.adopt(door(1, 2.0, 0.0, across_x=False), "floor:0")
    objects.adopt(door(2, 4.0, 2.0, across_x=True), "floor:0")
    builder = HierarchyBuilder(ZeroEmbedder())

    def locate(x: float, y: float, _floor: str | None) -> str | None:
        return "room:1" if x < 4.0 else "room:2"

    builder.rebuild(graph, objects, locate)
    labels = {o.id: o.label for o in graph.nodes(Layer.OBJECT) if isinstance(o, ObjectNode)}
    assert labels == {"obj:1": EXTERIOR_DOOR, "obj:2": "door"}
    # the map grows south of the door: it now leads into a room and is a door again
    graph.add_or_update(
        RoomNode("room:3", "room", floor_id="floor:0", mask=mask_at(0.0, -4.0, 4.0, 4.0))
    )
    builder.rebuild(graph, objects, locate)
    assert graph.get("obj:1").label == "door"
