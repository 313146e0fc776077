"""Furnishing the rooms of the real-world generator: the groups of
:mod:`inherit_sg.ingest.synthetic.room_contents` placed where their kinds belong.

Per group: the anchor (against a wall or free, with room for chairs), standing members
arranged around it (chairs at tables, nightstands beside beds, appliances along the
counter's wall, a coffee table before the sofa), wall-mounted members above the piece
they belong to (a range hood over the stove, a mirror over the sink, a light switch
beside a door), curtains and blinds at the room's windows, ceiling fixtures over the
table or the room's middle, and small objects on the supporters their kind lists (on a
counter, a shelf board, a bed's mattress, a sofa's seat), else on the floor against a
wall when the kind may stand there. Every object gets a colour sampled from its
palette (named by :mod:`inherit_sg.ingest.synthetic.colour_naming`), a material and a Matterport3D
raw name.
"""

from __future__ import annotations

import numpy as np

from inherit_sg.ingest.synthetic import arrange as ar
from inherit_sg.ingest.synthetic.catalogue import REAL_MATERIALS
from inherit_sg.ingest.synthetic.colour_models import palette_for, sample_colour
from inherit_sg.ingest.synthetic.colour_naming import colour_term
from inherit_sg.ingest.synthetic.furnish_checks import walkable
from inherit_sg.ingest.synthetic.placement import (
    FRONT,
    GAP,
    WALL_QUARTER,
    AreaPlan,
    Placed,
    RoomSpace,
    build_keepout,
    make_placed,
)
from inherit_sg.ingest.synthetic.plan import WALL_T, FloorPlan, HousePlan, Opening, RoomPlan
from inherit_sg.ingest.synthetic.room_contents import choose_groups, draw_members
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

# Wall-mounted kinds and the pieces they hang above, best first.
MOUNT_OVER: dict[str, tuple[str, ...]] = {
    "range hood": ("stove", "oven"),
    "wall cabinet": ("counter", "kitchen cabinet", "sink", "dishwasher", "washing machine"),
    "mirror": ("sink", "dresser", "console table", "sideboard"),
    "painting": ("sofa", "bed", "sideboard", "console table", "fireplace", "dresser", "desk"),
    "bathroom cabinet": ("toilet",),
    "towel rack": ("bathtub", "shower", "sink"),
    "whiteboard": ("desk", "table"),
}
# Ceiling fixtures and what they hang over, best first (else the room's middle).
CEILING_OVER: dict[str, tuple[str, ...]] = {
    "chandelier": ("dining table", "table", "kitchen island"),
    "ceiling fan": ("bed", "sofa", "coffee table"),
}
# Kinds mounted next to a door of the room.
BY_DOOR = frozenset({"light switch", "thermostat"})
# Standing members placed right in front of the anchor: (member, anchors, gap).
IN_FRONT: tuple[tuple[str, tuple[str, ...], float], ...] = (
    ("coffee table", ("sofa", "recliner"), 0.42),
    ("ottoman", ("armchair", "recliner", "sofa"), 0.3),
    ("footstool", ("armchair", "recliner"), 0.25),
    ("rug", ("sofa", "bed", "dining table", "recliner"), 0.05),
    ("bath mat", ("bathtub", "shower", "sink"), 0.05),
    ("office chair", ("desk",), 0.05),
)
BESIDE = {"nightstand": ("bed",), "side table": ("sofa", "armchair", "bed", "recliner")}
# Kinds made to a standard height (worktops, appliances, sanitary ware).
FIXED_HEIGHT = frozenset(
    {
        "counter",
        "kitchen cabinet",
        "kitchen island",
        "dishwasher",
        "stove",
        "oven",
        "sink",
        "washing machine",
        "dryer",
        "toilet",
        "bathtub",
        "bar counter",
        "mini fridge",
    }
)
WALL_HANG = 1.1  # bottom height of a small object hung on a wall (a flat TV)
_MATERIAL_WEIGHT = 1.4  # material i of a kind is chosen with weight 1 / (i + 1) ** this


