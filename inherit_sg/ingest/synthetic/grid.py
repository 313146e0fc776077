"""A 2D occupancy grid over a floor plan, shared by the furnisher's walkability check
and the trajectory planner."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from inherit_sg.ingest.synthetic.geom import Rect


@dataclass(frozen=True)
class Grid:
    """A regular grid of square cells covering ``bounds``; cell (i, j) is row y, column x."""

    bounds: Rect
    res: float

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols)."""
        return (
            int(np.ceil(self.bounds.h / self.res)) + 1,
            int(np.ceil(self.bounds.w / self.res)) + 1,
        )

    def cell(self, x: float, y: float) -> tuple[int, int]:
        """Index of the cell containing the point (clamped to the grid)."""
        rows, cols = self.shape
        i = int(np.clip(round((y - self.bounds.y0) / self.res), 0, rows - 1))
        j = int(np.clip(round((x - self.bounds.x0) / self.res), 0, cols - 1))
        return i, j

    def point(self, i: int, j: int) -> tuple[float, float]:
        """Plan coordinates of a cell centre."""
        return self.bounds.x0 + j * self.res, self.bounds.y0 + i * self.res

    def fill(self, mask: np.ndarray, rect: Rect, value: bool = True) -> None:
        """Set the cells whose centres lie inside ``rect``."""
        rows, cols = self.shape
        j0 = max(int(np.ceil((rect.x0 - self.bounds.x0) / self.res - 1e-9)), 0)
        j1 = min(int(np.floor((rect.x1 - self.bounds.x0) / self.res + 1e-9)), cols - 1)
        i0 = max(int(np.ceil((rect.y0 - self.bounds.y0) / self.res - 1e-9)), 0)
        i1 = min(int(np.floor((rect.y1 - self.bounds.y0) / self.res + 1e-9)), rows - 1)
        if i1 >= i0 and j1 >= j0:
            mask[i0 : i1 + 1, j0 : j1 + 1] = value

    def clearance(self, blocked: np.ndarray) -> np.ndarray:
        """Distance in metres from each cell to the nearest blocked cell."""
        return np.asarray(ndimage.distance_transform_edt(~blocked), dtype=np.float64) * self.res


def free_space(grid: Grid, obstacles: list[Rect], radius: float) -> np.ndarray:
    """Cells a disc of ``radius`` can stand on: inside the grid, clear of ``obstacles``."""
    blocked = np.zeros(grid.shape, dtype=bool)
    for rect in obstacles:
        grid.fill(blocked, rect)
    blocked[0, :] = blocked[-1, :] = blocked[:, 0] = blocked[:, -1] = True
    return grid.clearance(blocked) > radius


def components(free: np.ndarray) -> np.ndarray:
    """8-connected component labels of free cells (0 = blocked)."""
    labels, _ = ndimage.label(free, structure=np.ones((3, 3), dtype=int))
    return np.asarray(labels)
