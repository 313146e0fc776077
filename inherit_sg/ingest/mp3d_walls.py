"""Walls and openings of an MP3D house, planned from its region outlines.

Every region edge carries a wall just outside the region, up to the level's roof. Where
an edge runs along another region's edge (parallel, at most :data:`GAP` apart: the two
sides of one real wall, or a virtual boundary of an open plan) the rooms may connect:

* a door object on the shared stretch cuts a gap the width of the door (its frame is
  rendered by the world builder; a lintel remains above the door's top);
* two open-plan rooms (living, dining, kitchen, hallway, ...) without a door between them
  are open along the whole shared stretch (a soffit remains above the lower ceiling);
* if the rooms of a level are still not all connected through walkable gaps, a 0.9 m
  doorway is cut where the longest shared stretch between two disconnected groups has
  the most room to pass, until everything connects (annotations often miss doors).

Every opening becomes a ``DoorGT`` of the ground-truth scene.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from inherit_sg.ingest.mp3d_house import HouseFile, OrientedBox
from inherit_sg.ingest.mp3d_polygons import cross2
from inherit_sg.ingest.mp3d_space import Level, LevelSpace
from inherit_sg.ingest.synthetic.geom import subtract_intervals
from inherit_sg.ingest.synthetic.planner import RADIUS

WALL_T = 0.08  # thickness of a drawn wall, metres (it stands just outside its region)
GAP = 0.3  # largest distance between two region edges that face each other across a wall
PARALLEL = np.sin(np.radians(15.0))
MIN_OPENING = 0.5  # narrower shared stretches stay closed
DOORWAY = 0.9  # width of an inferred doorway
DOORWAY_TOP = 2.05  # its height above the floor
OPEN_PLAN = {
    "living room", "dining room", "kitchen", "family room", "tv room", "entryway", "hallway",
    "lounge", "stairs", "bar", "game room", "library", "dining booth", "porch", "balcony",
}  # fmt: skip


@dataclass(frozen=True)
class Edge:
    """One outline edge of a region: start ``a``, unit direction ``d``, outward normal ``n``."""

    room_id: str
    a: np.ndarray
    d: np.ndarray
    n: np.ndarray
    length: float

    def point(self, t: float, offset: float = 0.0) -> np.ndarray:
        """The plan point ``t`` along the edge and ``offset`` outwards."""
        return self.a + self.d * t + self.n * offset


@dataclass(frozen=True)
class Shared:
    """A stretch ``[t0, t1]`` of ``edge`` that faces room ``other`` ``offset`` metres away."""

    edge: Edge
    other: str
    t0: float
    t1: float
    offset: float


@dataclass(frozen=True)
class Opening:
    """A gap in the walls between two rooms: ``door`` (a door object's), ``open`` (open
    plan) or ``doorway`` (inferred for connectivity)."""

    rooms: tuple[str, str]
    centre: np.ndarray  # plan point midway between the two walls
    direction: np.ndarray  # unit vector along the wall
    width: float
    top: float  # absolute height of the opening's top
    kind: str
    door_id: str | None = None


@dataclass(frozen=True)
class WallSpan:
    """A straight wall piece from ``a`` to ``b`` (plan), ``normal`` pointing away from
    ``room_id``, between heights ``z0`` and ``z1``."""

    room_id: str
    a: np.ndarray
    b: np.ndarray
    normal: np.ndarray
    z0: float
    z1: float


@dataclass
class WallPlan:
    """Wall pieces and openings of all levels."""

    walls: list[WallSpan] = field(default_factory=list)
    openings: list[Opening] = field(default_factory=list)
    openings_by_level: dict[int, list[Opening]] = field(default_factory=dict)


def level_edges(level: Level) -> list[Edge]:
    """All outline edges of the level's regions."""
    out = []
    for room_id, poly in level.outlines.items():
        for a, b in zip(poly, np.roll(poly, -1, axis=0), strict=True):
            length = float(np.hypot(*(b - a)))
            if length > 1e-6:
                d = (b - a) / length
                out.append(Edge(room_id, a, d, np.array([d[1], -d[0]]), length))
    return out


