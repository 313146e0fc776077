"""An exploration walk through an MP3D house, deterministic by seed.

Free space per level is the regions' area (plus a margin that bridges the seams between
neighbouring regions) minus walls at walking height and furniture footprints, shrunk by
the body radius. The walker starts in the entryway (or the largest region), visits every
region nearest-first along shortest paths (the synthetic planner's Dijkstra search and
path shortcutting), stops at a roomy spot in each one and looks around in place; a region
it cannot enter is looked into from the nearest reachable spot. A region that one stop
does not see (a bed or sofa hides what stands behind it, an L-shaped room has a corner)
gets further stops (:mod:`inherit_sg.ingest.view_coverage`), and every other frame of a look-around
tilts up to take in what hangs high on the walls and from the ceiling. The synthetic walker's
turning and stepping rules apply: a frame every 0.5 m and every 30° of turning. Levels
are walked lowest first; the camera moves between levels without stairs in between.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import ndimage

from inherit_sg.ingest.mp3d_polygons import rasterise
from inherit_sg.ingest.mp3d_space import Level, LevelSpace
from inherit_sg.ingest.mp3d_walls import WALL_T, WallSpan
from inherit_sg.ingest.synthetic.grid import Grid, components
from inherit_sg.ingest.synthetic.planner import BODY, RADIUS, FloorMap
from inherit_sg.ingest.synthetic.trajectory import (
    Trajectory,
    _Walker,
    _wrap,
    camera_pose,
)
from inherit_sg.ingest.view_coverage import coverage_stops

SEAM = 0.3  # free space reaches this far outside the regions (across wall seams)
START_TYPES = ("entryway", "hallway", "living room")
LOOK_UP = math.radians(20.0)  # pitch above the horizon of the look-around's upward frames


class LevelMap(FloorMap):
    """The synthetic planner's shortest paths over a precomputed free-space mask."""

    def __init__(self, grid: Grid, free: np.ndarray) -> None:
        # FloorMap's own constructor derives free space from a generated plan; the
        # search, path and shortcut methods only need these attributes.
        self.grid = grid
        self.free = free
        self.clearance = grid.clearance(~free)
        self.labels = components(free)
        self._graph, self._index = self._build_graph()


def wall_cells(space: LevelSpace, walls: list[WallSpan]) -> np.ndarray:
    """Cells of ``space`` covered by the walls of its regions at walking height."""
    g = space.grid
    blocked = np.zeros(g.shape, dtype=bool)
    room_ids = set(space.room_ids)
    pad = g.res
    for w in walls:
        if w.room_id not in room_ids or w.z0 > space.level.z + BODY:
            continue
        d = (w.b - w.a) / max(float(np.hypot(*(w.b - w.a))), 1e-9)
        a, b = w.a - d * pad, w.b + d * pad
        lo, hi = -w.normal * pad, w.normal * (WALL_T + pad)
        blocked |= rasterise(g, np.array([a + lo, b + lo, b + hi, a + hi]))
    return blocked


def free_space(space: LevelSpace, walls: list[WallSpan]) -> np.ndarray:
    """Cells of ``space`` where a walking person fits (see the module docstring)."""
    g = space.grid
    inside = ndimage.binary_dilation(
        space.rooms >= 0, structure=np.ones((3, 3), bool), iterations=round(SEAM / g.res)
    )
    blocked = space.furniture | ~inside | wall_cells(space, walls)
    blocked[0, :] = blocked[-1, :] = blocked[:, 0] = blocked[:, -1] = True
    return g.clearance(blocked) > RADIUS