def new_object(space: RoomSpace, label: str, rng: np.random.Generator, shrink: int = 0) -> Placed:
    """An unplaced object of kind ``label``: size, material, sampled colour, raw name."""
    kind = OBJECT_KINDS[label]
    scale = round(max(float(rng.uniform(0.82, 1.22)) * 0.9**shrink, 0.75), 3)
    materials = REAL_MATERIALS.get(label, kind.materials)
    weights = np.array([1.0 / (i + 1) ** _MATERIAL_WEIGHT for i in range(len(materials))])
    material = materials[int(rng.choice(len(weights), p=weights / weights.sum()))]
    rgb = sample_colour(palette_for(kind.palette, material), rng)
    obj = make_placed(label, space, scale, colour_term(rgb), material)
    if label in FIXED_HEIGHT:  # worktops and appliances vary in width, hardly in height
        w, d, _ = obj.dims
        obj.dims = (w, d, round(kind.size[2] * (1.0 + 0.15 * (scale - 1.0)), 3))
    obj.rgb = rgb
    obj.params["real"] = True
    if label == "bed":
        obj.params["pillow"] = False
    raws = kind.raw or (label,)
    raw_w = np.array([1.0 / (i + 1) ** 2 for i in range(len(raws))])
    obj.raw = raws[int(rng.choice(len(raws), p=raw_w / raw_w.sum()))]
    return obj


def _anchor(space: RoomSpace, label: str, seats: bool, rng: np.random.Generator) -> Placed | None:
    """The group's anchor: against a wall, or free with room around it for chairs
    (less room on later tries)."""
    for shrink, margin in enumerate((0.65, 0.5, 0.35)):
        obj = new_object(space, label, rng, shrink)
        kind = OBJECT_KINDS[label]
        if kind.wall:
            ok = ar.random_wall(space, obj, rng)
        else:
            ok = ar.free_spot(space, obj, rng, margin=margin if seats else 0.0)
        if ok:
            return obj
    return None


def _first(group: list[Placed], labels: tuple[str, ...]) -> Placed | None:
    for label in labels:
        for obj in group:
            if obj.label == label:
                return obj
    return None


def _standing(
    space: RoomSpace,
    obj: Placed,
    anchor: Placed | None,
    group: list[Placed],
    rng: np.random.Generator,
) -> bool:
    """Place a floor-standing member relative to the group."""
    label = obj.label
    kind = OBJECT_KINDS[label]
    if anchor is not None:
        a = anchor.label
        if label in ar.SEATS and a in ar.TABLES:
            slots = ar.seat_slots(anchor, obj, OBJECT_KINDS[a].wall)
            order = rng.permutation(len(slots))
            return any(ar._try(space, obj, *slots[int(i)]) for i in order)
        for member, anchors, gap in IN_FRONT:
            if label == member and a in anchors and ar.in_front(space, obj, anchor, gap):
                return True
        if a in BESIDE.get(label, ()):
            if OBJECT_KINDS[a].wall and ar.beside_on_wall(space, obj, anchor, rng):
                return True
            if ar.near_anchor(space, obj, anchor, rng):
                return True
        if (
            label == "tv stand"
            and a in ("sofa", "recliner")
            and ar.facing_wall(space, obj, anchor, rng)
        ):
            return True
    if kind.wall:
        # in a row along the wall with the group's other wall pieces, latest first
        row = [o for o in reversed(group) if OBJECT_KINDS[o.label].wall and not o.support]
        if any(ar.beside_on_wall(space, obj, o, rng) for o in row[:4]):
            return True
        return ar.random_wall(space, obj, rng)
    if anchor is not None and ar.near_anchor(space, obj, anchor, rng):
        return True
    return ar.free_spot(space, obj, rng)


