"""Hand-built scenes for the geometry tests: worlds of axis-aligned boxes rendered by
exact ray casting into posed RGB-D frames (no simulator needed)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from inherit_sg.model import Frame, Intrinsics, Pose

Box = tuple[tuple[float, float, float], tuple[float, float, float]]

INTR = Intrinsics(160, 120, 87.5, 87.5, 79.5, 59.5, 1000.0)
EYE = 1.4
CEILING = 2.8
DOOR_TOP = 2.05


def look_pose(x: float, y: float, z: float, yaw: float, pitch_deg: float = 12.0) -> Pose:
    """Camera at (x, y, z) heading ``yaw`` (from +x, counter-clockwise), looking
    ``pitch_deg`` below the horizon; OpenCV axes."""
    p = math.radians(pitch_deg)
    fwd = np.array([math.cos(yaw) * math.cos(p), math.sin(yaw) * math.cos(p), -math.sin(p)])
    right = np.array([math.sin(yaw), -math.cos(yaw), 0.0])
    down = np.cross(fwd, right)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, down, fwd, (x, y, z)
    return Pose.from_matrix(m)


_CACHE: dict[tuple[object, ...], tuple[np.ndarray, np.ndarray]] = {}


def render(
    boxes: Sequence[Box], pose: Pose, intr: Intrinsics = INTR
) -> tuple[np.ndarray, np.ndarray]:
    """(z-depth in metres, index of the box hit or -1) for every pixel (memoised: tests
    walk the same poses through the same worlds)."""
    key = (tuple(boxes), pose.matrix16, intr)
    if key not in _CACHE:
        _CACHE[key] = _render(boxes, pose, intr)
    depth, which = _CACHE[key]
    return depth.copy(), which.copy()


def _render(boxes: Sequence[Box], pose: Pose, intr: Intrinsics) -> tuple[np.ndarray, np.ndarray]:
    u, v = np.meshgrid(np.arange(intr.width), np.arange(intr.height))
    d_cam = np.stack(
        [(u - intr.cx) / intr.fx, (v - intr.cy) / intr.fy, np.ones(u.shape)], axis=-1
    ).reshape(-1, 3)
    dirs = d_cam @ pose.rotation.T
    dirs[np.abs(dirs) < 1e-12] = 1e-12
    inv = 1.0 / dirs
    origin = pose.translation
    best = np.full(len(dirs), np.inf)
    which = np.full(len(dirs), -1)
    for k, (lo, hi) in enumerate(boxes):
        t1 = (np.asarray(lo) - origin) * inv
        t2 = (np.asarray(hi) - origin) * inv
        tmin = np.minimum(t1, t2).max(axis=1)
        tmax = np.maximum(t1, t2).min(axis=1)
        hit = (tmax >= tmin) & (tmin > 1e-6) & (tmin < best)
        best[hit] = tmin[hit]
        which[hit] = k
    depth = np.where(np.isfinite(best), best, 0.0).reshape(intr.height, intr.width)
    return depth.astype(np.float32), which.reshape(intr.height, intr.width)


def palette(n: int, seed: int = 0) -> np.ndarray:
    """``n`` distinct-ish RGB colours."""
    rng = np.random.default_rng(seed)
    return rng.integers(30, 230, size=(n, 3)).astype(np.uint8)


def make_frame(
    boxes: Sequence[Box], pose: Pose, index: int, colours: np.ndarray | None = None
) -> Frame:
    """A posed RGB-D frame of the box world (colour by box, shaded by depth)."""
    depth, which = render(boxes, pose)
    cols = palette(len(boxes)) if colours is None else colours
    rgb = np.where(which[..., None] >= 0, cols[np.maximum(which, 0)], 0).astype(np.float32)
    rgb *= np.clip(1.2 - depth[..., None] / 10.0, 0.3, 1.0)
    return Frame(
        index=index,
        frame_id=f"{index:06d}",
        timestamp=float(index),
        rgb=rgb.astype(np.uint8),
        depth=depth,
        pose=pose,
        intrinsics=INTR,
    )


def wall_x(y: float, x0: float, x1: float, z0: float, z1: float, t: float = 0.12) -> Box:
    """Wall along x at ``y``."""
    return ((x0, y - t / 2, z0), (x1, y + t / 2, z1))


def wall_y(x: float, y0: float, y1: float, z0: float, z1: float, t: float = 0.12) -> Box:
    """Wall along y at ``x``."""
    return ((x - t / 2, y0, z0), (x + t / 2, y1, z1))


def two_rooms(z: float = 0.0, door: tuple[float, float] = (1.5, 2.4)) -> list[Box]:
    """Rooms A (x 0–4) and B (x 4–8), y 0–4, joined by a door at x = 4 spanning ``door``
    in y, with a lintel above it; floor surface at ``z``."""
    top = z + CEILING
    d0, d1 = door
    return [
        ((-0.5, -0.5, z - 0.2), (8.5, 4.5, z)),  # floor slab
        ((-0.5, -0.5, top), (8.5, 4.5, top + 0.2)),  # ceiling slab
        wall_x(0.0, -0.06, 8.06, z, top),
        wall_x(4.0, -0.06, 8.06, z, top),
        wall_y(0.0, 0.0, 4.0, z, top),
        wall_y(8.0, 0.0, 4.0, z, top),
        wall_y(4.0, 0.0, d0, z, top),
        wall_y(4.0, d1, 4.0, z, top),
        wall_y(4.0, d0, d1, z + DOOR_TOP, top),  # lintel
    ]


def look_around(x: float, y: float, z: float, n: int = 12) -> list[Pose]:
    """Poses turning in place once around."""
    return [look_pose(x, y, z, 2 * math.pi * k / n) for k in range(n)]


def two_room_walk(z: float = 0.0) -> list[Pose]:
    """Look around in room A, walk through the door, look around in room B."""
    eye = z + EYE
    poses = look_around(2.0, 2.0, eye)
    for x in (2.8, 3.4, 4.0, 4.6, 5.2):
        poses.append(look_pose(x, 1.95, eye, 0.0))
    poses += look_around(6.0, 2.0, eye)
    return poses
