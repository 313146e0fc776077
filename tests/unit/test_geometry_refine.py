"""Global room-mask refinement: pruning, line regularisation, distance-field competition."""

from __future__ import annotations

import math

import numpy as np

from inherit_sg.geometry.lines import dominant_angle, fit_runs, regularise
from inherit_sg.geometry.refine import RefineParams, refine_rooms


def _iou(a: np.ndarray, b: np.ndarray) -> float:
    return float((a & b).sum()) / float((a | b).sum())


def _jagged_rect(
    shape: tuple[int, int], r0: int, r1: int, c0: int, c1: int, seed: int
) -> np.ndarray:
    """A rectangle whose border cells are randomly missing or grown by up to 3 cells."""
    rng = np.random.default_rng(seed)
    mask = np.zeros(shape, dtype=bool)
    for r in range(r0, r1):
        a = c0 + int(rng.integers(-3, 4))
        b = c1 + int(rng.integers(-3, 4))
        mask[r, a:b] = True
    for c in range(c0, c1):
        mask[r0 : r0 + int(rng.integers(0, 4)), c] = False
        mask[r1 - int(rng.integers(0, 4)) : r1, c] = False
    return mask


def test_fit_runs_straightens_jitter_and_keeps_real_steps() -> None:
    vals = np.r_[np.full(30, 10.0), np.full(30, 25.0)] + np.tile([0.0, 2.0, -1.0], 20)
    fit = fit_runs(vals, tol=4.0, min_run=5)
    assert set(np.unique(fit[:30])) == {10.0} and set(np.unique(fit[30:])) == {25.0}
    spike = np.full(40, 5.0)
    spike[20:22] = 30.0  # a two-row spike through a doorway
    assert np.all(fit_runs(spike, tol=4.0, min_run=6) == 5.0)


def test_regularise_makes_a_jagged_room_rectangular() -> None:
    true = np.zeros((80, 100), dtype=bool)
    true[10:70, 15:85] = True
    jagged = _jagged_rect(true.shape, 10, 70, 15, 85, seed=1)
    reg = regularise(jagged, 0.0, tol=7.0, min_run=6)
    assert _iou(reg, true) > _iou(jagged, true)
    assert _iou(reg, true) > 0.93
    # Straight: every row of the result spans one interval with few distinct ends.
    rows = np.flatnonzero(reg.any(axis=1))
    ends = {int(np.flatnonzero(reg[r])[-1]) for r in rows}
    assert len(ends) <= 2


def test_regularise_keeps_an_l_shape() -> None:
    true = np.zeros((80, 80), dtype=bool)
    true[10:70, 10:35] = True
    true[45:70, 10:70] = True
    reg = regularise(true, 0.0, tol=4.0, min_run=6)
    assert _iou(reg, true) > 0.97
    assert not reg[20, 60]  # the notch of the L stays empty


def test_dominant_angle_of_rotated_walls() -> None:
    occ = np.zeros((200, 200), dtype=bool)
    ang = math.radians(30.0)
    for t in np.linspace(-80, 80, 2000):
        for off in (-40, 40):
            for d, e in ((math.cos(ang), math.sin(ang)), (-math.sin(ang), math.cos(ang))):
                x = 100 + t * d - off * e
                y = 100 + t * e + off * d
                if 0 <= x < 200 and 0 <= y < 200:
                    occ[int(y), int(x)] = True
    got = math.degrees(dominant_angle(occ))
    assert abs(got - 30.0) < 3.0
    axis = np.zeros((50, 50), dtype=bool)
    axis[10, 5:45] = axis[40, 5:45] = axis[10:41, 5] = True
    assert dominant_angle(axis) == 0.0


def test_refine_prunes_noise_and_keeps_rooms_disjoint() -> None:
    shape = (90, 160)
    ids = np.zeros(shape, dtype=np.int32)
    a = _jagged_rect(shape, 10, 80, 10, 78, seed=2)
    b = _jagged_rect(shape, 10, 80, 82, 150, seed=3)
    ids[a] = 1
    ids[b & ~a] = 2
    ids[5:8, 100:103] = 1  # a stray patch of room 1 inside room 2's area
    ids[85:88, 5:8] = 3  # a tiny room: noise
    free = np.ones(shape, dtype=bool)
    occupied = np.zeros(shape, dtype=bool)
    occupied[:, 79:81] = True  # the wall between the rooms
    out = refine_rooms(ids, free, occupied, RefineParams(cell_size=0.05))
    assert set(np.unique(out)) == {0, 1, 2}
    assert not (out[5:8, 100:103] == 1).any()
    true_a = np.zeros(shape, dtype=bool)
    true_a[10:80, 10:79] = True
    assert _iou(out == 1, true_a) > 0.9
    assert _iou(out == 1, true_a) > _iou(ids == 1, true_a)


def test_overlapping_claims_go_to_the_nearest_room() -> None:
    shape = (60, 120)
    ids = np.zeros(shape, dtype=np.int32)
    ids[5:55, 5:60] = 1
    ids[5:55, 60:115] = 2
    ids[20:40, 50:60] = 2  # room 2 bulges into room 1's rectangle
    free = np.ones(shape, dtype=bool)
    out = refine_rooms(ids, free, np.zeros(shape, dtype=bool), RefineParams(cell_size=0.05))
    one, two = out == 1, out == 2
    assert not (one & two).any()
    assert one.sum() + two.sum() >= (ids > 0).sum() * 0.95
    assert out[30, 30] == 1 and out[30, 90] == 2
