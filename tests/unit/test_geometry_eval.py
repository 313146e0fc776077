"""Geometry evaluation: polygon rasterisation, room matching at IoU 0.5, floor metrics."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.benchmark.metrics.geometry import (
    combine,
    floor_metrics,
    match_masks,
    paste,
    rasterize_polygon,
    room_metrics,
    true_frame_floors,
)
from inherit_sg.ingest.synthetic.scene import FloorGT, RoomGT
from inherit_sg.model import RoomMask


def test_rasterize_polygon_area_and_l_shape() -> None:
    square = rasterize_polygon([[0, 0], [2, 0], [2, 3], [0, 3]], (-1.0, -1.0), 0.05, (120, 100))
    assert square.sum() * 0.05**2 == pytest.approx(6.0, rel=0.01)
    ell = [[0, 0], [4, 0], [4, 1], [1, 1], [1, 3], [0, 3]]
    mask = rasterize_polygon(ell, (0.0, 0.0), 0.1, (40, 50))
    assert mask.sum() * 0.01 == pytest.approx(6.0, rel=0.01)
    assert mask[5, 30] and not mask[20, 30]


def test_matching_is_one_to_one_at_iou_half() -> None:
    a = np.zeros((10, 10), dtype=bool)
    a[:, :5] = True
    b = np.zeros_like(a)
    b[:, 5:] = True
    half = np.zeros_like(a)
    half[:, :2] = True
    matches = match_masks({"p1": a, "p2": half, "p3": b}, {"t1": a, "t2": b})
    assert {(p, t) for p, t, _ in matches} == {("p1", "t1"), ("p3", "t2")}


def test_room_metrics_modes_and_unseen_rooms() -> None:
    rooms = [
        RoomGT("r0", "kitchen", 0, [[0, 0], [4, 0], [4, 4], [0, 4]]),
        RoomGT("r1", "bedroom", 0, [[4, 0], [8, 0], [8, 4], [4, 4]]),
        RoomGT("r2", "office", 0, [[8, 0], [12, 0], [12, 4], [8, 4]]),
    ]
    origin, res, shape = (0.0, 0.0), 0.1, (40, 120)
    observed = np.zeros(shape, dtype=bool)
    observed[:, :80] = True  # r2 never seen
    pred_a = rasterize_polygon(rooms[0].polygon, origin, res, shape)
    pred_b = np.zeros(shape, dtype=bool)
    pred_b[:, 40:60] = True  # the half of r1 that was seen... in full mode only half
    m = room_metrics(
        {"a": pred_a, "b": pred_b}, rooms, origin, res, observed & ~(np.arange(120)[None, :] >= 60)
    )
    assert (m.precision, m.recall, m.unseen) == (1.0, 1.0, 1)
    full = room_metrics({"a": pred_a, "b": pred_b}, rooms, origin, res, observed, mode="full")
    assert full.matched == 2 and full.mean_iou < 1.0
    with pytest.raises(ValueError):
        room_metrics({}, rooms, origin, res, observed, mode="nope")
    pooled = combine([m, full])
    assert pooled.predicted == 4 and pooled.matched == 4


def test_paste_places_a_cropped_mask() -> None:
    cells = np.ones((2, 3), dtype=bool)
    out = paste(RoomMask(1.0, 0.5, 0.5, cells), (0.0, 0.0), (5, 6))
    assert out.sum() == 6 and out[1, 2] and out[2, 4] and not out[0, 0]


def test_floor_metrics_skip_stairs_frames() -> None:
    floors = [FloorGT(0, 0.0, 2.8), FloorGT(1, 3.0, 2.8)]
    cam = [1.4, 1.42, 2.3, 3.1, 4.4, 4.38]
    assert true_frame_floors(cam, floors) == [0, 0, None, None, 1, 1]
    got = floor_metrics([0.0, 0.0, 0.0, 0.0, 3.0, 0.0], cam, 2, floors)
    assert got.count_exact and got.scored_frames == 4
    assert got.frame_accuracy == pytest.approx(0.75)
    assert not floor_metrics([0.0] * 6, cam, 1, floors).count_exact
