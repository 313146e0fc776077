"""Room segmentation (EDT + watershed) on synthetic grids, and the room-ID grid."""

from __future__ import annotations

import numpy as np

from inherit_sg.geometry.regions import adjacency, ascent_basins
from inherit_sg.geometry.room_ids import RoomIdGrid
from inherit_sg.geometry.rooms import SegmentParams, segment_rooms

RES = 0.05


def _cells(v: float) -> int:
    return round(v / RES)


class Plan:
    """A grid of free space with walls (2 cells thick) and door gaps."""

    def __init__(self, width: float, height: float) -> None:
        self.occ = np.zeros((_cells(height), _cells(width)), dtype=bool)
        self.occ[:2] = self.occ[-2:] = True
        self.occ[:, :2] = self.occ[:, -2:] = True

    def wall_x(self, y: float, x0: float, x1: float) -> None:
        self.occ[_cells(y) - 1 : _cells(y) + 1, _cells(x0) : _cells(x1)] = True

    def wall_y(self, x: float, y0: float, y1: float) -> None:
        self.occ[_cells(y0) : _cells(y1), _cells(x) - 1 : _cells(x) + 1] = True

    def gap_y(self, x: float, y0: float, y1: float) -> None:
        self.occ[_cells(y0) : _cells(y1), _cells(x) - 1 : _cells(x) + 1] = False

    def gap_x(self, y: float, x0: float, x1: float) -> None:
        self.occ[_cells(y) - 1 : _cells(y) + 1, _cells(x0) : _cells(x1)] = False

    @property
    def free(self) -> np.ndarray:
        return ~self.occ


def house() -> Plan:
    """A 2.5 m hallway (x 0–2.5) and three rooms, each with a 0.9 m door."""
    p = Plan(10.0, 6.0)
    p.wall_y(2.5, 0.0, 6.0)
    p.wall_y(6.2, 0.0, 6.0)
    p.wall_x(3.0, 2.5, 6.2)
    p.gap_y(2.5, 1.0, 1.9)  # hallway - room A
    p.gap_y(2.5, 4.0, 4.9)  # hallway - room B
    p.gap_y(6.2, 1.0, 1.9)  # room A - room C
    return p


def _room_at(labels: np.ndarray, x: float, y: float) -> int:
    return int(labels[_cells(y), _cells(x)])


def test_three_rooms_and_a_hallway_with_their_doors() -> None:
    seg = segment_rooms(house().free, SegmentParams())
    lab = seg.labels
    hall, a, b, c = (_room_at(lab, x, y) for x, y in ((1.2, 3), (4, 1.5), (4, 4.5), (8, 3)))
    assert seg.count == 4
    assert len({hall, a, b, c}) == 4 and 0 not in {hall, a, b, c}
    pairs = {frozenset((p.a, p.b)): p for p in seg.passages}
    assert set(pairs) == {frozenset(t) for t in ((hall, a), (hall, b), (a, c))}
    door = pairs[frozenset((hall, a))]
    assert abs(door.col * RES - 2.5) < 0.2 and abs(door.row * RES - 1.45) < 0.3
    assert 0.7 < door.width < 1.1


def test_long_hallway_is_one_room() -> None:
    p = Plan(2.5, 12.0)
    seg = segment_rooms(p.free, SegmentParams())
    assert seg.count == 1


def test_wide_opening_joins_rooms_but_a_known_door_separates_them() -> None:
    p = Plan(8.0, 4.0)
    p.wall_y(4.0, 0.0, 4.0)
    p.gap_y(4.0, 1.0, 3.0)  # a 2 m opening: no door
    assert segment_rooms(p.free, SegmentParams()).count == 1
    disc = (_cells(2.0), _cells(4.0), 1.05 / RES)
    seg = segment_rooms(p.free, SegmentParams(), doors=[disc])
    assert seg.count == 2
    assert _room_at(seg.labels, 2, 2) != _room_at(seg.labels, 6, 2)


