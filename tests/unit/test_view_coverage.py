"""Stops that let look-arounds see a whole room (inherit_sg/ingest/view_coverage.py)."""

from __future__ import annotations

import numpy as np

from inherit_sg.ingest.view_coverage import SIGHT_M, coverage_stops, sight

RES = 0.1


def _room(rows: int, cols: int) -> np.ndarray:
    return np.ones((rows, cols), dtype=bool)


def test_sight_is_stopped_by_walls_but_not_by_what_the_spot_belongs_to() -> None:
    blocked = np.zeros((30, 30), dtype=bool)
    blocked[:, 15] = True  # a wall across the middle
    targets = np.array([[5, 10], [5, 25], [5, 16]])
    seen = sight(blocked, (5, 5), targets, RES)
    # before the wall; behind it; just past it (the wall is within the spot's own margin)
    assert seen.tolist() == [True, False, True]
    far = np.array([[5, 5 + int(SIGHT_M / RES) + 2]])
    assert not sight(np.zeros((10, 60), dtype=bool), (5, 5), far, RES)[0]


def test_an_open_square_room_needs_one_stop() -> None:
    room = _room(30, 30)
    stops = coverage_stops(room, room, np.zeros_like(room), RES, (15, 15))
    assert stops == [(15, 15)]


def test_an_l_shaped_room_gets_a_stop_that_sees_round_the_corner() -> None:
    room = np.zeros((60, 60), dtype=bool)
    room[:20, :] = True  # the long arm
    room[:, :20] = True  # the other arm
    blocked = ~room
    stops = coverage_stops(room, room, blocked, RES, (10, 50))
    assert len(stops) >= 2
    cells = np.argwhere(room & ~blocked)
    seen = np.zeros(len(cells), dtype=bool)
    for stop in stops:
        seen |= sight(blocked, stop, cells, RES)
    assert seen.mean() > 0.85
    first_only = sight(blocked, stops[0], cells, RES)
    assert first_only.mean() < 0.7  # the first stop alone misses the other arm


def test_furniture_hides_what_stands_behind_it() -> None:
    room = _room(40, 40)
    blocked = np.zeros_like(room)
    blocked[5:35, 18:22] = True  # a long sofa across the room
    reach = room & ~blocked
    stops = coverage_stops(room, reach, blocked, RES, (20, 10))
    assert len(stops) == 2 and stops[1][1] > 22  # the second stop is behind the sofa