def shared_stretches(edges: list[Edge]) -> list[Shared]:
    """Stretches of edges that face another region's edge across at most :data:`GAP`."""
    out = []
    for e in edges:
        for f in edges:
            if f.room_id == e.room_id or abs(cross2(e.d, f.d)) > PARALLEL:
                continue
            ends = np.stack([f.a, f.a + f.d * f.length]) - e.a
            offsets = ends @ e.n
            if offsets.min() < -0.05 or offsets.max() > GAP:
                continue
            ts = ends @ e.d
            t0, t1 = max(float(ts.min()), 0.0), min(float(ts.max()), e.length)
            if t1 - t0 > 0.05:
                out.append(Shared(e, f.room_id, t0, t1, float(offsets.mean())))
    return out


class _Components:
    def __init__(self, rooms: list[str]) -> None:
        self.parent = {r: r for r in rooms}

    def find(self, r: str) -> str:
        while self.parent[r] != r:
            r = self.parent[r]
        return r

    def join(self, a: str, b: str) -> None:
        self.parent[self.find(a)] = self.find(b)

    def count(self) -> int:
        return len({self.find(r) for r in self.parent})


def door_axes(box: OrientedBox) -> tuple[int, int, int]:
    """Indices of a door box's (up, width, depth) axes: the most vertical axis is up, the
    wider of the other two runs along the wall."""
    up = int(np.argmax(np.abs(box.axes[:, 2])))
    flat = [k for k in range(3) if k != up]
    width = max(flat, key=lambda k: box.radii[k])
    return up, width, flat[0] if flat[1] == width else flat[1]


def _door_openings(house: HouseFile, level: Level, shared: list[Shared]) -> list[Opening]:
    out: list[Opening] = []
    for obj in house.scene.objects:
        if obj.label != "door" or obj.floor != level.index or obj.id not in house.boxes:
            continue
        box = house.boxes[obj.id]
        along = box.axes[door_axes(box)[1], :2]
        along = along / max(float(np.hypot(*along)), 1e-9)
        corners = box.corners()[:, :2]
        centre = corners.mean(axis=0)
        for s in shared:
            e = s.edge
            if abs(float(along @ e.d)) < np.cos(np.radians(30.0)):
                continue
            offset = float((centre - e.a) @ e.n)
            if not -0.5 <= offset <= s.offset + 0.5:
                continue
            ts = (corners - e.a) @ e.d
            g0, g1 = max(float(ts.min()), s.t0), min(float(ts.max()), s.t1)
            if g1 - g0 < MIN_OPENING:
                continue
            rooms = (e.room_id, s.other)
            mid = e.point((g0 + g1) / 2, s.offset / 2)
            out.append(Opening(rooms, mid, e.d, g1 - g0, obj.bbox_max[2], "door", obj.id))
            break
    return out


def _side_clearance(space: LevelSpace, s: Shared, t: float) -> float:
    """Room to pass at ``t`` along a shared stretch: clearance on both sides of the wall."""
    e = s.edge
    pts = np.stack([e.point(t, -0.45), e.point(t, s.offset + 0.45)])
    return float(space.clearance(pts).min())


def _walkable(space: LevelSpace, opening: Opening, shared: list[Shared]) -> bool:
    for s in shared:
        if (s.edge.room_id, s.other) == opening.rooms:
            t = float((opening.centre - s.edge.a) @ s.edge.d)
            if s.t0 - 0.05 <= t <= s.t1 + 0.05:
                return opening.width >= MIN_OPENING and _side_clearance(space, s, t) > RADIUS
    return False


def _best_doorway(space: LevelSpace, s: Shared) -> tuple[float, float]:
    """(clearance, position) of the roomiest doorway position along a shared stretch."""
    half = DOORWAY / 2
    ts = np.arange(s.t0 + half, s.t1 - half + 1e-9, 0.1)
    scored = [(min(_side_clearance(space, s, float(t)), 0.8), float(t)) for t in ts]
    return max(scored, key=lambda c: (c[0], -abs(c[1] - (s.t0 + s.t1) / 2)))