def _mounted(
    space: RoomSpace,
    obj: Placed,
    anchor: Placed | None,
    group: list[Placed],
    rng: np.random.Generator,
) -> bool:
    """Hang a wall-mounted member above its piece, beside a door, or on any wall."""
    if obj.label in BY_DOOR and _by_door(space, obj, rng):
        return True
    over = _first(group, MOUNT_OVER.get(obj.label, ()))
    if over is None and anchor is not None and obj.label not in MOUNT_OVER:
        over = anchor
    base = obj.z
    if over is not None and OBJECT_KINDS[over.label].wall:
        side = ar.side_of(space, over)
        obj.z = max(base, round(over.top + 0.08, 3))
        if obj.top < space.floor.z + space.floor.height - 0.1 and ar.on_wall(
            space, obj, side, over.x if side in ("N", "S") else over.y
        ):
            return True
        obj.z = base
    return ar.random_wall(space, obj, rng)


def _wall_side(space: RoomSpace, opening: Opening) -> str | None:
    """The side of the room whose wall holds ``opening``."""
    r = space.room.rect
    if opening.axis == "x":
        if abs(opening.coord - r.y0) < 1e-6:
            return "S"
        return "N" if abs(opening.coord - r.y1) < 1e-6 else None
    if abs(opening.coord - r.x0) < 1e-6:
        return "W"
    return "E" if abs(opening.coord - r.x1) < 1e-6 else None


def _by_door(space: RoomSpace, obj: Placed, rng: np.random.Generator) -> bool:
    doors = [d for d in space.floor.doors if space.room.id in d.rooms]
    for k in rng.permutation(len(doors)):
        door = doors[int(k)]
        side = _wall_side(space, door)
        if side is None:
            continue
        for t in (door.hi + 0.12 + obj.dims[0] / 2, door.lo - 0.12 - obj.dims[0] / 2):
            if ar.on_wall(space, obj, side, t):
                return True
    return False


def _objects_clear(space: RoomSpace, obj: Placed) -> bool:
    """No overlap with placed objects (keep-out zones ignored: window dressing stands in
    front of its window on purpose)."""
    if not space.room.rect.grown(-WALL_T / 2).contains_rect(obj.footprint):
        return False
    return not any(obj.box.overlaps(o.box, GAP) for o in space.objects if not o.flat)


def _at_window(space: RoomSpace, obj: Placed, rng: np.random.Generator) -> bool:
    """Hang a curtain panel beside a window of the room, or blinds across its top."""
    windows = [w for w in space.floor.windows if space.room.id in w.rooms]
    fl = space.floor
    for k in rng.permutation(len(windows)):
        win = windows[int(k)]
        side = _wall_side(space, win)
        if side is None:
            continue
        w, d, h = obj.dims
        if obj.label == "blinds":
            h = min(h, win.z1 - win.z0)
            obj.dims = (round(win.hi - win.lo + 0.06, 3), d, round(h, 3))
            spots = [(win.lo + win.hi) / 2]
            z = fl.z + win.z1 - h
        else:
            top = min(win.z1 + 0.15, fl.height - 0.05)
            obj.dims = (w, d, round(top - 0.02, 3))
            spots = [win.lo - 0.04 - w / 2, win.hi + 0.04 + w / 2]
            z = fl.z + 0.02
        for t in rng.permutation(spots):
            x, y = space.wall_spot(side, float(t), obj.dims)
            fx, fy = FRONT[WALL_QUARTER[side]]
            ar.set_pose(obj, x + fx * 0.03, y + fy * 0.03, WALL_QUARTER[side])
            obj.z = round(z, 4)
            if _objects_clear(space, obj):
                return True
    return False


