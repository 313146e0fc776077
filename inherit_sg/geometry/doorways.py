"""Is a narrow passage a doorway? Evidence gathered around its narrowest point.

Geometry alone cannot tell a doorway from a gap between two wardrobes or a gap
between an armchair and a patch of never-observed floor. In order:

1. Open above (rays crossed the band above door height there, and no surface was ever
   seen in it nearby): a gap between furniture, not a doorway.
2. A lintel (a surface seen above door height) or a known door nearby: a doorway.
3. Otherwise both sides of the passage must be observed walls (jambs): obstacles that
   belong to a structure at least ``min_wall`` long. If one side is unobserved space or
   a small free-standing object (a plant, a lamp), it is not a doorway.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np
from scipy import ndimage as ndi


@dataclass(frozen=True)
class DoorEvidence:
    """Per-cell evidence for :meth:`is_doorway` (any part may be missing)."""

    open_above: np.ndarray | None  # bool: open above door height, pooled around the cell
    near_lintel: np.ndarray | None  # bool: a lintel or a known door within reach
    occupied: np.ndarray | None  # bool: observed obstacles
    nearest: np.ndarray | None  # (2, H, W): row, col of each cell's nearest barrier
    space: np.ndarray  # bool: the free space being segmented
    walls: np.ndarray | None = None  # bool: obstacles that are part of long structures

    @classmethod
    def build(
        cls,
        space: np.ndarray,
        cut: np.ndarray,
        nearest: np.ndarray | None,
        open_above: np.ndarray | None,
        lintel: np.ndarray | None,
        occupied: np.ndarray | None,
        radius_cells: int,
        min_wall_cells: float = 20.0,
    ) -> DoorEvidence:
        """Pool the raw layers (``cut``: discs of known doors)."""
        rad = max(1, radius_cells)
        disk = np.hypot(*np.mgrid[-rad : rad + 1, -rad : rad + 1]) <= rad
        above = cut if lintel is None else (lintel | cut)
        near = cv2.dilate(above.astype(np.uint8), disk.astype(np.uint8)) > 0
        pooled = None
        if open_above is not None:
            share = ndi.uniform_filter(open_above.astype(np.float32), size=2 * rad + 1)
            pooled = (share >= 0.5) & ~near
        walls = None
        if occupied is not None:
            comp, n = ndi.label(occupied, structure=np.ones((3, 3), dtype=bool))
            long = np.zeros(n + 1, dtype=bool)
            for k, box in enumerate(ndi.find_objects(comp), start=1):
                if box is not None:
                    long[k] = max(s.stop - s.start for s in box) >= min_wall_cells
            walls = long[comp]
        return cls(pooled, near, occupied, nearest, space, walls)

    def is_doorway(self, row: float, col: float) -> bool:
        """Whether the passage whose narrowest point is at (row, col) is a doorway."""
        h, w = self.space.shape
        r = min(max(int(row + 0.5), 0), h - 1)
        c = min(max(int(col + 0.5), 0), w - 1)
        if self.open_above is not None and self.open_above[r, c]:
            return False
        if self.near_lintel is not None and self.near_lintel[r, c]:
            return True
        if self.occupied is None or self.nearest is None:
            return True
        qr, qc = int(self.nearest[0, r, c]), int(self.nearest[1, r, c])
        if not self._solid(qr, qc):
            return False
        return self._opposite_solid(r, c, qr, qc)

    def _solid(self, r: int, c: int) -> bool:
        assert self.occupied is not None
        h, w = self.occupied.shape
        return bool(
            self.occupied[max(0, r - 1) : min(h, r + 2), max(0, c - 1) : min(w, c + 2)].any()
        )

    def _opposite_solid(self, r: int, c: int, qr: int, qc: int) -> bool:
        """Walk from (r, c) away from its nearest barrier to the first non-free cell."""
        d = math.hypot(r - qr, c - qc)
        if d == 0:
            return True
        dr, dc = (r - qr) / d, (c - qc) / d
        h, w = self.space.shape
        k = 0.5
        while k <= 2.0 * d + 3.0:
            rr, cc = round(r + dr * k), round(c + dc * k)
            if not (0 <= rr < h and 0 <= cc < w):
                return False
            if not self.space[rr, cc]:
                return self._solid(rr, cc)
            k += 0.5
        return False
