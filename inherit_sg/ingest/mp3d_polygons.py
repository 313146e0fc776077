"""Plane polygon helpers for MP3D region outlines: orientation, ear-clipping
triangulation, point-in-polygon tests, convex hulls and rasterisation onto a grid."""

from __future__ import annotations

import numpy as np

from inherit_sg.ingest.synthetic.grid import Grid

EPS = 1e-9


def signed_area(poly: np.ndarray) -> float:
    """Shoelace area of an (N, 2) polygon: positive when counter-clockwise."""
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def clean_ccw(points: list[list[float]] | np.ndarray, tol: float = 1e-4) -> np.ndarray:
    """The polygon counter-clockwise, without repeated or collinear vertices."""
    poly = np.asarray(points, dtype=float)[:, :2]
    if signed_area(poly) < 0:
        poly = poly[::-1]
    changed = True
    while changed and len(poly) > 3:
        changed = False
        for i in range(len(poly)):
            a, b, c = poly[i - 1], poly[i], poly[(i + 1) % len(poly)]
            if np.hypot(*(b - a)) < tol or abs(cross2(b - a, c - b)) < tol * np.hypot(*(c - a)):
                poly = np.delete(poly, i, axis=0)
                changed = True
                break
    return poly


def cross2(u: np.ndarray, v: np.ndarray) -> float:
    """z component of the cross product of two plan vectors."""
    return float(u[0] * v[1] - u[1] * v[0])


def _inside_triangle(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> bool:
    return (
        cross2(b - a, p - a) >= -EPS
        and cross2(c - b, p - b) >= -EPS
        and (cross2(a - c, p - c) >= -EPS)
    )


def triangulate(poly: np.ndarray) -> np.ndarray:
    """Ear-clipping triangulation of a simple counter-clockwise polygon: (N - 2, 3) vertex
    indices. A polygon that is not simple still yields triangles (fan of what is left)."""
    remaining = list(range(len(poly)))
    triangles: list[tuple[int, int, int]] = []
    while len(remaining) > 3:
        n = len(remaining)
        for k in range(n):
            i, j, m = remaining[k - 1], remaining[k], remaining[(k + 1) % n]
            a, b, c = poly[i], poly[j], poly[m]
            if cross2(b - a, c - b) <= EPS:
                continue  # reflex or flat corner: not an ear
            others = (poly[o] for o in remaining if o not in (i, j, m))
            if any(_inside_triangle(p, a, b, c) for p in others):
                continue
            triangles.append((i, j, m))
            remaining.pop(k)
            break
        else:  # no ear found (self-intersecting outline): fan the rest
            triangles += [(remaining[0], remaining[t], remaining[t + 1]) for t in range(1, n - 1)]
            remaining = []
    if len(remaining) == 3:
        triangles.append((remaining[0], remaining[1], remaining[2]))
    return np.array(triangles, dtype=np.int64).reshape(-1, 3)


def contains(poly: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Even-odd test: which of the (M, 2) ``points`` lie inside ``poly``."""
    x, y = points[:, 0], points[:, 1]
    inside = np.zeros(len(points), dtype=bool)
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0), strict=True):
        crosses = (y0 > y) != (y1 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (x < at)
    return inside


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Counter-clockwise convex hull of (N, 2) points (monotone chain)."""
    pts = sorted({(float(x), float(y)) for x, y in points})
    if len(pts) < 3:
        return np.array(pts, dtype=float)

    def half(seq: list[tuple[float, float]]) -> list[tuple[float, float]]:
        out: list[tuple[float, float]] = []
        for p in seq:
            while (
                len(out) >= 2
                and cross2(np.subtract(out[-1], out[-2]), np.subtract(p, out[-2])) <= EPS
            ):
                out.pop()
            out.append(p)
        return out

    lower, upper = half(pts), half(pts[::-1])
    return np.array(lower[:-1] + upper[:-1], dtype=float)


def rasterise(grid: Grid, poly: np.ndarray) -> np.ndarray:
    """Cells of ``grid`` whose centres lie inside ``poly``."""
    mask = np.zeros(grid.shape, dtype=bool)
    lo, hi = poly.min(axis=0), poly.max(axis=0)
    rows, cols = grid.shape
    b = grid.bounds
    j0 = max(int(np.floor((lo[0] - b.x0) / grid.res)), 0)
    j1 = min(int(np.ceil((hi[0] - b.x0) / grid.res)), cols - 1)
    i0 = max(int(np.floor((lo[1] - b.y0) / grid.res)), 0)
    i1 = min(int(np.ceil((hi[1] - b.y0) / grid.res)), rows - 1)
    if i1 < i0 or j1 < j0:
        return mask
    ii, jj = np.mgrid[i0 : i1 + 1, j0 : j1 + 1]
    centres = np.stack([b.x0 + jj.ravel() * grid.res, b.y0 + ii.ravel() * grid.res], axis=1)
    mask[i0 : i1 + 1, j0 : j1 + 1] = contains(poly, centres).reshape(ii.shape)
    return mask
