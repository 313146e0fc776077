"""Best viewpoint of a room (paper §III-B): 2D ray casting on the grid with occlusion,
choosing the keyframe whose field of view covers most of the room mask."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from inherit_sg.model import Intrinsics, Pose


@dataclass(frozen=True)
class View:
    """A keyframe seen from above: grid cell position, heading and horizontal FOV."""

    key: str
    row: float
    col: float
    yaw: float  # radians, world frame (0 = +x, pi/2 = +y)
    hfov: float  # radians


def heading(pose: Pose) -> float:
    """Yaw of the camera's optical axis projected on the floor."""
    fwd = pose.rotation[:, 2]
    return math.atan2(float(fwd[1]), float(fwd[0]))


def horizontal_fov(intr: Intrinsics) -> float:
    """Horizontal field of view of a pinhole camera."""
    return 2.0 * math.atan(intr.width / (2.0 * intr.fx))


def grid_views(
    shots: Sequence[tuple[str, Pose, float]], origin: tuple[float, float], resolution: float
) -> list[View]:
    """Views on a grid from ``(key, pose, horizontal fov)`` of keyframes."""
    out = []
    for key, pose, hfov in shots:
        t = pose.translation
        row = (float(t[1]) - origin[1]) / resolution - 0.5
        col = (float(t[0]) - origin[0]) / resolution - 0.5
        out.append(View(key, row, col, heading(pose), hfov))
    return out


def visible_cells(
    blocked: np.ndarray, view: View, max_range_cells: float, n_rays: int
) -> np.ndarray:
    """Flat indices of cells seen from ``view``; a ray stops at the first blocked cell."""
    h, w = blocked.shape
    ang = view.yaw + np.linspace(-view.hfov / 2.0, view.hfov / 2.0, n_rays)
    steps = np.arange(0.0, max_range_cells, 0.7)
    rr = view.row + 0.5 + np.sin(ang)[:, None] * steps[None, :]
    cc = view.col + 0.5 + np.cos(ang)[:, None] * steps[None, :]
    ri = np.floor(rr).astype(np.int64)
    ci = np.floor(cc).astype(np.int64)
    inside = (ri >= 0) & (ri < h) & (ci >= 0) & (ci < w)
    flat = np.where(inside, ri * w + ci, 0)
    stop = ~inside | blocked.reshape(-1)[flat]
    seen = np.cumsum(stop, axis=1) == 0
    return np.unique(flat[seen])


def best_viewpoint(
    room: np.ndarray,
    blocked: np.ndarray,
    views: Sequence[View],
    max_range_cells: float,
    n_rays: int = 90,
) -> tuple[str | None, float]:
    """Key of the view covering the largest share of ``room``, and that share."""
    total = int(room.sum())
    if total == 0 or not views:
        return None, 0.0
    flat_room = room.reshape(-1)
    r, c = np.nonzero(room)
    centre = (float(r.mean()), float(c.mean()))
    best: tuple[str | None, float, float] = (None, 0.0, -math.inf)
    for view in views:
        seen = visible_cells(blocked, view, max_range_cells, n_rays)
        share = float(flat_room[seen].sum()) / total
        # Ties go to the view nearer the room centre.
        near = -math.hypot(view.row - centre[0], view.col - centre[1])
        if (share, near) > (best[1], best[2]):
            best = (view.key, share, near)
    return best[0], best[1]


def best_views(
    ids: np.ndarray,
    blocked: np.ndarray,
    views: Sequence[View],
    max_range_cells: float,
    n_rays: int = 90,
    outside_weight: float = 0.5,
) -> dict[int, tuple[str, float]]:
    """Best view of every room of an id image at once: ``{room: (key, share)}``.

    Each view is ray-cast once; its visible cells are counted per room. A view taken
    from outside a room (through a door) counts ``outside_weight`` of its share, so a
    picture from inside wins unless it sees much less.
    """
    n = int(ids.max()) if ids.size else 0
    if n == 0 or not views:
        return {}
    sizes = np.bincount(ids.reshape(-1), minlength=n + 1).astype(np.float64)
    flat = ids.reshape(-1)
    best: dict[int, tuple[str, float]] = {}
    scores: dict[int, float] = {}
    h, w = ids.shape
    for view in views:
        seen = visible_cells(blocked, view, max_range_cells, n_rays)
        counts = np.bincount(flat[seen], minlength=n + 1)
        r = min(max(int(view.row + 0.5), 0), h - 1)
        c = min(max(int(view.col + 0.5), 0), w - 1)
        home = int(ids[r, c])
        for room in np.flatnonzero(counts[1:]) + 1:
            share = float(counts[room]) / sizes[room]
            score = share if room == home else share * outside_weight
            if score > scores.get(int(room), 0.0):
                scores[int(room)] = score
                best[int(room)] = (view.key, share)
    return best