def test_narrow_gap_open_above_is_furniture_not_a_door() -> None:
    p = Plan(8.0, 4.0)
    p.wall_y(4.0, 0.0, 4.0)
    p.gap_y(4.0, 1.6, 2.4)
    assert segment_rooms(p.free, SegmentParams()).count == 2
    open_above = np.zeros_like(p.occ)
    open_above[_cells(1.2) : _cells(2.8), _cells(3.5) : _cells(4.5)] = True
    lintel = np.zeros_like(p.occ)
    assert segment_rooms(p.free, SegmentParams(), open_above=open_above, lintel=lintel).count == 1
    lintel[_cells(1.6) : _cells(2.4), _cells(4.0) - 1 : _cells(4.0) + 1] = True
    assert segment_rooms(p.free, SegmentParams(), open_above=open_above, lintel=lintel).count == 2


def test_small_regions_are_pruned_and_specks_ignored() -> None:
    p = house()
    free = p.free.copy()
    closet = np.zeros_like(free)
    closet[_cells(0.1) : _cells(0.6), _cells(9.0) : _cells(9.6)] = True
    free[_cells(0.1) - 1 : _cells(0.6) + 1, _cells(9.0) - 1 : _cells(9.6) + 1] = False
    free |= closet  # 0.25 m² enclosed pocket
    rng = np.random.default_rng(0)
    speck = rng.random(free.shape) < 0.002
    seg = segment_rooms(free & ~speck, SegmentParams())
    assert seg.count == 4
    assert not seg.labels[closet].any()


def test_unobserved_streaks_do_not_split_a_room() -> None:
    p = Plan(8.0, 5.0)
    free = p.free.copy()
    for k in range(8):  # unobserved streaks across the middle, like gaps between far rays
        row = _cells(0.6 * k + 0.3)
        free[row : row + 2, _cells(3.0) : _cells(5.0)] = False
    params = SegmentParams()
    assert segment_rooms(free, params).count == 2  # as if the streaks were walls
    assert segment_rooms(free, params, occupied=p.occ).count == 1


def test_ascent_basins_finds_each_peak() -> None:
    h = np.zeros((20, 40))
    h[10, 8] = 5.0
    h[10, 30] = 4.0
    from scipy import ndimage as ndi

    smooth = ndi.gaussian_filter(h, 3)
    labels = ascent_basins(smooth, np.ones_like(h, dtype=bool))
    assert labels.max() == 2
    assert labels[10, 0] != labels[10, 39]
    adj = adjacency(labels, smooth)
    assert len(adj.a) == 1 and adj.length[0] == 20


def test_room_ids_keep_identity_and_resist_flicker() -> None:
    grid = RoomIdGrid(hysteresis=2)
    labels = np.zeros((10, 20), dtype=np.int32)
    labels[:, :10], labels[:, 10:] = 1, 2
    grid.align(labels.shape, 0, 0)
    first = grid.update(labels).copy()
    a, b = int(first[0, 0]), int(first[0, 19])
    assert a != b and a > 0 and b > 0
    swapped = np.where(labels == 1, 2, 1).astype(np.int32)  # same rooms, other numbers
    assert np.array_equal(grid.update(swapped), first)
    moved = labels.copy()
    moved[:, 10:12] = 1  # the border moves by two columns
    grid.update(moved)
    assert grid.ids[0, 10] == b  # one vote is not enough
    grid.update(moved)
    assert grid.ids[0, 10] == a
    grid.align((12, 24), 1, 2)  # the occupancy grid grew
    assert grid.ids.shape == (12, 24) and grid.ids[1, 2] == a
    assert grid.room_ids() == sorted({a, b})


def test_split_room_gets_a_new_id() -> None:
    grid = RoomIdGrid(hysteresis=1)
    whole = np.ones((10, 20), dtype=np.int32)
    grid.align(whole.shape, 0, 0)
    first = int(grid.update(whole)[0, 0])
    split = whole.copy()
    split[:, 12:] = 2
    ids = grid.update(split)
    assert ids[0, 0] == first and ids[0, 19] not in (0, first)