class _HouseWalker(_Walker):
    """The synthetic walker's turning, stepping and looking, over MP3D levels; every
    other look-around frame tilts up (:data:`LOOK_UP`)."""

    look_up = LOOK_UP

    def __init__(self, rng: np.random.Generator) -> None:
        # _Walker's constructor takes a generated plan, used only by its emit().
        self.rng = rng
        self.traj = Trajectory()
        self.eye = float(rng.uniform(1.3, 1.5))
        self.pitch = math.radians(float(rng.uniform(10.0, 15.0)))
        self.x = self.y = self.yaw = 0.0
        self.floor = 0
        self.space: LevelSpace | None = None

    def emit(self, activity: str, z: float | None = None) -> None:
        assert self.space is not None
        base = self.space.level.z if z is None else z
        height = base + self.eye + float(self.rng.normal(0.0, 0.008))
        pitch = self.pitch + math.radians(float(self.rng.normal(0.0, 1.0)))
        yaw = self.yaw + math.radians(float(self.rng.normal(0.0, 1.0)))
        self.traj.poses.append(camera_pose(self.x, self.y, height, yaw, pitch))
        self.traj.floors.append(self.floor)
        self.traj.rooms.append(self.space.room_at(self.x, self.y))
        self.traj.activity.append(activity)


def _viewpoint(fm: LevelMap, room: np.ndarray, reach: np.ndarray) -> tuple[tuple[int, int], bool]:
    """A roomy reachable cell of the region mask ``room`` near its middle, or (when none
    is reachable) the reachable cell nearest to the region; and whether it is inside."""
    g = fm.grid
    cells = np.argwhere(room & reach)
    if len(cells) == 0:
        gap = ndimage.distance_transform_edt(~room)
        gap = np.where(reach, gap, np.inf)
        i, j = np.unravel_index(int(np.argmin(gap)), gap.shape)
        return (int(i), int(j)), False
    centre = np.argwhere(room).mean(axis=0)
    size = max(np.ptp(np.argwhere(room), axis=0).max(), 1) * g.res
    off = np.hypot(*(cells - centre).T) * g.res / size
    score = np.minimum(fm.clearance[cells[:, 0], cells[:, 1]], 0.9) - 0.6 * off
    best = cells[int(np.argmax(score))]
    return (int(best[0]), int(best[1])), True


def _start_room(space: LevelSpace) -> int:
    types = [r.type for r in space.level.rooms]
    for wanted in START_TYPES:
        if wanted in types:
            return types.index(wanted)
    return int(np.argmax([(space.rooms == k).sum() for k in range(len(types))]))


def _tour_level(
    w: _HouseWalker, space: LevelSpace, fm: LevelMap, sight_blocked: np.ndarray
) -> None:
    masks = [space.rooms == k for k in range(len(space.room_ids))]
    free_any = fm.free if fm.free.any() else np.ones_like(fm.free)
    start, _ = _viewpoint(fm, masks[_start_room(space)], free_any)
    reach = fm.labels == fm.labels[start] if fm.free[start] else fm.free
    w.x, w.y = fm.grid.point(*start)
    targets = {k: _viewpoint(fm, m, reach) for k, m in enumerate(masks) if m.any()}
    w.emit("walk")
    while targets:
        dist, pred = fm.search(fm.snap(w.x, w.y))
        k = min(sorted(targets), key=lambda r: fm.cost_to(dist, targets[r][0]))
        goal, inside = targets.pop(k)
        if not inside:  # look into the region we could not enter
            w.walk(fm.path(pred, goal))
            cy, cx = np.argwhere(masks[k]).mean(axis=0)
            x, y = fm.grid.point(0, 0)
            w.turn_to(math.atan2(y + cy * fm.grid.res - w.y, x + cx * fm.grid.res - w.x))
            w.look_around()
            continue
        stops = coverage_stops(masks[k], reach, sight_blocked, fm.grid.res, goal)
        while stops:  # the region's stops, nearest first
            stop = min(stops, key=lambda c: fm.cost_to(dist, c))
            stops.remove(stop)
            w.walk(fm.path(pred, stop))
            w.look_around()
            dist, pred = fm.search(fm.snap(w.x, w.y))


def plan_house_walk(
    levels: list[Level],
    spaces: list[LevelSpace],
    walls: list[WallSpan],
    rng: np.random.Generator,
) -> Trajectory:
    """The walk through every region of every level (see the module docstring)."""
    w = _HouseWalker(rng)
    w.yaw = _wrap(float(rng.uniform(-math.pi, math.pi)))
    for level, space in zip(levels, spaces, strict=True):
        w.floor, w.space = level.index, space
        fm = LevelMap(space.grid, free_space(space, walls))
        _tour_level(w, space, fm, wall_cells(space, walls) | space.furniture)
    return w.traj
