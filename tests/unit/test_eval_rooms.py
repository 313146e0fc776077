"""Room precision and recall against every true room (inherit_sg.benchmark.metrics.mapping): overlap
areas, the mutual-majority matching and the most-overlap correspondence."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.benchmark.metrics.mapping import match_rooms, room_correspondence, room_overlaps
from inherit_sg.ingest.synthetic.scene import FloorGT, RoomGT, Scene
from inherit_sg.model import RoomMask, RoomNode

RES = 0.1
LEVELS = {"floor:0": 0, "floor:1": 1}


def _rect(x0: float, y0: float, x1: float, y1: float) -> list[list[float]]:
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def _mask(x0: float, y0: float, x1: float, y1: float) -> RoomMask:
    shape = (round((y1 - y0) / RES), round((x1 - x0) / RES))
    return RoomMask(x0, y0, RES, np.ones(shape, dtype=bool))


def _room(rid: str, mask: RoomMask, floor: str = "floor:0", label: str = "room") -> RoomNode:
    return RoomNode(id=rid, label=label, floor_id=floor, mask=mask)


@pytest.fixture
def scene() -> Scene:
    s = Scene(name="rooms", seed=None)
    s.floors = [FloorGT(0, 0.0, 2.5), FloorGT(1, 3.0, 2.5)]
    s.rooms = [
        RoomGT("kitchen", "kitchen", 0, _rect(0, 0, 4, 4)),
        RoomGT("dining", "dining room", 0, _rect(4, 0, 8, 4)),
        RoomGT("living", "living room", 0, _rect(8, 0, 12, 4)),
        RoomGT("porch", "porch", 0, _rect(12, 0, 16, 4)),  # never mapped
        RoomGT("bed", "bedroom", 1, _rect(0, 0, 4, 4)),
    ]
    return s


def test_overlaps_are_areas_on_the_same_floor(scene: Scene) -> None:
    rooms = [
        _room("room:k", _mask(0, 0, 4, 4)),
        _room("room:up", _mask(0, 0, 2, 4), floor="floor:1"),
    ]
    ov = room_overlaps(rooms, scene, LEVELS)
    assert ov.pred_ids == ["room:k", "room:up"]
    assert ov.true_ids == ["kitchen", "dining", "living", "porch", "bed"]
    assert ov.overlap[0].tolist() == pytest.approx([16.0, 0, 0, 0, 0])
    # The upstairs room covers half the bedroom and nothing of the kitchen below it.
    assert ov.overlap[1].tolist() == pytest.approx([0, 0, 0, 0, 8.0])
    assert ov.true_area.tolist() == pytest.approx([16.0] * 5)
    assert ov.mapped.tolist() == pytest.approx([16.0, 0, 0, 0, 8.0])
    assert ov.pred_area.tolist() == pytest.approx([16.0, 8.0])


def test_mutual_majority_matching(scene: Scene) -> None:
    rooms = [
        _room("room:k", _mask(0, 0, 4, 4)),  # the kitchen
        _room("room:open", _mask(4, 0, 12, 4)),  # dining and living merged: matches neither
        _room("room:corner", _mask(0, 0, 1, 1)),  # a fragment of the kitchen
        _room("room:up", _mask(0, 0, 2, 4), floor="floor:1"),  # what was seen of the bedroom
    ]
    m = match_rooms(rooms, scene, LEVELS)
    assert m.pairs == {"room:k": "kitchen", "room:up": "bed"}
    assert (m.predicted, m.true_rooms, m.matched) == (4, 5, 2)
    assert m.precision == pytest.approx(0.5) and m.recall == pytest.approx(0.4)
    assert m.unseen == ["porch"] and m.recall_seen == pytest.approx(0.5)
    assert "overlaps" not in m.to_dict() and m.to_dict()["pairs"] == m.pairs
    # Most overlap, for room assignment: the merged room stands for the larger part.
    rooms[1] = _room("room:open", _mask(4, 0, 10, 4))
    corr = room_correspondence(rooms, scene, LEVELS)
    assert corr == {
        "room:k": "kitchen",
        "room:open": "dining",
        "room:corner": "kitchen",
        "room:up": "bed",
    }


def test_a_region_split_in_two_is_matched_only_by_a_majority_part(scene: Scene) -> None:
    halves = [_room("room:a", _mask(4, 0, 6.4, 4)), _room("room:b", _mask(6.4, 0, 8, 4))]
    assert match_rooms(halves, scene, LEVELS).pairs == {"room:a": "dining"}
    even = [_room("room:a", _mask(4, 0, 6, 4)), _room("room:b", _mask(6, 0, 8, 4))]
    m = match_rooms(even, scene, LEVELS)
    assert m.pairs == {} and m.precision == 0.0 and m.recall == 0.0
    assert match_rooms([], scene, LEVELS).precision == 0.0
