"""Shortest walkable paths on one storey: an occupancy grid of walls (with door gaps),
furniture, stairs and stairwells, searched with Dijkstra (scipy.sparse.csgraph)."""

from __future__ import annotations

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import dijkstra

from inherit_sg.ingest.synthetic.geom import Rect, subtract_intervals
from inherit_sg.ingest.synthetic.grid import Grid, components, free_space
from inherit_sg.ingest.synthetic.placement import Placed
from inherit_sg.ingest.synthetic.plan import WALL_T, FloorPlan, HousePlan
from inherit_sg.ingest.synthetic.structure import JAMB

RADIUS = 0.2  # body radius kept clear of obstacles
BODY = 1.8
RES = 0.05
TALL_M = 1.3  # furniture taller than this hides what stands behind it from a standing eye


def wall_rects(floor: FloorPlan) -> list[Rect]:
    """Plan rectangles of the walls of ``floor`` at walking height (door gaps left open)."""
    out = []
    t = WALL_T / 2
    for wall in floor.walls:
        gaps = [
            (d.lo + JAMB, d.hi - JAMB)
            for d in floor.doors
            if d.axis == wall.axis and abs(d.coord - wall.coord) < 1e-6
        ]
        for a, b in subtract_intervals(wall.lo - t, wall.hi + t, gaps):
            if wall.axis == "x":
                out.append(Rect(a, wall.coord - t, b, wall.coord + t))
            else:
                out.append(Rect(wall.coord - t, a, wall.coord + t, b))
    return out


