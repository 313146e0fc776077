"""Rooms of objects outside every room's mask: the nearest mask within reach."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.mapping.update import ROOM_REACH, nearest_room
from inherit_sg.model import BBox3D, ObjectNode, RoomMask, RoomNode, SceneGraph


def _mask(x0: float, y0: float, x1: float, y1: float, res: float = 0.1) -> RoomMask:
    cells = np.ones((round((y1 - y0) / res), round((x1 - x0) / res)), dtype=bool)
    return RoomMask(x0, y0, res, cells)


def _object(x: float, y: float) -> ObjectNode:
    box = BBox3D((x - 0.2, y - 0.2, 0.0), (x + 0.2, y + 0.2, 0.5))
    return ObjectNode("obj:1", "cushion", (x, y, 0.4), box, floor_id="floor:0")


@pytest.fixture()
def graph() -> SceneGraph:
    g = SceneGraph()
    # a narrow strip mapped of a TV room (x 0-1) whose far side the camera only saw
    # past the couch, and a big living room whose centre is nearer that far side
    g.add_or_update(
        RoomNode("room:tv", "tv room", "floor:0", (0.5, 2.0, 0.0), mask=_mask(0, 0, 1, 4))
    )
    g.add_or_update(
        RoomNode("room:lr", "living room", "floor:0", (2.5, 7.5, 0.0), mask=_mask(0, 5, 5, 10))
    )
    g.add_or_update(RoomNode("room:up", "bedroom", "floor:1", (2.5, 2.0, 0.0)))
    return g


def test_mask_distance() -> None:
    mask = _mask(0, 0, 1, 4)
    assert mask.distance_xy(0.5, 2.0) == 0.0
    assert mask.distance_xy(3.0, 2.05) == pytest.approx(2.05, abs=1e-6)  # to a cell centre
    empty = RoomMask(0.0, 0.0, 0.1, np.zeros((3, 3), dtype=bool))
    assert empty.distance_xy(0.0, 0.0) == float("inf")


def test_an_object_past_the_mapped_floor_joins_the_nearest_mask(graph: SceneGraph) -> None:
    # 2.05 m from the TV room's mask but 2.5 m from its centre (by room centres it
    # would have had no room), 3 m from the living room's mask
    assert nearest_room(graph, _object(3.0, 2.0)) == "room:tv"
    assert nearest_room(graph, _object(0.5, 6.0)) == "room:lr"  # inside a mask


def test_nothing_within_reach_or_on_another_floor(graph: SceneGraph) -> None:
    assert nearest_room(graph, _object(1.0 + ROOM_REACH + 0.5, 2.0)) is None
    other = _object(2.5, 2.5)
    other.floor_id = "floor:1"
    assert nearest_room(graph, other) == "room:up"  # no mask: by its centre
