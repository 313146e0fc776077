"""Furnishing rooms by function: each room gets functional groups (the areas), each
group is placed around an anchor piece, small objects stand on surfaces, and the room
must stay walkable between its doors.

The classic world's groups come from ``AREA_TEMPLATES`` and are placed here; the
real-world generator's (:mod:`inherit_sg.ingest.synthetic.room_contents`) by
:mod:`inherit_sg.ingest.synthetic.furnish_real`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from inherit_sg.ingest.synthetic import arrange as ar
from inherit_sg.ingest.synthetic.furnish_checks import walkable
from inherit_sg.ingest.synthetic.furnish_real import furnish_room_real
from inherit_sg.ingest.synthetic.placement import (
    AreaPlan,
    Placed,
    RoomSpace,
    build_keepout,
    make_placed,
)
from inherit_sg.ingest.synthetic.plan import FloorPlan, HousePlan, RoomPlan
from inherit_sg.ingest.synthetic.structure import structural_objects
from inherit_sg.ingest.synthetic.vocabulary import AREA_TEMPLATES, OBJECT_KINDS

__all__ = ["AreaPlan", "Furnishing", "furnish", "furnish_room", "place_group", "walkable"]


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


def furnish(plan: HousePlan, rng: np.random.Generator, style: str = "real") -> Furnishing:
    """Place structural objects and furniture in every room; assign ids. ``style`` is the
    house's ("real" or "classic")."""
    objects = structural_objects(plan, rng, style)
    areas: list[AreaPlan] = []
    furnish_one = furnish_room_real if style == "real" else furnish_room
    for floor in plan.floors:
        for room in floor.rooms:
            for area in furnish_one(plan, floor, room, rng):
                areas.append(area)
                objects.extend(area.members)
    for n, obj in enumerate(objects, start=1):
        obj.id, obj.instance_id = f"o{n}", n
    for n, area in enumerate(areas):
        area.id = f"a{n}"
    return Furnishing(objects, areas)
