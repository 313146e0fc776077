"""Furnishing rooms by function: each room gets functional groups from
``AREA_TEMPLATES`` (the areas), each group is placed around an anchor piece, small
objects stand on surfaces, and the room must stay walkable between its doors."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ingest.synthetic import arrange as ar
from ingest.synthetic.geom import Rect
from ingest.synthetic.grid import Grid, components, free_space
from ingest.synthetic.placement import Placed, RoomSpace, build_keepout, make_placed
from ingest.synthetic.plan import FloorPlan, HousePlan, RoomPlan
from ingest.synthetic.planner import BODY, RADIUS
from ingest.synthetic.structure import structural_objects
from ingest.synthetic.vocabulary import AREA_TEMPLATES, OBJECT_KINDS

# Wider than the walker (by two grid cells) so the check holds on any grid alignment.
ROBOT_RADIUS = RADIUS + 0.1


@dataclass
class AreaPlan:
    """A placed functional group."""

    label: str
    room_id: str
    members: list[Placed] = field(default_factory=list)
    id: str = ""


@dataclass
class Furnishing:
    """Everything placed in a house, ids assigned."""

    objects: list[Placed]
    areas: list[AreaPlan]


def choose_groups(room: RoomPlan, rng: np.random.Generator) -> list[str]:
    """Functional groups for a room: its main one plus more in bigger rooms."""
    labels = list(AREA_TEMPLATES.get(room.type, {}))
    if not labels:
        return []
    n = int(np.clip(1 + (room.rect.area - 6.0) // 5.0, 1, len(labels)))
    extra = [labels[i] for i in sorted(rng.permutation(len(labels) - 1)[: n - 1] + 1)]
    return [labels[0], *extra]


def _new(space: RoomSpace, label: str, rng: np.random.Generator, shrink: int = 0) -> Placed:
    kind = OBJECT_KINDS[label]
    scale = float(rng.uniform(0.8, 1.25)) * 0.9**shrink
    return make_placed(
        label,
        space,
        round(max(scale, 0.8), 3),
        str(rng.choice(kind.colours)),
        str(rng.choice(kind.materials)),
    )


def _anchor(
    space: RoomSpace, label: str, members: tuple[str, ...], rng: np.random.Generator
) -> Placed | None:
    seats = any(m in ar.SEATS for m in members)
    for shrink in range(3):
        obj = _new(space, label, rng, shrink)
        if OBJECT_KINDS[label].wall:
            ok = ar.random_wall(space, obj, rng)
        else:
            ok = ar.free_spot(space, obj, rng, margin=0.65 if seats else 0.0)
        if ok:
            return obj
    return None


def _member(space: RoomSpace, obj: Placed, anchor: Placed, rng: np.random.Generator) -> bool:
    label, a = obj.label, anchor.label
    if label in ar.SEATS and a in ar.TABLES:
        slots = ar.seat_slots(anchor, obj, OBJECT_KINDS[a].wall)
        return any(ar._try(space, obj, x, y, q) for x, y, q in slots)
    if label == "nightstand" and a == "bed":
        return ar.beside_on_wall(space, obj, anchor, rng)
    if a == "sofa" and label == "coffee table":
        return ar.in_front(space, obj, anchor, float(rng.uniform(0.35, 0.5)))
    if a == "sofa" and label == "rug":
        return ar.in_front(space, obj, anchor, 0.1) or ar.free_spot(space, obj, rng)
    if a == "sofa" and label == "tv stand" and ar.facing_wall(space, obj, anchor, rng):
        return True
    if OBJECT_KINDS[label].wall:
        if OBJECT_KINDS[a].wall and ar.beside_on_wall(space, obj, anchor, rng):
            return True
        return ar.random_wall(space, obj, rng)
    return ar.near_anchor(space, obj, anchor, rng) or ar.free_spot(space, obj, rng)


def _mounted(
    space: RoomSpace, obj: Placed, anchor: Placed | None, rng: np.random.Generator
) -> bool:
    base = obj.z
    if anchor is not None and OBJECT_KINDS[anchor.label].wall:
        side = ar.side_of(space, anchor)
        obj.z = max(base, round(anchor.top + 0.08, 3))
        if obj.top < space.floor.z + space.floor.height - 0.1 and ar.on_wall(
            space, obj, side, anchor.x if side in ("N", "S") else anchor.y
        ):
            return True
        obj.z = base
    return ar.random_wall(space, obj, rng)


def _small(space: RoomSpace, obj: Placed, group: list[Placed], rng: np.random.Generator) -> bool:
    prefer = ar.PREFERRED.get(obj.label, ())
    pool = [o for o in group if OBJECT_KINDS[o.label].surface]
    pool += [o for o in space.objects if OBJECT_KINDS[o.label].surface and o not in pool]
    pool.sort(key=lambda o: prefer.index(o.label) if o.label in prefer else len(prefer))
    return any(ar.on_surface(space, obj, support, rng) for support in pool)


def place_group(
    space: RoomSpace, members: tuple[str, ...], rng: np.random.Generator
) -> list[Placed]:
    """Place one functional group; returns its members that found a place."""
    kinds = OBJECT_KINDS
    standing = [m for m in members if not kinds[m].small and kinds[m].mount_height == 0]
    group: list[Placed] = []
    anchor = None
    rest = list(members)
    if standing:
        anchor = _anchor(space, standing[0], members, rng)
        if anchor is None:
            return []
        space.objects.append(anchor)
        group.append(anchor)
        rest.remove(standing[0])
    for label in rest:
        kind = kinds[label]
        if kind.small:
            continue
        obj = _new(space, label, rng)
        if kind.mount_height > 0:
            ok = _mounted(space, obj, anchor, rng)
        else:
            ok = anchor is not None and _member(space, obj, anchor, rng)
        if ok:
            space.objects.append(obj)
            group.append(obj)
    for label in (m for m in members if kinds[m].small):
        for shrink in range(3):
            obj = _new(space, label, rng, shrink)
            if _small(space, obj, group, rng):
                space.objects.append(obj)
                group.append(obj)
                break
    return group


def walkable(space: RoomSpace) -> bool:
    """Whether every doorway of the room is reachable from every other through it."""
    grid = Grid(space.interior, 0.05)
    fl = space.floor
    obstacles: list[Rect] = [
        o.footprint for o in space.objects if not o.flat and o.z - fl.z < BODY and o.support is None
    ]
    obstacles += space.obstacles
    free = free_space(grid, obstacles, ROBOT_RADIUS)
    labels = components(free)
    seen = set()
    for door in fl.doors:
        if space.room.id not in door.rooms:
            continue
        x, y = door.center_xy
        r = space.room.rect
        if door.axis == "x":
            y += 0.45 if abs(y - r.y0) < abs(y - r.y1) else -0.45
        else:
            x += 0.45 if abs(x - r.x0) < abs(x - r.x1) else -0.45
        seen.add(int(labels[grid.cell(x, y)]))
    if not seen or 0 in seen or len(seen) > 1:
        return False
    return bool((labels == seen.pop()).sum() * grid.res**2 >= 1.0)


def furnish_room(
    plan: HousePlan, floor: FloorPlan, room: RoomPlan, rng: np.random.Generator
) -> list[AreaPlan]:
    """Furnish one room; falls back to single groups when all would block the way."""
    groups = choose_groups(room, rng)
    # All groups first; then each group alone, so a cramped room still gets something.
    tries = [groups] * 5 + [[label] for label in groups for _ in range(3)]
    for use in tries:
        space = RoomSpace(room, floor)
        space.obstacles = floor.holes + [s.rect for s in plan.stairs if s.from_floor == floor.index]
        build_keepout(space)
        areas = []
        for label in use:
            members = place_group(space, AREA_TEMPLATES[room.type][label], rng)
            if members:
                areas.append(AreaPlan(label, room.id, members))
        if areas and walkable(space):
            return areas
    return []


def furnish(plan: HousePlan, rng: np.random.Generator) -> Furnishing:
    """Place structural objects and furniture in every room; assign ids."""
    objects = structural_objects(plan, rng)
    areas: list[AreaPlan] = []
    for floor in plan.floors:
        for room in floor.rooms:
            for area in furnish_room(plan, floor, room, rng):
                areas.append(area)
                objects.extend(area.members)
    for n, obj in enumerate(objects, start=1):
        obj.id, obj.instance_id = f"o{n}", n
    for n, area in enumerate(areas):
        area.id = f"a{n}"
    return Furnishing(objects, areas)