class FloorMap:
    """Free space and shortest paths of one storey."""

    def __init__(self, plan: HousePlan, floor: FloorPlan, objects: list[Placed]) -> None:
        self.floor = floor
        self.grid = Grid(plan.footprint.grown(0.3), RES)
        obstacles = wall_rects(floor) + list(floor.holes)
        obstacles += [s.rect for s in plan.stairs if s.from_floor == floor.index]
        # what hides things from a standing eye: walls and furniture above TALL_M
        self.sight_blocked = np.zeros(self.grid.shape, dtype=bool)
        for rect in obstacles:
            self.grid.fill(self.sight_blocked, rect)
        for obj in objects:
            if obj.floor != floor.index or obj.flat or obj.support is not None:
                continue
            if obj.label in ("door", "window", "stairs"):
                continue
            if obj.z - floor.z < BODY:
                obstacles.append(obj.footprint)
                if obj.top - floor.z > TALL_M:
                    self.grid.fill(self.sight_blocked, obj.footprint)
        outside = [
            Rect(self.grid.bounds.x0, self.grid.bounds.y0, plan.footprint.x0, self.grid.bounds.y1),
            Rect(plan.footprint.x1, self.grid.bounds.y0, self.grid.bounds.x1, self.grid.bounds.y1),
            Rect(self.grid.bounds.x0, self.grid.bounds.y0, self.grid.bounds.x1, plan.footprint.y0),
            Rect(self.grid.bounds.x0, plan.footprint.y1, self.grid.bounds.x1, self.grid.bounds.y1),
        ]
        self.free = free_space(self.grid, obstacles + outside, RADIUS)
        # every footprint and wall: what surfaces (and what hangs on walls) stand on
        self.occupied = np.zeros(self.grid.shape, dtype=bool)
        for rect in obstacles:
            self.grid.fill(self.occupied, rect)
        blocked = ~self.free
        self.clearance = self.grid.clearance(blocked)
        self.labels = components(self.free)
        self._graph, self._index = self._build_graph()

    def _build_graph(self) -> tuple[csr_matrix, np.ndarray]:
        rows, cols = self.free.shape
        index = np.full(self.free.shape, -1, dtype=np.int64)
        cells = np.flatnonzero(self.free)
        index.flat[cells] = np.arange(len(cells))
        # Cost grows near obstacles so paths keep to the middle of rooms and doorways.
        penalty = 1.0 + 3.0 * np.clip(0.6 - self.clearance, 0.0, None)
        src, dst, cost = [], [], []
        for di, dj in ((0, 1), (1, 0), (1, 1), (1, -1)):
            a_rows, b_rows = slice(0, rows - di), slice(di, rows)
            a_cols = (
                slice(0, cols - 1) if dj == 1 else slice(1, cols) if dj == -1 else slice(0, cols)
            )
            b_cols = (
                slice(1, cols) if dj == 1 else slice(0, cols - 1) if dj == -1 else slice(0, cols)
            )
            a, b = index[a_rows, a_cols], index[b_rows, b_cols]
            ok = (a >= 0) & (b >= 0)
            both = np.maximum(penalty[a_rows, a_cols], penalty[b_rows, b_cols])
            src.append(a[ok])
            dst.append(b[ok])
            cost.append(float(np.hypot(di, dj)) * both[ok])
        s, d, c = np.concatenate(src), np.concatenate(dst), np.concatenate(cost)
        n = len(cells)
        graph = csr_matrix(
            (np.concatenate([c, c]), (np.concatenate([s, d]), np.concatenate([d, s]))), shape=(n, n)
        )
        return graph, index

    def snap(self, x: float, y: float) -> tuple[int, int]:
        """The free cell nearest to a plan point."""
        i, j = self.grid.cell(x, y)
        if self.free[i, j]:
            return i, j
        free = np.argwhere(self.free)
        k = int(np.argmin((free[:, 0] - i) ** 2 + (free[:, 1] - j) ** 2))
        return int(free[k, 0]), int(free[k, 1])

    def search(self, start: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
        """Path costs (in grid steps, inf if unreachable) and predecessors from ``start``."""
        dist, pred = dijkstra(
            self._graph, indices=int(self._index[start]), return_predecessors=True
        )
        return np.asarray(dist), np.asarray(pred)

    def cost_to(self, dist: np.ndarray, cell: tuple[int, int]) -> float:
        """Cost of reaching ``cell`` in a :meth:`search` result."""
        k = int(self._index[cell])
        return float(dist[k]) if k >= 0 else float("inf")

    def path(self, pred: np.ndarray, goal: tuple[int, int]) -> list[tuple[float, float]]:
        """Plan points from the search start to ``goal`` (empty if unreachable)."""
        flat_cells = np.flatnonzero(self.free)
        k = int(self._index[goal])
        if k < 0:
            return []
        chain = [k]
        while pred[chain[-1]] >= 0:
            chain.append(int(pred[chain[-1]]))
        cols = self.free.shape[1]
        pts = [self.grid.point(*divmod(int(flat_cells[c]), cols)) for c in reversed(chain)]
        return self._shortcut(pts)

    def line_free(self, a: tuple[float, float], b: tuple[float, float]) -> bool:
        """Whether the straight segment between two plan points stays in free space."""
        n = max(2, int(np.hypot(b[0] - a[0], b[1] - a[1]) / (RES / 2)))
        s = np.linspace(0.0, 1.0, n)
        g = self.grid
        i = np.round((a[1] + s * (b[1] - a[1]) - g.bounds.y0) / g.res).astype(np.int64)
        j = np.round((a[0] + s * (b[0] - a[0]) - g.bounds.x0) / g.res).astype(np.int64)
        rows, cols = self.free.shape
        if i.min() < 0 or j.min() < 0 or i.max() >= rows or j.max() >= cols:
            return False
        return bool(self.free[i, j].all())

    def _shortcut(self, pts: list[tuple[float, float]]) -> list[tuple[float, float]]:
        """Drop path vertices while the straight line to later ones stays free."""
        if len(pts) <= 2:
            return pts
        out = [pts[0]]
        i = 0
        while i < len(pts) - 1:
            j = i + 1
            while j + 1 < len(pts) and self.line_free(pts[i], pts[j + 1]):
                j += 1
            out.append(pts[j])
            i = j
        return out
