"""Label-image helpers: catchment basins by steepest ascent, region adjacency with
saddle heights, union-find relabelling. Pure numpy on 2D arrays."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage as ndi

_OFFSETS = ((-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1))


def ascent_basins(height: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Label every masked cell with the local maximum its steepest ascent path reaches.

    This is the watershed partition of ``-height`` (catchment basins of its minima),
    computed without a priority queue: each cell points to its highest 8-neighbour
    inside ``mask`` when that is higher than itself, and pointer jumping finds the roots.
    Returns int32 labels 1..n (0 outside ``mask``).
    """
    h, w = height.shape
    ramp = np.arange(h * w, dtype=np.float64).reshape(h, w) * (1e-9 / max(1, h * w))
    val = np.where(mask, height.astype(np.float64) + ramp, -np.inf)
    padded = np.pad(val, 1, constant_values=-np.inf)
    best = val.copy()
    ptr = np.arange(h * w, dtype=np.int64).reshape(h, w)
    rows, cols = np.indices((h, w))
    for dr, dc in _OFFSETS:
        nb = padded[1 + dr : 1 + dr + h, 1 + dc : 1 + dc + w]
        better = nb > best
        best = np.where(better, nb, best)
        ptr = np.where(better, (rows + dr) * w + (cols + dc), ptr)
    flat = ptr.reshape(-1)
    while True:
        nxt = flat[flat]
        if np.array_equal(nxt, flat):
            break
        flat = nxt
    roots = np.zeros(h * w, dtype=np.int32)
    root_ids = np.flatnonzero((flat == np.arange(h * w)) & mask.reshape(-1))
    roots[root_ids] = np.arange(1, len(root_ids) + 1, dtype=np.int32)
    labels = roots[flat].reshape(h, w)
    labels[~mask] = 0
    return labels


@dataclass(frozen=True)
class Adjacency:
    """Touching label pairs ``a < b`` with the highest ``value`` on their border.

    ``value`` of a border is the smaller of the two cells' values; ``where`` holds the
    (row, col) of the cell pair centre reaching it and ``length`` the number of
    touching cell pairs.
    """

    a: np.ndarray
    b: np.ndarray
    value: np.ndarray
    where: np.ndarray  # (K, 2) float rows, cols
    length: np.ndarray


def adjacency(labels: np.ndarray, value: np.ndarray) -> Adjacency:
    """Region adjacency over 4-neighbour borders of a label image."""
    parts = []
    for la, lb, va, vb, shift in (
        (labels[:, :-1], labels[:, 1:], value[:, :-1], value[:, 1:], (0.0, 0.5)),
        (labels[:-1, :], labels[1:, :], value[:-1, :], value[1:, :], (0.5, 0.0)),
    ):
        m = (la != lb) & (la > 0) & (lb > 0)
        r, c = np.nonzero(m)
        a, b = la[m], lb[m]
        parts.append(
            (
                np.minimum(a, b),
                np.maximum(a, b),
                np.minimum(va[m], vb[m]),
                r + shift[0],
                c + shift[1],
            )
        )
    a = np.concatenate([p[0] for p in parts]).astype(np.int64)
    b = np.concatenate([p[1] for p in parts]).astype(np.int64)
    v = np.concatenate([p[2] for p in parts]).astype(np.float64)
    rr = np.concatenate([p[3] for p in parts])
    cc = np.concatenate([p[4] for p in parts])
    if a.size == 0:
        empty = np.zeros(0, dtype=np.int64)
        return Adjacency(empty, empty, np.zeros(0), np.zeros((0, 2)), empty)
    key = a * (int(b.max()) + 1) + b
    order = np.lexsort((v, key))
    key, a, b, v, rr, cc = key[order], a[order], b[order], v[order], rr[order], cc[order]
    last = np.flatnonzero(np.r_[key[1:] != key[:-1], True])
    first = np.r_[0, last[:-1] + 1]
    return Adjacency(
        a=a[last],
        b=b[last],
        value=v[last],
        where=np.stack([rr[last], cc[last]], axis=1),
        length=last - first + 1,
    )


class UnionFind:
    """Disjoint sets over integer labels ``0..n`` with per-set peak values."""

    def __init__(self, peaks: np.ndarray) -> None:
        self.parent = np.arange(len(peaks), dtype=np.int64)
        self.peak = peaks.astype(np.float64).copy()

    def find(self, x: int) -> int:
        """Root of ``x`` (with path halving)."""
        p = self.parent
        while p[x] != x:
            p[x] = p[p[x]]
            x = int(p[x])
        return x

    def union(self, x: int, y: int) -> int:
        """Join the sets of ``x`` and ``y``; the root with the higher peak survives."""
        rx, ry = self.find(x), self.find(y)
        if rx == ry:
            return rx
        if self.peak[rx] < self.peak[ry]:
            rx, ry = ry, rx
        self.parent[ry] = rx
        return rx

    def relabel(self, labels: np.ndarray) -> np.ndarray:
        """Map a label image through the sets and renumber roots 1..k (0 stays 0)."""
        roots = np.array([self.find(i) for i in range(len(self.parent))], dtype=np.int64)
        roots[0] = 0
        uniq = np.unique(roots[roots > 0])
        lut = np.zeros(len(self.parent), dtype=np.int32)
        lut[uniq] = np.arange(1, len(uniq) + 1, dtype=np.int32)
        return lut[roots][labels]


def region_peaks(labels: np.ndarray, value: np.ndarray, n: int) -> np.ndarray:
    """Maximum of ``value`` in every label 0..n (0 for empty labels)."""
    peaks = np.zeros(n + 1, dtype=np.float64)
    if n > 0:
        found = ndi.maximum(value, labels=labels, index=np.arange(1, n + 1))
        peaks[1:] = np.nan_to_num(np.asarray(found, dtype=np.float64), nan=0.0)
    return np.maximum(peaks, 0.0)
