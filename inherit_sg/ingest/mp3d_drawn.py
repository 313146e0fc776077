"""What each MP3D object is drawn as: its oriented box, adjusted so that annotated objects
the camera could see are not lost inside other boxes.

Matterport3D object boxes are the bounds of annotated mesh segments, not solid shapes.
Drawn as solid boxes they hide one another: the oven and the dishwasher (9–11 cm deep
fronts) lie inside the kitchen cabinet's box, pillows inside the bed's (which includes
the headboard), cushions inside couches, a basin inside its counter, a coffee table
inside a carpet's 0.57 m box, ceiling lights above the region's ceiling, a flush button
inside the wall. The rules, applied in this order (the ground truth keeps the file's
boxes; only the rendered mesh changes):

1. **floor coverings** (rugs, carpets, mats: the mpcat40 class ``floor``) are drawn as
   :data:`COVER_T` thin slabs on the floor, whatever the height of their box;
2. **under the ceiling**: a box reaching above its region's ceiling is cut
   :data:`CEILING_GAP` below it (kept at least :data:`MIN_T` thick), so ceiling lights
   hang just under the ceiling instead of above it;
3. **proud of what buries it**: a point just outside a box face is *open* when it lies
   inside a region of the level, between that region's floor and ceiling, outside every
   other drawn box and wall (grown by :data:`TOUCH`, so a coincident face counts as
   covered), and *in sight* when a straight line joins it to a viewpoint: a point of the
   level's walkable space at eye height (:data:`EYE`), on a :data:`VIEW_STEP` grid, within
   :data:`VIEW_RANGE`. The exposure of a box is the largest open, in-sight area of one of
   its faces (sampled :data:`SAMPLES` × :data:`SAMPLES` per face), over the area of its
   largest face: about how much of its biggest silhouette a camera can see.

   A box with exposure below :data:`MIN_EXPOSURE` is extended through one of its larger
   faces (never the bottom) until that face stands :data:`PROUD` (:data:`PROUD_UP` for a
   top face, which the camera sees at a grazing angle; plus :data:`PROUD_STEP` per
   earlier extended object, smaller objects last, so stacked ones do not share a plane)
   in front of the first open place of its own region or a region open to it (never
   through a wall or a doorway) that at least :data:`MIN_VIEWS` viewpoints see (not a
   gap only a corner of the room looks into). The cheapest face wins: the extension's
   length, upwards counted at :data:`UP_COST` (things rest on what buries them), at most
   :data:`MAX_PUSH_UP` up or :data:`MAX_PUSH_SIDE` sideways. The oven's front thus
   stands just proud of the cabinet front, a pillow's top just above the bed. A box
   that no face can free stays as it is (noted ``buried``). Extended boxes can bury
   further objects, so exposure is measured again (at most :data:`ROUNDS` passes).

Doors are drawn as frames (two jambs and a head) and never extended; their frames, not
their boxes, are what other objects can be buried in.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh

from inherit_sg.ingest.mp3d_house import HouseFile, OrientedBox
from inherit_sg.ingest.mp3d_polygons import contains
from inherit_sg.ingest.mp3d_space import FLOOR_COVERINGS, Level, LevelSpace
from inherit_sg.ingest.mp3d_walk import free_space
from inherit_sg.ingest.mp3d_walls import WALL_T, WallPlan, WallSpan, door_axes
from inherit_sg.ingest.synthetic.world import _CUBE_F

COVER_T = 0.02  # drawn thickness of rugs and carpets
CEILING_GAP = 0.01  # clearance kept under a region's ceiling
MIN_T = 0.02  # thinnest a box cut under the ceiling becomes
MIN_EXPOSURE = 0.15  # boxes less exposed than this are extended
TOUCH = 0.01  # occluders grow by this much: a face within 1 cm of another box is covered
PROBE = 0.005  # sample points sit this far outside a face
PROUD = 0.012  # how far an extended face stands in front of the first open place
PROUD_UP = 0.06  # the same for a top face: tops are seen at grazing angles
PROUD_STEP = 0.002  # added per earlier extended object
MAX_PUSH_UP, MAX_PUSH_SIDE = 0.6, 0.35
UP_COST = 0.6  # cost of an upward extension per metre (sideways: 1)
STEP = 0.01  # search step of the extension
MIN_FACE = 0.25  # faces smaller than this share of the largest face are not extended
OPEN_SHARE = 0.6  # share of a face's samples that must be open and in sight to free it
SAMPLES = 5  # samples per face side
EYE = 1.4  # viewpoint height above the level's floor
VIEW_STEP = 0.5  # spacing of the viewpoint grid
VIEW_RANGE = 7.0  # farthest viewpoint that counts
MIN_VIEWS = 8  # an extended face must be in sight of this many viewpoints
ROUNDS = 3  # exposure passes: an extended box may bury another one
JAMB = 0.05  # door frame: jamb width and head height
HEAD = 0.08


@dataclass
class Drawn:
    """The boxes one object is drawn as and what was changed (``notes``: ``flattened``,
    ``under ceiling``, ``proud of <ids> by <m> (<face>)`` or ``buried``); ``exposure``
    is :func:`exposure` of its box before any extension."""

    object_id: str
    parts: list[OrientedBox]
    exposure: float = 1.0
    notes: list[str] = field(default_factory=list)

    @property
    def note(self) -> str:
        """The changes, ``; ``-separated (empty when drawn as annotated)."""
        return "; ".join(self.notes)


def wall_box(w: WallSpan) -> OrientedBox:
    """A wall piece as an oriented box (just outside its region's outline)."""
    along = w.b - w.a
    length = float(np.hypot(*along))
    d = along / max(length, 1e-9)
    centre = np.array([*((w.a + w.b) / 2 + w.normal * WALL_T / 2), (w.z0 + w.z1) / 2])
    axes = np.array([[d[0], d[1], 0.0], [w.normal[0], w.normal[1], 0.0], [0.0, 0.0, 1.0]])
    return OrientedBox(centre, axes, np.array([length / 2, WALL_T / 2, (w.z1 - w.z0) / 2]))


def door_frame(box: OrientedBox) -> list[OrientedBox]:
    """Two jambs and a head inside a door's box."""
    up, width, _ = door_axes(box)
    u, w = box.axes[up] * np.sign(box.axes[up, 2] or 1.0), box.axes[width]
    parts = []
    for side in (-1.0, 1.0):
        radii = box.radii.copy()
        radii[width] = min(JAMB / 2, box.radii[width])
        centre = box.center + side * (box.radii[width] - radii[width]) * w
        parts.append(OrientedBox(centre, box.axes, radii))
    radii = box.radii.copy()
    radii[up] = min(HEAD / 2, box.radii[up])
    parts.append(OrientedBox(box.center + (box.radii[up] - radii[up]) * u, box.axes, radii))
    return parts


# ------------------------------------------------------------------ box helpers
def _vertical(box: OrientedBox) -> int | None:
    """Index of the box axis that is (anti)parallel to z, None when the box is tilted."""
    k = int(np.argmax(np.abs(box.axes[:, 2])))
    return k if abs(box.axes[k, 2]) >= 0.95 else None


def _with_span(box: OrientedBox, bottom: float, top: float) -> OrientedBox:
    """``box`` with its vertical extent replaced by ``[bottom, top]`` (upright boxes)."""
    k = _vertical(box)
    if k is None:
        return box
    radii = box.radii.copy()
    radii[k] = (top - bottom) / 2
    centre = box.center.copy()
    centre[2] = (top + bottom) / 2
    return OrientedBox(centre, box.axes, radii)


def _z_span(box: OrientedBox) -> tuple[float, float]:
    z = box.corners()[:, 2]
    return float(z.min()), float(z.max())


def _faces(box: OrientedBox) -> list[tuple[int, float]]:
    """(axis, sign) of every face but the one facing down."""
    return [(k, s) for k in range(3) for s in (-1.0, 1.0) if s * box.axes[k, 2] >= -0.7]


def _face_area(box: OrientedBox, k: int) -> float:
    j, m = [a for a in range(3) if a != k]
    return float(4 * box.radii[j] * box.radii[m])


def _face_samples(box: OrientedBox, k: int, s: float, offset: float) -> np.ndarray:
    """(SAMPLES², 3) points on face (k, s) of ``box``, ``offset`` outside it."""
    j, m = [a for a in range(3) if a != k]
    t = (np.arange(SAMPLES) + 0.5) / SAMPLES * 2 - 1
    u, v = np.meshgrid(t, t)
    base = box.center + s * (box.radii[k] + offset) * box.axes[k]
    return (
        base
        + (u.ravel() * box.radii[j])[:, None] * box.axes[j]
        + (v.ravel() * box.radii[m])[:, None] * box.axes[m]
    )


def _extend(box: OrientedBox, k: int, s: float, distance: float) -> OrientedBox:
    radii = box.radii.copy()
    radii[k] += distance / 2
    return OrientedBox(box.center + s * box.axes[k] * distance / 2, box.axes, radii)


def _face_name(box: OrientedBox, k: int, s: float) -> str:
    n = s * box.axes[k]
    if n[2] > 0.7:
        return "top"
    i = int(np.argmax(np.abs(n[:2])))
    return f"{'+' if n[i] > 0 else '-'}{'xy'[i]} side"


# ------------------------------------------------------------------ open space and sight
class _Space:
    """Open space of one level and lines of sight to its viewpoints (module docstring)."""

    def __init__(
        self,
        house: HouseFile,
        level: Level,
        viewpoints: np.ndarray,
        occluders: list[tuple[str, OrientedBox]],
    ) -> None:
        self.regions = [
            (rid, outline, house.region_floor_z.get(rid, level.z), level.ceilings[rid])
            for rid, outline in level.outlines.items()
        ]
        self.owners = [owner for owner, _ in occluders]
        self.centres = np.array([b.center for _, b in occluders]).reshape(-1, 3)
        self.axes = np.array([b.axes for _, b in occluders]).reshape(-1, 3, 3)
        self.radii = np.array([b.radii for _, b in occluders]).reshape(-1, 3) + TOUCH
        self.viewpoints = viewpoints
        self._scene = rtcore_scene.EmbreeScene()
        if occluders:
            verts = np.concatenate([b.corners() for _, b in occluders]).astype(np.float32)
            faces = np.concatenate([_CUBE_F + 8 * i for i in range(len(occluders))])
            TriangleMesh(scene=self._scene, vertices=verts, indices=faces.astype(np.int32))

    def in_room(self, pts: np.ndarray, rooms: set[str] | None = None) -> np.ndarray:
        """Points inside a region of the level (one of ``rooms`` when given), between its
        floor and its ceiling."""
        ok = np.zeros(len(pts), dtype=bool)
        for rid, outline, floor_z, ceiling in self.regions:
            if rooms is not None and rid not in rooms:
                continue
            todo = (pts[:, 2] > floor_z + 0.005) & (pts[:, 2] < ceiling - 0.005) & ~ok
            if todo.any():
                ok[todo] = contains(outline, pts[todo, :2])
        return ok

    def covering(self, pts: np.ndarray, skip: str) -> np.ndarray:
        """(points, occluders) bool: which occluders (not ``skip``'s) hold each point."""
        if not self.owners:
            return np.zeros((len(pts), 0), dtype=bool)
        rel = pts[:, None, :] - self.centres[None, :, :]
        local = np.einsum("pkj,kij->pki", rel, self.axes)
        inside = np.all(np.abs(local) < self.radii[None], axis=2)
        inside[:, [o == skip for o in self.owners]] = False
        return inside

    def open(self, pts: np.ndarray, skip: str, rooms: set[str] | None = None) -> np.ndarray:
        """Points in open space (``skip``'s own boxes do not count), in ``rooms`` if given."""
        return self.in_room(pts, rooms) & ~self.covering(pts, skip).any(axis=1)

    def views(self, pts: np.ndarray) -> np.ndarray:
        """How many viewpoints within range have a clear line to each point."""
        count = np.zeros(len(pts), dtype=np.int64)
        if len(pts) == 0 or len(self.viewpoints) == 0:
            return count
        delta = self.viewpoints[None, :, :] - pts[:, None, :]
        dist = np.linalg.norm(delta, axis=2)
        pi, vi = np.nonzero((dist <= VIEW_RANGE) & (dist > 0.05))
        if len(pi) == 0:
            return count
        d = dist[pi, vi]
        hits = self._scene.run(
            pts[pi].astype(np.float32),
            (delta[pi, vi] / d[:, None]).astype(np.float32),
            dists=(d - 0.01).astype(np.float32),
            query="OCCLUDED",
        )
        return np.bincount(pi[np.asarray(hits) < 0], minlength=len(pts))

    def visible(
        self, pts: np.ndarray, skip: str, rooms: set[str] | None = None, min_views: int = 1
    ) -> np.ndarray:
        """Points that are open and in sight of at least ``min_views`` viewpoints."""
        ok = self.open(pts, skip, rooms)
        if ok.any():
            ok[ok] = self.views(pts[ok]) >= min_views
        return ok


def _viewpoints(level: Level, space: LevelSpace, walls: list[WallSpan]) -> np.ndarray:
    """Walkable cells of the level on a :data:`VIEW_STEP` grid, at eye height."""
    free = free_space(space, walls)
    stride = max(1, round(VIEW_STEP / space.grid.res))
    cells = np.argwhere(free[::stride, ::stride]) * stride
    b = space.grid.bounds
    xy = np.column_stack([b.x0 + cells[:, 1] * space.grid.res, b.y0 + cells[:, 0] * space.grid.res])
    return np.column_stack([xy, np.full(len(xy), level.z + EYE)])


def exposure(box: OrientedBox, space: _Space, owner: str) -> float:
    """The largest open, in-sight area of one face of the box (any face, the bottom
    included), over the area of its largest face."""
    areas = [(k, s, max(_face_area(box, k), 1e-6)) for k in range(3) for s in (-1.0, 1.0)]
    largest = max(a for _, _, a in areas)
    best = 0.0
    for k, s, area in sorted(areas, key=lambda t: -t[2]):
        if area <= best * largest:
            break  # no smaller face can beat what is already seen
        share = float(space.visible(_face_samples(box, k, s, PROBE), owner).mean())
        best = max(best, share * area / largest)
    return best


def _push(
    box: OrientedBox, space: _Space, owner: str, rooms: set[str]
) -> tuple[int, float, float] | None:
    """(axis, sign, distance) of the cheapest extension that frees a face into ``rooms``."""
    best: tuple[int, float, float] | None = None
    best_cost = np.inf
    steps = np.arange(0.0, MAX_PUSH_UP + STEP / 2, STEP)
    faces = _faces(box)
    largest = max(_face_area(box, k) for k, _ in faces)
    for k, s in faces:
        if _face_area(box, k) < MIN_FACE * largest:
            continue  # too small a face to show the object by
        upward = s * box.axes[k, 2] > 0.7
        reach = steps[steps <= (MAX_PUSH_UP if upward else MAX_PUSH_SIDE)]
        n = SAMPLES * SAMPLES
        pts = np.concatenate([_face_samples(box, k, s, PROBE + t) for t in reach])
        share = space.open(pts, owner, rooms).reshape(len(reach), n).mean(axis=1)
        for i in np.flatnonzero(share >= OPEN_SHARE):
            cost = float(reach[i]) * (UP_COST if upward else 1.0)
            if cost >= best_cost:
                break
            chunk = pts[i * n : (i + 1) * n]
            if space.visible(chunk, owner, rooms, MIN_VIEWS).mean() >= OPEN_SHARE:
                best, best_cost = (k, s, float(reach[i])), cost
                break
    return best


# ------------------------------------------------------------------ the rules
def drawn_objects(
    house: HouseFile, levels: list[Level], spaces: list[LevelSpace], walls: WallPlan
) -> dict[str, Drawn]:
    """Object id -> how it is drawn (every object of the scene with a box)."""
    level_of = {lv.index: lv for lv in levels}
    out: dict[str, Drawn] = {}
    for obj in house.scene.objects:
        box = house.boxes.get(obj.id)
        if box is None:
            continue
        if obj.label == "door":
            out[obj.id] = Drawn(obj.id, door_frame(box))
            continue
        drawn = Drawn(obj.id, [box])
        level = level_of.get(obj.floor)
        default_z = level.z if level is not None else 0.0
        floor_z = house.region_floor_z.get(obj.room_id or "", default_z)
        bottom, top = _z_span(box)
        is_cover = obj.label in FLOOR_COVERINGS or obj.attributes.get("mpcat40") == "floor"
        if is_cover and top - max(bottom, floor_z) > COVER_T and _vertical(box) is not None:
            low = max(bottom, floor_z)
            box = _with_span(box, low, low + COVER_T)
            drawn.notes.append("flattened")
        if level is not None and obj.room_id in level.ceilings:
            ceiling = level.ceilings[obj.room_id] - CEILING_GAP
            if _z_span(box)[1] > ceiling and _vertical(box) is not None:
                box = _with_span(box, min(_z_span(box)[0], ceiling - MIN_T), ceiling)
                drawn.notes.append("under ceiling")
        drawn.parts = [box]
        out[obj.id] = drawn
    for level, space in zip(levels, spaces, strict=True):
        _free_buried(house, level, space, walls, out)
    return out


def _free_buried(
    house: HouseFile, level: Level, level_space: LevelSpace, walls: WallPlan, out: dict[str, Drawn]
) -> None:
    """Measure the exposure of the level's objects and extend the buried ones; repeated
    (at most :data:`ROUNDS` times) while extended boxes bury further objects."""
    objects = [o for o in house.scene.objects if o.floor == level.index and o.id in out]
    level_walls = [w for w in walls.walls if w.room_id in level.outlines]
    wall_boxes = [("wall", wall_box(w)) for w in level_walls]
    viewpoints = _viewpoints(level, level_space, level_walls)
    open_to: dict[str, set[str]] = {}
    for opening in walls.openings:
        if opening.kind == "open":
            a, b = opening.rooms
            open_to.setdefault(a, set()).add(b)
            open_to.setdefault(b, set()).add(a)
    settled: set[str] = {o.id for o in objects if o.label == "door"}
    rank = 0
    for round_ in range(ROUNDS):
        occluders = [(o.id, part) for o in objects for part in out[o.id].parts] + wall_boxes
        space = _Space(house, level, viewpoints, occluders)
        buried = []
        for obj in objects:
            if obj.id in settled:
                continue
            drawn = out[obj.id]
            seen = exposure(drawn.parts[0], space, obj.id)
            if round_ == 0:
                drawn.exposure = seen
            if seen < MIN_EXPOSURE:
                buried.append(obj)
        if not buried:
            return
        buried.sort(key=lambda o: -float(np.prod(out[o.id].parts[0].radii)))
        for obj in buried:
            settled.add(obj.id)
            # out into its own region or one open to it, never through a wall or doorway
            rooms = {obj.room_id, *open_to.get(obj.room_id, set())} if obj.room_id else set()
            if _free_one(out[obj.id], space, rooms, rank):
                rank += 1


def _free_one(drawn: Drawn, space: _Space, rooms: set[str], rank: int) -> bool:
    """Extend ``drawn``'s box through its cheapest face; False (noted) when none frees."""
    box = drawn.parts[0]
    push = _push(box, space, drawn.object_id, rooms)
    if push is None:
        drawn.notes.append("buried")
        return False
    k, s, distance = push
    inner = _face_samples(box, k, s, PROBE + max(distance - STEP, 0.0))
    held = space.covering(inner, drawn.object_id).any(axis=0)
    by = sorted({space.owners[i] for i in np.flatnonzero(held)})
    upward = s * box.axes[k, 2] > 0.7
    extra = (PROUD_UP if upward else PROUD) + PROUD_STEP * rank
    drawn.parts = [_extend(box, k, s, distance + extra)]
    drawn.notes.append(
        f"proud of {','.join(by) or 'open space'} by {distance + extra:.3f} m "
        f"({_face_name(box, k, s)})"
    )
    return True
