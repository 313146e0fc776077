"""RANSAC-lite detection of the structural planes (floor, walls, ceiling) of a depth
image, used by the classical segmenter to separate objects from the room shell.

A plane is structural when it is large and almost nothing lies behind it as seen from
the camera: a wall or floor bounds the view, while the front of a cabinet or a table top
has the wall or floor behind it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from inherit_sg.model import Intrinsics


@dataclass(frozen=True)
class Plane:
    """``normal · p + offset = 0`` in the camera frame, oriented towards the camera."""

    normal: np.ndarray
    offset: float

    def signed_distance(self, points: np.ndarray) -> np.ndarray:
        """Positive on the camera's side (computed in the points' precision)."""
        return points @ self.normal.astype(points.dtype) + points.dtype.type(self.offset)


def backproject(depth: np.ndarray, k: Intrinsics) -> np.ndarray:
    """(H, W, 3) camera-frame points of a depth image in metres (0 where no reading)."""
    h, w = depth.shape
    vs, us = np.mgrid[0:h, 0:w].astype(np.float32)
    x = (us - np.float32(k.cx)) / np.float32(k.fx) * depth
    y = (vs - np.float32(k.cy)) / np.float32(k.fy) * depth
    return np.stack([x, y, depth], axis=-1)


def _fit(points: np.ndarray) -> Plane | None:
    """Least-squares plane through points, oriented towards the origin."""
    centre = points.mean(axis=0)
    _, s, vt = np.linalg.svd(points - centre, full_matrices=False)
    if s[1] < 1e-9:
        return None
    n = vt[2] / np.linalg.norm(vt[2])
    d = -float(n @ centre)
    return Plane(n, d) if d > 0 else Plane(-n, -d)


def _tolerance(z: np.ndarray, base: float, rel: float) -> np.ndarray:
    return base + rel * z


def _best_plane(
    pts: np.ndarray,
    tol: np.ndarray,
    alive: np.ndarray,
    rng: np.random.Generator,
    iterations: int,
    sample: int,
) -> Plane | None:
    """RANSAC: all candidate planes from random point triples, scored at once."""
    cand = np.flatnonzero(alive)
    tri = pts[rng.choice(cand, size=(iterations, 3))]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norms = np.linalg.norm(n, axis=1)
    ok = norms > 1e-9
    if not ok.any():
        return None
    n = n[ok] / norms[ok, None]
    d = -(n * tri[ok, 0]).sum(axis=1)
    ev = cand if cand.size <= sample else cand[rng.integers(0, cand.size, size=sample)]
    score = (np.abs(pts[ev] @ n.T + d) < tol[ev, None]).sum(axis=0)
    best = int(np.argmax(score))
    plane = Plane(n[best], float(d[best]))
    inl = alive & (np.abs(plane.signed_distance(pts)) < tol)
    refined = _fit(pts[inl]) if inl.sum() >= 3 else None
    return refined or (plane if plane.offset > 0 else Plane(-plane.normal, -plane.offset))


def structural_planes(
    points: np.ndarray,
    valid: np.ndarray,
    *,
    min_fraction: float = 0.01,
    max_planes: int = 8,
    iterations: int = 64,
    sample: int = 2000,
    max_points: int = 20000,
    tol: float = 0.015,
    rel_tol: float = 0.008,
    behind_fraction: float = 0.01,
    seed: int = 0,
) -> np.ndarray:
    """(H, W) bool mask of pixels on structural planes.

    Planes are searched on a subsample of at most ``max_points`` valid pixels; each
    structural plane then claims every valid pixel within tolerance of it.
    """
    rng = np.random.default_rng(seed)
    flat = points.reshape(-1, 3)
    idx_valid = np.flatnonzero(valid.ravel())
    structure = np.zeros(flat.shape[0], dtype=bool)
    if idx_valid.size < 3:
        return structure.reshape(valid.shape)
    step = max(1, idx_valid.size // max_points)
    pts = flat[idx_valid[::step]].astype(np.float64)
    tols = _tolerance(pts[:, 2], tol, rel_tol)
    alive = np.ones(len(pts), dtype=bool)
    full = flat[idx_valid]
    full_tols = _tolerance(full[:, 2], tol, rel_tol)
    for _ in range(max_planes):
        if alive.sum() < max(3, min_fraction * len(pts)):
            break
        plane = _best_plane(pts, tols, alive, rng, iterations, sample)
        if plane is None:
            break
        dist = plane.signed_distance(pts)
        inl = alive & (np.abs(dist) < tols)
        if inl.sum() < min_fraction * len(pts):
            break
        if (dist < -3 * tols).mean() <= behind_fraction:
            near = np.abs(plane.signed_distance(full)) < full_tols
            structure[idx_valid[near]] = True
        alive &= ~inl
    return structure.reshape(valid.shape)
