"""BEV occupancy grid and depth ray casting."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.errors import FrameError
from inherit_sg.geometry.occupancy import OccupancyGrid
from inherit_sg.geometry.raycast import band_scan, integrate_scan, world_points
from tests.unit.geometry_fixtures import EYE, look_around, make_frame, two_rooms


def test_grid_grows_and_keeps_cells_in_place() -> None:
    grid = OccupancyGrid(0.1, margin=0.5)
    grid.ensure_contains(0.0, 0.0, 1.0, 1.0)
    r, c = grid.cells_of(np.array([[0.55, 0.25]]))
    grid.logodds[r[0], c[0]] = 2.0
    before = grid.shape
    grid.ensure_contains(-3.0, -2.0, 0.5, 4.0)
    assert grid.shape[0] > before[0] and grid.shape[1] > before[1]
    r2, c2 = grid.cells_of(np.array([[0.55, 0.25]]))
    assert grid.logodds[r2[0], c2[0]] == 2.0
    assert grid.origin_x <= -3.0 and grid.origin_y <= -2.0
    x, y = grid.cell_center(float(r2[0]), float(c2[0]))
    assert abs(x - 0.55) < 0.05 and abs(y - 0.25) < 0.05


def test_hit_wins_over_miss_in_one_scan_and_log_odds_clamp() -> None:
    grid = OccupancyGrid(0.1)
    grid.ensure_contains(0, 0, 1, 1)
    w = grid.shape[1]
    cell = 3 * w + 4
    other = 5 * w + 5
    for _ in range(20):
        grid.update(np.array([cell, other]), np.array([cell]))
    assert grid.logodds.reshape(-1)[cell] == grid.params.hi
    assert grid.logodds.reshape(-1)[other] == grid.params.lo
    assert grid.occupied_mask().reshape(-1)[cell]
    assert grid.free_mask().reshape(-1)[other]
    assert grid.known_mask().sum() == 2


def _scan_room(z0: float = 0.0) -> OccupancyGrid:
    boxes = two_rooms(z0)
    grid = OccupancyGrid(0.05)
    for i, pose in enumerate(look_around(2.0, 2.0, z0 + EYE)):
        frame = make_frame(boxes, pose, i)
        pts = world_points(frame, 1, 12.0)
        scan = band_scan(pts, pose.translation, z0, (1.2, 1.9), 8.0, 0.5)
        integrate_scan(grid, scan)
    return grid


def _cell(grid: OccupancyGrid, x: float, y: float) -> tuple[int, int]:
    r, c = grid.cells_of(np.array([[x, y]]))
    return int(r[0]), int(c[0])


def test_walls_occupied_and_room_free_after_a_look_around() -> None:
    grid = _scan_room()
    occ, free = grid.occupied_mask(), grid.free_mask()
    for x, y in ((0.07, 2.0), (2.0, 3.92), (3.92, 0.8), (2.0, 0.07)):
        assert occ[_cell(grid, x, y)], (x, y)
    for x, y in ((2.0, 2.0), (1.0, 1.0), (3.0, 3.0), (0.5, 3.5)):
        assert free[_cell(grid, x, y)], (x, y)
    # Space beyond the outer wall was never seen.
    assert not grid.known_mask()[_cell(grid, -0.4, 2.0)]
    # Seen through the doorway: free space of room B.
    assert free[_cell(grid, 5.0, 1.95)]


def test_lintel_band_marks_the_door_and_not_open_floor() -> None:
    grid = _scan_room()
    lintel = grid.lintel_hits > 0
    assert lintel[_cell(grid, 3.92, 1.95)]  # wall above the door
    assert not lintel[_cell(grid, 2.0, 2.0)]
    r0, c0 = _cell(grid, 0.5, 0.5)
    r1, c1 = _cell(grid, 3.5, 3.5)
    # Rays to the upper walls crossed the band inside the room: open above there.
    assert grid.open_above_mask(1)[r0:r1, c0:c1].sum() > 100
    assert not grid.open_above_mask(1)[_cell(grid, 3.92, 1.95)]


def test_band_follows_the_floor_height() -> None:
    low = _scan_room(0.0)
    high = _scan_room(3.0)
    assert low.shape == high.shape
    assert np.array_equal(low.occupied_mask(), high.occupied_mask())


def test_far_noisy_hits_weigh_less() -> None:
    grid = OccupancyGrid(0.05)
    grid.ensure_contains(-1, -1, 8, 1)
    pts = np.array([[1.0, 0.0, 1.5], [6.0, 0.0, 1.5]], dtype=np.float32)
    scan = band_scan(pts, np.array([0.0, 0.0, 1.4]), 0.0, (1.2, 1.9), 8.0, 0.5)
    integrate_scan(grid, scan, sigma_1m=0.01)
    near = grid.logodds[_cell(grid, 1.0, 0.0)]
    far = grid.logodds[_cell(grid, 6.0, 0.0)]
    assert near > far > 0


def test_a_far_frame_cannot_stretch_the_grid() -> None:
    grid = OccupancyGrid(0.05)
    grid.ensure_contains(0.0, 0.0, 10.0, 8.0)
    before = (grid.shape, grid.origin_x, grid.origin_y)
    with pytest.raises(FrameError, match="beyond 300 m"):
        grid.ensure_contains(0.0, 0.0, 5000.0, 8.0)
    with pytest.raises(FrameError):
        grid.ensure_contains(0.0, 0.0, float("inf"), 8.0)
    assert (grid.shape, grid.origin_x, grid.origin_y) == before
    grid.ensure_contains(-20.0, 0.0, 40.0, 8.0)  # a larger house still fits
    assert grid.shape[1] > before[0][1]
