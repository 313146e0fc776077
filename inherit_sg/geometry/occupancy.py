"""Log-odds BEV occupancy grid of one floor that grows as the robot explores.

``logodds[r, c]`` covers world x in ``[origin_x + c*res, origin_x + (c+1)*res)`` and y in
``[origin_y + r*res, ...)``, the same layout as :class:`~inherit_sg.model.RoomMask`.
The grid only grows by whole cells so every layer aligned with it can be padded.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from inherit_sg.errors import FrameError

# The widest a floor's occupancy grid may grow (metres on a side): every layer aligned with
# it (room ids, lintel counts) is a dense array of this size.
MAX_EXTENT_M = 300.0


@dataclass(frozen=True)
class LogOddsParams:
    """Increments, clamps and classification thresholds of the log-odds update."""

    hit: float = 0.85
    miss: float = -0.4
    lo: float = -2.0
    hi: float = 3.5
    occupied: float = 0.6
    free: float = -0.6


class OccupancyGrid:
    """A growing 2D log-odds grid (free < 0 < occupied; 0 = unknown)."""

    def __init__(
        self,
        resolution: float,
        params: LogOddsParams | None = None,
        margin: float = 2.0,
    ) -> None:
        self.resolution = float(resolution)
        self.params = params or LogOddsParams()
        self.margin_cells = max(1, math.ceil(margin / self.resolution))
        self.origin_x = 0.0
        self.origin_y = 0.0
        self.logodds = np.zeros((0, 0), dtype=np.float32)
        # Scans that saw a surface in the lintel band (above doors, below the ceiling),
        # and scans whose rays crossed that band there (open above).
        self.lintel_hits = np.zeros((0, 0), dtype=np.uint16)
        self.lintel_open = np.zeros((0, 0), dtype=np.uint16)
        self.updates = 0  # number of integrated scans

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols)."""
        return (int(self.logodds.shape[0]), int(self.logodds.shape[1]))

    @property
    def empty(self) -> bool:
        """True before the first cell was allocated."""
        return self.logodds.size == 0

    def ensure_contains(self, xmin: float, ymin: float, xmax: float, ymax: float) -> None:
        """Grow the grid (by at least the margin) so the box lies inside it; FrameError
        (nothing changed) when the grid would then span more than :data:`MAX_EXTENT_M`
        (a pose far from the rest of the walk)."""
        res = self.resolution
        lo_x, lo_y = (
            (xmin, ymin) if self.empty else (min(xmin, self.origin_x), min(ymin, self.origin_y))
        )
        h, w = self.shape
        hi_x = xmax if self.empty else max(xmax, self.origin_x + w * res)
        hi_y = ymax if self.empty else max(ymax, self.origin_y + h * res)
        span = max(hi_x - lo_x, hi_y - lo_y)
        if not math.isfinite(span) or span > MAX_EXTENT_M:
            raise FrameError(
                f"the frame would stretch a floor's occupancy grid to {span:.0f} m, beyond "
                f"{MAX_EXTENT_M:g} m: its pose lies far from the rest of the walk"
            )
        if self.empty:
            m = self.margin_cells * res
            self.origin_x = math.floor((xmin - m) / res) * res
            self.origin_y = math.floor((ymin - m) / res) * res
            w = math.ceil((xmax + m - self.origin_x) / res)
            h = math.ceil((ymax + m - self.origin_y) / res)
            self.logodds = np.zeros((h, w), dtype=np.float32)
            self.lintel_hits = np.zeros((h, w), dtype=np.uint16)
            self.lintel_open = np.zeros((h, w), dtype=np.uint16)
            return
        h, w = self.shape
        c0 = math.floor((xmin - self.origin_x) / res)
        r0 = math.floor((ymin - self.origin_y) / res)
        c1 = math.floor((xmax - self.origin_x) / res)
        r1 = math.floor((ymax - self.origin_y) / res)
        m = self.margin_cells
        left = max(0, -c0) + m if c0 < 0 else 0
        below = max(0, -r0) + m if r0 < 0 else 0
        right = c1 - w + 1 + m if c1 >= w else 0
        above = r1 - h + 1 + m if r1 >= h else 0
        if left or below or right or above:
            self.grow(below, above, left, right)

    def grow(self, below: int, above: int, left: int, right: int) -> None:
        """Pad the grid by whole cells on each side (rows below/above, cols left/right)."""
        pad = ((below, above), (left, right))
        self.logodds = np.pad(self.logodds, pad)
        self.lintel_hits = np.pad(self.lintel_hits, pad)
        self.lintel_open = np.pad(self.lintel_open, pad)
        self.origin_x -= left * self.resolution
        self.origin_y -= below * self.resolution

    def cells_of(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(rows, cols) of world points (N, 2); callers make sure they are inside."""
        inv = 1.0 / self.resolution
        cols = np.floor((xy[:, 0] - self.origin_x) * inv).astype(np.int64)
        rows = np.floor((xy[:, 1] - self.origin_y) * inv).astype(np.int64)
        return rows, cols

    def cell_center(self, row: float, col: float) -> tuple[float, float]:
        """World (x, y) of a cell centre."""
        return (
            self.origin_x + (col + 0.5) * self.resolution,
            self.origin_y + (row + 0.5) * self.resolution,
        )

    def update(
        self,
        free_flat: np.ndarray,
        hit_flat: np.ndarray,
        lintel_flat: np.ndarray | None = None,
        open_flat: np.ndarray | None = None,
        hit_weight: np.ndarray | None = None,
    ) -> None:
        """Apply one scan: cells passed by rays get a miss, cells with returns a hit
        (scaled by the largest ``hit_weight`` in the cell, default 1); lintel-band
        sightings and open-above crossings are counted per cell.

        A cell counts once per scan; a hit wins over a miss in the same scan.
        """
        p = self.params
        flat = self.logodds.reshape(-1)
        weight = np.zeros(flat.size, dtype=np.float32)
        if hit_weight is None:
            weight[hit_flat] = 1.0
        else:
            np.maximum.at(weight, hit_flat, hit_weight.astype(np.float32))
        idx_hit = np.flatnonzero(weight)
        missed = np.zeros(flat.size, dtype=bool)
        missed[free_flat] = True
        missed[idx_hit] = False
        idx_free = np.flatnonzero(missed)
        flat[idx_free] = np.maximum(flat[idx_free] + p.miss, p.lo)
        flat[idx_hit] = np.minimum(flat[idx_hit] + p.hit * weight[idx_hit], p.hi)
        for flat_idx, layer in ((lintel_flat, self.lintel_hits), (open_flat, self.lintel_open)):
            if flat_idx is not None and flat_idx.size:
                seen = np.zeros(flat.size, dtype=bool)
                seen[flat_idx] = True
                cells = np.flatnonzero(seen)
                counts = layer.reshape(-1)
                counts[cells] = np.minimum(counts[cells].astype(np.int32) + 1, 65535)
        self.updates += 1

    def free_mask(self) -> np.ndarray:
        """Cells believed free."""
        return self.logodds < self.params.free

    def occupied_mask(self) -> np.ndarray:
        """Cells believed occupied."""
        return self.logodds > self.params.occupied

    def open_above_mask(self, min_scans: int = 2) -> np.ndarray:
        """Cells where rays crossed the lintel band in at least ``min_scans`` scans and no
        surface was ever seen there (no wall above: not a doorway)."""
        return (self.lintel_open >= min_scans) & (self.lintel_hits == 0)

    def known_mask(self) -> np.ndarray:
        """Cells observed at all (free, occupied or in between)."""
        return self.logodds != 0.0