def _doorway_rank(clearance: float, s: Shared, types: dict[str, str]) -> tuple[float, ...]:
    """Preference for an inferred doorway: passable first, then into open-plan rooms (a
    bedroom opens onto the living room rather than into a bathroom), roomier, longer."""
    public = (types[s.edge.room_id] in OPEN_PLAN) + (types[s.other] in OPEN_PLAN)
    return (float(clearance > RADIUS + 0.15), float(public), round(clearance, 1), s.t1 - s.t0)


def plan_level_openings(house: HouseFile, level: Level, space: LevelSpace) -> list[Opening]:
    """Door gaps, open-plan boundaries and inferred doorways of one level."""
    shared = shared_stretches(level_edges(level))
    types = {r.id: r.type for r in level.rooms}
    openings = _door_openings(house, level, shared)
    links = _Components(list(types))
    for o in openings:
        if _walkable(space, o, shared):
            links.join(*o.rooms)
    with_door = {frozenset(o.rooms) for o in openings}
    for s in shared:
        pair = (s.edge.room_id, s.other)
        if pair[0] > pair[1] or frozenset(pair) in with_door or s.t1 - s.t0 < MIN_OPENING:
            continue
        if types[pair[0]] in OPEN_PLAN and types[pair[1]] in OPEN_PLAN:
            top = min(level.ceilings[pair[0]], level.ceilings[pair[1]])
            mid = s.edge.point((s.t0 + s.t1) / 2, s.offset / 2)
            openings.append(Opening(pair, mid, s.edge.d, s.t1 - s.t0, top, "open"))
            links.join(*pair)
    while links.count() > 1:
        candidates = [
            (*_best_doorway(space, s), s)
            for s in shared
            if s.t1 - s.t0 >= DOORWAY and links.find(s.edge.room_id) != links.find(s.other)
        ]
        if not candidates:
            break
        _, t, s = max(candidates, key=lambda c: _doorway_rank(c[0], c[2], types))
        pair = (s.edge.room_id, s.other)
        top = min(level.z + DOORWAY_TOP, level.ceilings[pair[0]], level.ceilings[pair[1]])
        centre = s.edge.point(t, s.offset / 2)
        openings.append(Opening(pair, centre, s.edge.d, DOORWAY, top, "doorway"))
        links.join(*pair)
    return openings


def _cuts(edge: Edge, openings: list[Opening]) -> list[tuple[float, float, float]]:
    """(t0, t1, top) of the openings that cut ``edge``."""
    out = []
    for o in openings:
        if edge.room_id not in o.rooms or abs(cross2(edge.d, o.direction)) > PARALLEL:
            continue
        rel = o.centre - edge.a
        if abs(float(rel @ edge.n)) > GAP:
            continue
        t = float(rel @ edge.d)
        t0, t1 = max(t - o.width / 2, 0.0), min(t + o.width / 2, edge.length)
        if t1 - t0 > 1e-3:
            out.append((t0, t1, o.top))
    return out


def plan_walls(house: HouseFile, levels: list[Level], spaces: list[LevelSpace]) -> WallPlan:
    """Wall pieces (with gaps and lintels) and openings of every level."""
    plan = WallPlan()
    for level, space in zip(levels, spaces, strict=True):
        openings = plan_level_openings(house, level, space)
        plan.openings += openings
        plan.openings_by_level[level.index] = openings
        floor_z = min(house.region_floor_z.get(r.id, level.z) for r in level.rooms) - 0.02
        roof = max(level.ceilings.values()) + 0.02
        for edge in level_edges(level):
            cuts = _cuts(edge, openings)
            solid = subtract_intervals(0.0, edge.length, [(c[0], c[1]) for c in cuts])
            pieces = [(a, b, floor_z) for a, b in solid]
            pieces += [(a, b, top) for a, b, top in cuts if top < roof]
            for t0, t1, z0 in pieces:
                plan.walls.append(
                    WallSpan(edge.room_id, edge.point(t0), edge.point(t1), edge.n, z0, roof)
                )
    return plan
