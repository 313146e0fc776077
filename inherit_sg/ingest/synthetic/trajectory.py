"""Teleoperation-like exploration walks: every room of every storey, lowest first.

On each storey the walker goes from room to room (nearest unvisited first, along
shortest paths through doors and around furniture), stops at a roomy spot in each room,
looks around in place and glances up at the ceiling, then steps up to the walls and
furniture that the look-around saw only from afar (close looks, chosen from the plan's
occupancy alone), and finally climbs the stairs to the next storey with the camera
following the steps. Frames come about every 0.5 m of walking and every 30° of turning;
the camera looks slightly down and its yaw never jumps by more than 30°.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import pairwise

import numpy as np
from scipy import ndimage

from inherit_sg.ingest.synthetic.placement import Placed
from inherit_sg.ingest.synthetic.plan import HousePlan, RoomPlan, StairPlan
from inherit_sg.ingest.synthetic.planner import FloorMap
from inherit_sg.ingest.view_coverage import CoverageGoal, coverage_stops, sight
from inherit_sg.model import Pose

STEP = 0.5  # metres between frames while walking
TURN = math.radians(30.0)  # largest yaw change between frames
LOOK_FRAMES = 12  # frames of the in-place look-around (360°)
# The close look (a person filming a room for a scan steps up to its shelves, counters
# and walls): stops are added, from the room's reachable cells, while less than
# CLOSE.goal of the strip in front of walls and furniture (SURFACE_M deep) lies within
# CLOSE.sight_m of a stop in plain view (view_coverage); at each stop three frames face
# what it sees, CLOSE_SPREAD apart.
CLOSE = CoverageGoal(sight_m=2.0, goal=0.7, min_gain=0.12, max_stops=3)
SURFACE_M = 0.3
CLOSE_SPREAD = math.radians(30.0)
CEILING_PITCH = math.radians(65.0)  # the glance up at the ceiling above a stop


@dataclass
class Trajectory:
    """Camera poses with the storey, room and activity of each frame."""

    poses: list[Pose] = field(default_factory=list)
    floors: list[int] = field(default_factory=list)
    rooms: list[str | None] = field(default_factory=list)
    activity: list[str] = field(default_factory=list)  # walk | look | turn | stairs | glance

    def __len__(self) -> int:
        return len(self.poses)


def camera_pose(x: float, y: float, z: float, yaw: float, pitch: float) -> Pose:
    """T_world_camera for a camera at (x, y, z) heading ``yaw`` (from +x, CCW) and looking
    ``pitch`` radians below the horizon (OpenCV axes: x right, y down, z forward)."""
    forward = np.array(
        [math.cos(yaw) * math.cos(pitch), math.sin(yaw) * math.cos(pitch), -math.sin(pitch)]
    )
    right = np.array([math.sin(yaw), -math.cos(yaw), 0.0])
    down = np.cross(forward, right)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, down, forward, (x, y, z)
    return Pose.from_matrix(m)


def _wrap(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi


class _Walker:
    def __init__(self, plan: HousePlan, rng: np.random.Generator) -> None:
        self.plan = plan
        self.rng = rng
        self.traj = Trajectory()
        self.eye = float(rng.uniform(1.3, 1.5))
        self.pitch = math.radians(float(rng.uniform(10.0, 15.0)))
        self.x = self.y = self.yaw = 0.0
        self.floor = 0

    def emit(self, activity: str, z: float | None = None) -> None:
        fl = self.plan.floors[self.floor]
        height = (fl.z if z is None else z) + self.eye + float(self.rng.normal(0.0, 0.008))
        pitch = self.pitch + math.radians(float(self.rng.normal(0.0, 1.0)))
        yaw = self.yaw + math.radians(float(self.rng.normal(0.0, 1.0)))
        self.traj.poses.append(camera_pose(self.x, self.y, height, yaw, pitch))
        self.traj.floors.append(self.floor)
        room = fl.room_at(self.x, self.y) if activity != "stairs" else None
        self.traj.rooms.append(room.id if room else None)
        self.traj.activity.append(activity)

    def turn_to(self, yaw: float) -> None:
        delta = _wrap(yaw - self.yaw)
        steps = math.ceil(abs(delta) / TURN - 1e-9)
        for _k in range(1, steps):
            self.yaw = _wrap(self.yaw + delta / steps)
            self.emit("turn")
        self.yaw = _wrap(yaw)

    def walk(self, points: list[tuple[float, float]]) -> None:
        """Follow a polyline, a frame every ``STEP`` metres, heading smoothed ahead."""
        dense = _resample(points, STEP)
        for k, (x, y) in enumerate(dense[1:], start=1):
            ahead = dense[min(k + 1, len(dense) - 1)]
            dx, dy = ahead[0] - dense[k - 1][0], ahead[1] - dense[k - 1][1]
            if math.hypot(dx, dy) > 1e-6:
                self.turn_to(math.atan2(dy, dx))
            self.x, self.y = x, y
            self.emit("walk")

    # Pitch above the horizon of every other look-around frame; None keeps the camera
    # level (the MP3D walker tilts up to take in what hangs high on walls and ceilings).
    look_up: float | None = None

    def look_around(self) -> None:
        direction = 1.0 if self.rng.random() < 0.5 else -1.0
        level = self.pitch
        for k in range(LOOK_FRAMES):
            self.yaw = _wrap(self.yaw + direction * 2 * math.pi / LOOK_FRAMES)
            if self.look_up is not None:
                self.pitch = -self.look_up if k % 2 else level
            self.emit("look")
        self.pitch = level

    def glance_up(self) -> None:
        """One frame looking steeply up: the ceiling light right above the stop."""
        level = self.pitch
        self.pitch = -CEILING_PITCH
        self.emit("glance")
        self.pitch = level

    def climb(self, stairs: StairPlan) -> None:
        heading = math.pi / 2 if stairs.direction > 0 else -math.pi / 2
        self.turn_to(heading)
        y_end = stairs.y_top + stairs.direction * 0.7
        n = max(2, math.ceil(abs(y_end - self.y) / STEP))
        y_start = self.y
        for k in range(1, n + 1):
            self.y = y_start + (y_end - y_start) * k / n
            z = stairs.surface_z(self.y)
            if k == n:
                self.floor = stairs.from_floor + 1
                self.emit("walk")
            else:
                self.emit("stairs", z=z)


def _resample(points: list[tuple[float, float]], step: float) -> list[tuple[float, float]]:
    if len(points) < 2:
        return list(points)
    out = [points[0]]
    carry = 0.0
    for (ax, ay), (bx, by) in pairwise(points):
        seg = math.hypot(bx - ax, by - ay)
        s = step - carry
        while s <= seg:
            out.append((ax + (bx - ax) * s / seg, ay + (by - ay) * s / seg))
            s += step
        carry = seg - (s - step)
    if math.hypot(out[-1][0] - points[-1][0], out[-1][1] - points[-1][1]) > 0.15:
        out.append(points[-1])
    return out


def _viewpoint(fm: FloorMap, room: RoomPlan, reach: np.ndarray) -> tuple[int, int] | None:
    """A roomy reachable cell of ``room`` close to its middle."""
    g = fm.grid
    inner = room.rect.grown(-0.15)
    mask = np.zeros(fm.free.shape, dtype=bool)
    g.fill(mask, inner)
    mask &= reach
    cells = np.argwhere(mask)
    if len(cells) == 0:
        return None
    xs = g.bounds.x0 + cells[:, 1] * g.res
    ys = g.bounds.y0 + cells[:, 0] * g.res
    off = np.hypot(xs - room.rect.cx, ys - room.rect.cy) / max(room.rect.w, room.rect.h)
    score = np.minimum(fm.clearance[cells[:, 0], cells[:, 1]], 0.9) - 0.6 * off
    best = cells[int(np.argmax(score))]
    return int(best[0]), int(best[1])


def _surface_strip(fm: FloorMap) -> np.ndarray:
    """The strip of the storey right in front of its walls and furniture (SURFACE_M
    deep): where things stand on surfaces and hang on walls, and what a close look is
    for."""
    near = ndimage.binary_dilation(fm.occupied, iterations=max(round(SURFACE_M / fm.grid.res), 1))
    return near & ~fm.occupied


def _close_look(w: _Walker, fm: FloorMap, stop: tuple[int, int], spots: np.ndarray) -> None:
    """Walk to ``stop`` and look over the surfaces within reach: facing the middle of
    the spots it sees up close, a frame either side and one in the middle."""
    _dist, pred = fm.search(fm.snap(w.x, w.y))
    w.walk(fm.path(pred, stop))
    cells = np.argwhere(spots)
    seen = sight(fm.sight_blocked, stop, cells, fm.grid.res, CLOSE.sight_m)
    if not seen.any():
        return
    row, col = cells[seen].mean(axis=0)
    sx, sy = fm.grid.point(*stop)
    tx, ty = fm.grid.point(round(row), round(col))
    face = math.atan2(ty - sy, tx - sx)
    for offset in (-CLOSE_SPREAD, 0.0, CLOSE_SPREAD):
        w.turn_to(_wrap(face + offset))
        w.emit("look")


def _tour_floor(w: _Walker, fm: FloorMap, rooms: list[RoomPlan], close: bool) -> None:
    start = fm.snap(w.x, w.y)
    reach = fm.labels == fm.labels[start]
    targets = {room.id: vp for room in rooms if (vp := _viewpoint(fm, room, reach)) is not None}
    by_id = {room.id: room for room in rooms}
    strip = _surface_strip(fm) if close else None
    while targets:
        dist, pred = fm.search(fm.snap(w.x, w.y))
        room_id = min(sorted(targets), key=lambda r: fm.cost_to(dist, targets[r]))
        goal = targets.pop(room_id)
        w.walk(fm.path(pred, goal))
        w.look_around()
        if strip is None:
            continue
        w.glance_up()
        inside = np.zeros(fm.free.shape, dtype=bool)
        fm.grid.fill(inside, by_id[room_id].rect)
        spots = inside & strip
        stops = coverage_stops(inside, reach, fm.sight_blocked, fm.grid.res, goal, spots, CLOSE)
        for stop in stops[1:]:
            _close_look(w, fm, stop, spots)


def plan_trajectory(
    plan: HousePlan, objects: list[Placed], rng: np.random.Generator, close: bool = True
) -> Trajectory:
    """An exploration walk through every room of every storey, lowest storey first;
    ``close``: each room also gets a glance at its ceiling and close looks over the
    surfaces its look-around saw only from afar (off: the earlier walk)."""
    w = _Walker(plan, rng)
    w.x, w.y = _front_door(plan)
    w.yaw = math.pi / 2 if w.y < plan.footprint.cy else -math.pi / 2
    w.emit("walk")
    for floor in plan.floors:
        w.floor = floor.index
        fm = FloorMap(plan, floor, objects)
        _tour_floor(w, fm, floor.rooms, close)
        stairs = next((s for s in plan.stairs if s.from_floor == floor.index), None)
        if stairs is None:
            break
        landing = (stairs.rect.cx, stairs.y_bottom - stairs.direction * 0.7)
        _dist, pred = fm.search(fm.snap(w.x, w.y))
        w.walk([*fm.path(pred, fm.snap(*landing)), landing])
        w.climb(stairs)
    return w.traj


def _front_door(plan: HousePlan) -> tuple[float, float]:
    """A point just inside the front door (the door of the ground floor with one room)."""
    door = next(d for d in plan.floors[0].doors if len(d.rooms) == 1)
    x, y = door.center_xy
    hall = plan.room(door.rooms[0]).rect
    return x, y + (0.8 if abs(y - hall.y0) < abs(y - hall.y1) else -0.8)
