"""Best viewpoint of a room: 2D ray casting with occlusion."""

from __future__ import annotations

import math

import numpy as np

from inherit_sg.geometry.viewpoint import View, best_viewpoint, best_views, visible_cells


def _world() -> tuple[np.ndarray, np.ndarray]:
    """Room 1 (cols 0-49) and room 2 (cols 51-99) split by a wall with a small door."""
    ids = np.zeros((50, 100), dtype=np.int32)
    ids[:, :50] = 1
    ids[:, 51:] = 2
    blocked = np.zeros_like(ids, dtype=bool)
    blocked[:, 50] = True
    blocked[22:28, 50] = False  # door
    return ids, blocked


def test_walls_occlude_and_the_fov_limits_what_is_seen() -> None:
    ids, blocked = _world()
    east = View("east", 25.0, 10.0, 0.0, math.radians(60))
    seen = visible_cells(blocked, east, 200, 120)
    rows, cols = np.divmod(seen, ids.shape[1])
    behind = (cols > 50) & (np.abs(rows - 25) > 8)
    assert not behind.any()  # the wall stops the rays beside the door
    assert ((cols > 60) & (np.abs(rows - 25) <= 3)).any()  # the door lets some through
    assert np.all(np.abs(rows - 25) <= (cols - 10) * math.tan(math.radians(31)) + 2)


def test_best_view_prefers_the_view_facing_the_room_from_inside() -> None:
    ids, blocked = _world()
    views = [
        View("facing-wall", 25.0, 45.0, 0.0, math.radians(80)),
        View("facing-room", 25.0, 5.0, 0.0, math.radians(80)),
        View("other-room", 25.0, 95.0, math.pi, math.radians(80)),
    ]
    key, share = best_viewpoint(ids == 1, blocked, views, 200, 120)
    assert key == "facing-room" and 0.3 < share <= 1.0
    best = best_views(ids, blocked, views, 200, 120)
    assert best[1][0] == "facing-room"
    assert best[2][0] == "other-room"
    assert best_viewpoint(np.zeros_like(blocked), blocked, views, 200) == (None, 0.0)