def _on_ceiling(
    space: RoomSpace, obj: Placed, group: list[Placed], rng: np.random.Generator
) -> bool:
    """Hang a fixture from the ceiling over its piece or near the room's middle."""
    fl = space.floor
    obj.z = round(fl.z + fl.height - obj.dims[2], 4)
    over = _first(group + space.objects, CEILING_OVER.get(obj.label, ()))
    r = space.interior
    cx, cy = (over.x, over.y) if over is not None else (r.cx, r.cy)
    for k in range(30):
        spread = 0.0 if k == 0 else 0.25 + 0.05 * k
        ar.set_pose(
            obj, cx + float(rng.normal(0, spread)), cy + float(rng.normal(0, spread)), obj.quarter
        )
        if space.fits(obj):
            return True
    return False


def _small(space: RoomSpace, obj: Placed, group: list[Placed], rng: np.random.Generator) -> bool:
    """Stand a small object on a supporter its kind belongs on, else on the floor."""
    kind = OBJECT_KINDS[obj.label]
    base = obj.z
    for label in kind.rests_on:
        if label == "floor":
            continue
        pool = [o for o in group if o.label == label]
        pool += [o for o in space.objects if o.label == label and o not in pool]
        if any(ar.on_surface(space, obj, support, rng, keepout=False) for support in pool):
            return True
    obj.z, obj.support = base, None
    if "wall" in kind.rests_on:
        obj.z = round(base + WALL_HANG, 4)
        if ar.random_wall(space, obj, rng, tries=25):
            obj.params["hung"] = True
            return True
        obj.z = base
    if "floor" in kind.rests_on:
        return ar.random_wall(space, obj, rng, tries=25)
    return False


def _place(
    space: RoomSpace,
    obj: Placed,
    anchor: Placed | None,
    group: list[Placed],
    rng: np.random.Generator,
) -> bool:
    kind = OBJECT_KINDS[obj.label]
    if kind.window:
        return _at_window(space, obj, rng)
    if kind.ceiling:
        return _on_ceiling(space, obj, group, rng)
    if kind.mount_height > 0:
        return _mounted(space, obj, anchor, group, rng)
    if kind.small:
        return _small(space, obj, group, rng)
    return _standing(space, obj, anchor, group, rng)


def _stage(label: str) -> int:
    """Placement order: standing pieces, then what hangs on walls, windows and
    ceilings, then small things (which need their supporters placed)."""
    kind = OBJECT_KINDS[label]
    if kind.small:
        return 3
    if kind.window or kind.ceiling or kind.mount_height > 0:
        return 2
    return 1


def place_group(
    space: RoomSpace, anchor_label: str, members: list[str], rng: np.random.Generator
) -> list[Placed]:
    """Place one drawn group; returns the objects that found a place."""
    seats = any(m in ar.SEATS for m in members)
    anchor = _anchor(space, anchor_label, seats, rng)
    if anchor is None:
        return []
    space.objects.append(anchor)
    group = [anchor]
    for label in sorted(members, key=_stage):
        small = OBJECT_KINDS[label].small
        for shrink in range(4 if small else 1):
            obj = new_object(space, label, rng, shrink)
            if _place(space, obj, anchor, group, rng):
                space.objects.append(obj)
                group.append(obj)
                break
    return group


def furnish_room_real(
    plan: HousePlan, floor: FloorPlan, room: RoomPlan, rng: np.random.Generator
) -> list[AreaPlan]:
    """Furnish one room of a real-world house; fewer groups when all would block the way."""
    groups = choose_groups(room.type, room.rect.area, rng)
    tries = [groups] * 5 + [[g] for g in groups for _ in range(3)]
    for use in tries:
        space = RoomSpace(room, floor)
        space.obstacles = floor.holes + [s.rect for s in plan.stairs if s.from_floor == floor.index]
        build_keepout(space)
        areas = []
        for group in use:
            anchor, members = draw_members(group, rng)
            placed = place_group(space, anchor, members, rng)
            if placed:
                areas.append(AreaPlan(group.label, room.id, placed))
        if areas and walkable(space):
            return areas
    return []
