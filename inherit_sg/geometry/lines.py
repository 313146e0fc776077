"""Rectilinear line regularisation of a region's boundary (paper §III-C, step 2).

Boundaries are measured in the floor's dominant wall frame (the angle of most wall
edges, modulo 90°). The left/right extent of every row and the bottom/top extent of
every column are fitted with piecewise-constant runs: jitter below a tolerance
collapses to one straight line and real corners (steps larger than the tolerance that
last at least ``min_run`` cells) survive.
"""

from __future__ import annotations

import math

import numpy as np

OUTER_Q = 0.2  # quantile of a run's extents used for its straight boundary


def _alignment(r: np.ndarray, c: np.ndarray, theta: float) -> float:
    """How sharply obstacle cells pile up along lines at ``theta`` and ``theta + 90°``."""
    ct, st = math.cos(theta), math.sin(theta)
    score = 0.0
    for u in (c * ct + r * st, -c * st + r * ct):
        hist = np.bincount(np.rint(u - u.min()).astype(np.int64))
        score += float(np.dot(hist, hist))
    return score


def dominant_angle(occupied: np.ndarray, snap_deg: float = 1.5, max_cells: int = 20000) -> float:
    """Dominant wall direction in radians, in ``[-pi/4, pi/4)`` (0 for axis-aligned).

    Walls are straight runs of obstacle cells: projected on the axis across them, their
    cells pile into few bins. The angle maximising that pile-up (coarse 1° search, then
    0.1°) wins.
    """
    r, c = np.nonzero(occupied)
    if r.size < 10:
        return 0.0
    if r.size > max_cells:
        pick = np.random.default_rng(0).choice(r.size, max_cells, replace=False)
        r, c = r[pick], c[pick]
    r, c = r.astype(np.float64), c.astype(np.float64)
    coarse = np.arange(-45.0, 45.0, 1.0)
    best = float(coarse[int(np.argmax([_alignment(r, c, math.radians(a)) for a in coarse]))])
    fine = np.arange(best - 1.0, best + 1.0, 0.1)
    deg = float(fine[int(np.argmax([_alignment(r, c, math.radians(a)) for a in fine]))])
    deg = (deg + 45.0) % 90.0 - 45.0
    return 0.0 if abs(deg) < snap_deg else math.radians(deg)


def fit_runs(values: np.ndarray, tol: float, min_run: int, q: float = 0.5) -> np.ndarray:
    """Piecewise-constant fit: runs spanning at most ``tol``, each at least ``min_run``
    long (shorter runs join the neighbour with the closer level); a run's level is the
    ``q`` quantile of its values (0.5: median)."""
    n = len(values)
    if n == 0:
        return values.astype(np.float64)
    runs: list[list[int]] = []
    i = 0
    while i < n:
        lo = hi = float(values[i])
        j = i + 1
        while j < n and max(hi, values[j]) - min(lo, values[j]) <= tol:
            lo, hi = min(lo, float(values[j])), max(hi, float(values[j]))
            j += 1
        runs.append([i, j])
        i = j
    while len(runs) > 1:
        lengths = [b - a for a, b in runs]
        k = int(np.argmin(lengths))
        if lengths[k] >= min_run:
            break
        level = float(np.median(values[runs[k][0] : runs[k][1]]))
        options = [
            (abs(float(np.median(values[runs[t][0] : runs[t][1]])) - level), t)
            for t in (k - 1, k + 1)
            if 0 <= t < len(runs)
        ]
        t = min(options)[1]
        a, b = min(runs[k][0], runs[t][0]), max(runs[k][1], runs[t][1])
        runs[min(k, t)] = [a, b]
        del runs[max(k, t)]
    out = np.empty(n, dtype=np.float64)
    for a, b in runs:
        out[a:b] = np.quantile(values[a:b], q)
    return out


def _profile(key: np.ndarray, val: np.ndarray, size: int) -> tuple[np.ndarray, np.ndarray]:
    lo = np.full(size, np.inf)
    hi = np.full(size, -np.inf)
    np.minimum.at(lo, key, val)
    np.maximum.at(hi, key, val)
    ok = np.isfinite(lo)
    idx = np.arange(size)
    lo = np.interp(idx, idx[ok], lo[ok])
    hi = np.interp(idx, idx[ok], hi[ok])
    return lo, hi


def regularise(mask: np.ndarray, angle: float, tol: float, min_run: int) -> np.ndarray:
    """Rectilinear version of ``mask`` in the frame rotated by ``angle`` (cells units).

    The result stays inside the mask's bounding box grown by ``tol`` cells; interior
    holes are filled.
    """
    r, c = np.nonzero(mask)
    if r.size == 0:
        return mask.copy()
    ca, sa = math.cos(angle), math.sin(angle)
    u = c * ca + r * sa
    v = -c * sa + r * ca
    u0, v0 = np.floor(u.min()), np.floor(v.min())
    iu = np.rint(u - u0).astype(np.int64)
    iv = np.rint(v - v0).astype(np.int64)
    nu, nv = int(iu.max()) + 1, int(iv.max()) + 1
    u_lo, u_hi = _profile(iv, iu, nv)
    v_lo, v_hi = _profile(iu, iv, nu)
    # Outer quantiles: a boundary is pulled out to where most rows reach (the wall),
    # not to the median of ragged rows.
    u_lo, u_hi = fit_runs(u_lo, tol, min_run, OUTER_Q), fit_runs(u_hi, tol, min_run, 1 - OUTER_Q)
    v_lo, v_hi = fit_runs(v_lo, tol, min_run, OUTER_Q), fit_runs(v_hi, tol, min_run, 1 - OUTER_Q)
    g = math.ceil(tol) + 1
    h, w = mask.shape
    r0, r1 = max(0, int(r.min()) - g), min(h, int(r.max()) + g + 1)
    c0, c1 = max(0, int(c.min()) - g), min(w, int(c.max()) + g + 1)
    rr, cc = np.mgrid[r0:r1, c0:c1]
    ju = np.rint(cc * ca + rr * sa - u0).astype(np.int64)
    jv = np.rint(-cc * sa + rr * ca - v0).astype(np.int64)
    inside = (ju >= 0) & (ju < nu) & (jv >= 0) & (jv < nv)
    jus, jvs = np.clip(ju, 0, nu - 1), np.clip(jv, 0, nv - 1)
    inside &= (ju >= np.rint(u_lo[jvs])) & (ju <= np.rint(u_hi[jvs]))
    inside &= (jv >= np.rint(v_lo[jus])) & (jv <= np.rint(v_hi[jus]))
    out = np.zeros_like(mask, dtype=bool)
    out[r0:r1, c0:c1] = inside
    return out
