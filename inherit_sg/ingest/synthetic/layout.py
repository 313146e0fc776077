"""Procedural floor plans: a stair hall spine, rooms by recursive rectangle splitting,
typed rooms (Matterport3D region types, or the classic nine), open-plan ground floors,
stairs between storeys.

Every storey shares one rectangular footprint. A hallway runs across the whole depth of
the house (along y) and holds the straight staircases; the regions on either side of it
are split recursively into rooms. Doors, windows and wall lines are added by
:mod:`inherit_sg.ingest.synthetic.openings`.
"""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np

from inherit_sg.ingest.synthetic.geom import Rect, shared_border
from inherit_sg.ingest.synthetic.open_plan import FOYER_MIN, OPEN_MIN, open_edge
from inherit_sg.ingest.synthetic.openings import add_openings, blocked_intervals, connect_rooms
from inherit_sg.ingest.synthetic.plan import (
    STAIR_WIDTH,
    WALL_T,
    FloorPlan,
    HousePlan,
    Opening,
    RoomPlan,
    StairPlan,
)
from inherit_sg.ingest.synthetic.room_assign import assign_rooms
from inherit_sg.ingest.synthetic.taxonomy import draw_programme

MIN_ROOMS, MAX_ROOMS = 4, 12
STYLES = ("real", "classic")
OPEN_PLAN_SHARE = 0.5  # houses whose ground floor is drawn open-plan (where it fits)
OPEN_TRIES = 60  # splits tried for an open-plan ground floor before giving up
MAX_FLOORS = 3
MIN_ROOM_DIM = 2.4
TREAD = 0.25
LANDING = 1.4
# Rough size rank of room types: big rooms go to the first, small ones to the last.
_SIZE_RANK = (
    "garage",
    "living room",
    "kitchen",
    "dining room",
    "bedroom",
    "office",
    "laundry room",
    "bathroom",
)


def _snap(v: float) -> float:
    return round(v * 20.0) / 20.0


def split_region(region: Rect, k: int, rng: np.random.Generator) -> list[Rect] | None:
    """Split ``region`` into ``k`` rectangles by recursive cuts; None if too cramped."""
    if k == 1:
        return [region]
    k1 = int(np.clip(round(k * rng.uniform(0.35, 0.65)), 1, k - 1))
    along_x = region.w > region.h if abs(region.w - region.h) > 0.5 else bool(rng.random() < 0.5)
    frac = k1 / k * rng.uniform(0.88, 1.12)
    if along_x:
        cut = _snap(region.x0 + region.w * frac)
        a, b = (
            Rect(region.x0, region.y0, cut, region.y1),
            Rect(cut, region.y0, region.x1, region.y1),
        )
    else:
        cut = _snap(region.y0 + region.h * frac)
        a, b = (
            Rect(region.x0, region.y0, region.x1, cut),
            Rect(region.x0, cut, region.x1, region.y1),
        )
    for part, n in ((a, k1), (b, k - k1)):
        if min(part.w, part.h) < MIN_ROOM_DIM or part.area / n < MIN_ROOM_DIM * 2.6:
            return None
    left = split_region(a, k1, rng)
    right = split_region(b, k - k1, rng)
    if left is None or right is None:
        return None
    return left + right


def _split_with_retries(region: Rect, k: int, rng: np.random.Generator) -> list[Rect]:
    for _ in range(200):
        rooms = split_region(region, k, rng)
        if rooms is not None:
            return rooms
    # Deterministic fallback: equal strips across the longer side.
    if region.h >= region.w:
        edges = [_snap(region.y0 + region.h * i / k) for i in range(k)] + [region.y1]
        return [Rect(region.x0, a, region.x1, b) for a, b in pairwise(edges)]
    edges = [_snap(region.x0 + region.w * i / k) for i in range(k)] + [region.x1]
    return [Rect(a, region.y0, b, region.y1) for a, b in pairwise(edges)]


def _room_types(
    rects: list[Rect], floor: int, footprint: Rect, rng: np.random.Generator
) -> list[str]:
    """Pick a type for each rectangle (same order)."""
    n = len(rects)
    if floor == 0:
        required = ["living room", "kitchen", "dining room"]
        caps = {"bathroom": 2, "office": 2, "laundry room": 1, "bedroom": 9}
    else:
        required = ["bedroom", "bathroom", "bedroom"]
        caps = {"bedroom": 9, "office": 2, "bathroom": 2, "laundry room": 1, "living room": 1}
    types = required[:n]
    while len(types) < n:
        pool = [t for t, cap in caps.items() if types.count(t) < cap]
        weights = np.array([3.0 if t == "bedroom" else 1.0 for t in pool])
        types.append(str(rng.choice(pool, p=weights / weights.sum())))
    out = [""] * n
    order = sorted(range(n), key=lambda i: -rects[i].area)
    if floor == 0 and n >= 4 and rng.random() < 0.6:
        for i in order:
            r = rects[i]
            on_edge = r.x0 <= footprint.x0 + 1e-6 or r.x1 >= footprint.x1 - 1e-6
            if min(r.w, r.h) >= 3.0 and max(r.w, r.h) >= 5.4 and on_edge:
                out[i] = "garage"
                types.remove(types[-1])
                break
    types.sort(key=_SIZE_RANK.index)
    for i in order:
        if not out[i]:
            out[i] = types.pop(0)
    return out


def _name_rooms(plan: HousePlan) -> None:
    counts: dict[str, int] = {}
    for room in plan.all_rooms:
        counts[room.type] = counts.get(room.type, 0) + 1
        n = counts[room.type]
        room.name = room.type if n == 1 else f"{room.type} {n}"


def _dimensions(floors: int, counts: list[int], rng: np.random.Generator) -> tuple[float, ...]:
    spacing = float(rng.uniform(2.95, 3.15))
    n_steps = round(spacing / 0.18)
    run = n_steps * TREAD
    hall_w = _snap(2.5 if floors <= 2 else 3.3)
    side_area = (max(counts) - 1) * rng.uniform(13.0, 18.0)
    stairs_depth = run + 2 * LANDING + rng.uniform(0.2, 1.5)
    depth = _snap(max(stairs_depth, 7.4, math.sqrt(side_area / rng.uniform(1.1, 1.6))))
    side_w = max(side_area / depth, 3.0)
    left_w = _snap(side_w * rng.uniform(0.4, 0.6)) if side_w >= 7.0 else 0.0
    right_w = _snap(max(side_w - left_w, 3.0))
    return spacing, float(n_steps), run, depth, hall_w, left_w, right_w


def plan_house(
    rng: np.random.Generator,
    floors: int,
    rooms_per_floor: int | None,
    style: str = "real",
    open_plan: bool | None = None,
) -> HousePlan:
    """Lay out a house of ``floors`` storeys; ``rooms_per_floor`` counts the hallway.

    ``style`` "real" (default) draws Matterport3D room types (:mod:`taxonomy`) and makes
    the ground floor open-plan with chance :data:`OPEN_PLAN_SHARE` (``open_plan`` True
    forces it where the rooms allow; False gives walled rooms only, without open borders
    anywhere); "classic" is the earlier nine-type generator.
    """
    counts = [
        rooms_per_floor if rooms_per_floor is not None else int(rng.integers(5, 9))
        for _ in range(floors)
    ]
    spacing, n_steps_f, run, depth, hall_w, left_w, right_w = _dimensions(floors, counts, rng)
    footprint = Rect(0.0, 0.0, left_w + hall_w + right_w, depth)
    hall = Rect(left_w, 0.0, left_w + hall_w, depth)
    plan = HousePlan(footprint=footprint, level_spacing=spacing, style=style)
    ceiling = spacing - 0.2
    for f in range(floors):
        plan.floors.append(FloorPlan(index=f, z=round(f * spacing, 4), height=round(ceiling, 4)))
    _add_stairs(plan, hall, run, int(n_steps_f), rng)
    if style == "classic":
        for f, count in enumerate(counts):
            _add_rooms(plan, f, count, hall, left_w, right_w, rng)
    elif style == "real":
        programme = draw_programme(rng, [c - 1 for c in counts])
        draw = rng.random() < OPEN_PLAN_SHARE
        want_open = draw if open_plan is None else open_plan
        for f, count in enumerate(counts):
            open_floor = want_open and f == 0
            walled = open_plan is False
            sides = (left_w, right_w)
            _add_real_rooms(plan, f, count, hall, sides, programme[f], (open_floor, walled), rng)
    else:
        raise ValueError(f"unknown house style {style!r}; expected one of {STYLES}")
    for stairs in plan.stairs:
        stairs.room_bottom = plan.floors[stairs.from_floor].rooms[0].id
        stairs.room_top = plan.floors[stairs.from_floor + 1].rooms[0].id
    _name_rooms(plan)
    add_openings(plan, rng)
    return plan


def _add_stairs(
    plan: HousePlan, hall: Rect, run: float, n_steps: int, rng: np.random.Generator
) -> None:
    y0 = _snap(float(rng.uniform(LANDING, hall.h - LANDING - run)))
    for k in range(len(plan.floors) - 1):
        if k % 2 == 0:
            x0 = hall.x0 + WALL_T / 2
            rect = Rect(x0, y0, x0 + STAIR_WIDTH, y0 + run)
        else:
            x1 = hall.x1 - WALL_T / 2
            rect = Rect(x1 - STAIR_WIDTH, y0, x1, y0 + run)
        stairs = StairPlan(
            id=f"s{k}",
            from_floor=k,
            rect=rect,
            direction=1 if k % 2 == 0 else -1,
            n_steps=n_steps,
            z0=plan.floors[k].z,
            z1=plan.floors[k + 1].z,
            room_bottom="",
            room_top="",
        )
        plan.stairs.append(stairs)
        plan.floors[k + 1].holes.append(rect)
        zone = Rect(hall.x0, y0 - LANDING, hall.x1, y0 + run + LANDING)
        for f in (k, k + 1):
            if zone not in plan.floors[f].stair_zones:
                plan.floors[f].stair_zones.append(zone)


def _add_rooms(
    plan: HousePlan,
    f: int,
    count: int,
    hall: Rect,
    left_w: float,
    right_w: float,
    rng: np.random.Generator,
) -> None:
    floor = plan.floors[f]
    stair_rects = [s.rect for s in plan.stairs if s.from_floor == f] + floor.holes
    for _ in range(100):
        rects = _split_sides(plan, count, hall, (left_w, right_w), rng)
        types = _room_types(rects, f, plan.footprint, rng)
        floor.rooms = [RoomPlan(id=f"r{f}_0", type="hallway", floor=f, rect=hall)]
        for i, (rect, kind) in enumerate(zip(rects, types, strict=True), start=1):
            floor.rooms.append(RoomPlan(id=f"r{f}_{i}", type=kind, floor=f, rect=rect))
        doors = connect_rooms(floor, stair_rects, rng)
        if doors is not None:
            floor.doors = doors
            return
    raise RuntimeError(f"could not connect the rooms of floor {f}")


def _split_sides(
    plan: HousePlan,
    count: int,
    hall: Rect,
    sides: tuple[float, float],
    rng: np.random.Generator,
) -> list[Rect]:
    """The side regions (``sides``: left and right widths) split into ``count - 1`` rooms."""
    left_w, right_w = sides
    others = count - 1
    rects: list[Rect] = []
    if left_w > 0:
        k_left = int(np.clip(round(others * left_w / (left_w + right_w)), 1, others - 1))
        rects += _split_with_retries(Rect(0.0, 0.0, left_w, hall.h), k_left, rng)
        others -= k_left
    rects += _split_with_retries(Rect(hall.x1, 0.0, plan.footprint.x1, hall.h), others, rng)
    return rects


def _add_real_rooms(
    plan: HousePlan,
    f: int,
    count: int,
    hall: Rect,
    sides: tuple[float, float],
    programme: list[str],
    openness: tuple[bool, bool],
    rng: np.random.Generator,
) -> None:
    """Rooms of storey ``f`` from its programme, open borders and doors; ``openness`` is
    (open-plan wanted, no open border at all)."""
    open_plan, walled = openness
    floor = plan.floors[f]
    stair_rects = [s.rect for s in plan.stairs if s.from_floor == f] + floor.holes
    for attempt in range(100):
        rects = _split_sides(plan, count, hall, sides, rng)
        want_open = open_plan and attempt < OPEN_TRIES
        assignment = assign_rooms(rects, programme, hall, plan.footprint, rng, want_open, walled)
        if assignment is None:
            continue
        floor.rooms = [RoomPlan(id=f"r{f}_0", type="hallway", floor=f, rect=hall)]
        for i, (rect, kind) in enumerate(zip(rects, assignment.types, strict=True), start=1):
            floor.rooms.append(RoomPlan(id=f"r{f}_{i}", type=kind, floor=f, rect=rect))
        floor.open_edges = _open_edges(floor, assignment.open_pairs, stair_rects)
        pairs = frozenset(
            frozenset(int(r.split("_")[1]) for r in e.rooms) for e in floor.open_edges
        )
        doors = connect_rooms(floor, stair_rects, rng, pairs)
        if doors is not None:
            floor.doors = doors
            _group_open_rooms(floor)
            return
    raise RuntimeError(f"could not connect the rooms of floor {f}")


def _open_edges(
    floor: FloorPlan, pairs: list[tuple[int, int]], stair_rects: list[Rect]
) -> list[Opening]:
    """Open spans for the assignment's pairs (rectangle index -1 is the hallway)."""
    out = []
    for i, j in pairs:
        a, b = floor.rooms[i + 1], floor.rooms[j + 1]
        span = shared_border(a.rect, b.rect)
        if span is None:
            continue
        hall_pair = i < 0 or j < 0
        blocked = blocked_intervals(floor, stair_rects, span[0], span[1]) if hall_pair else []
        minimum = FOYER_MIN if hall_pair or "entryway" in (a.type, b.type) else OPEN_MIN
        edge = open_edge(floor, (a.id, b.id), a.rect, b.rect, blocked, minimum)
        if edge is not None:
            out.append(edge)
    return out


def _group_open_rooms(floor: FloorPlan) -> None:
    """Give the rooms of each open space one ``open_group`` name."""
    parent = {room.id: room.id for room in floor.rooms}

    def root(room_id: str) -> str:
        while parent[room_id] != room_id:
            room_id = parent[room_id]
        return room_id

    for edge in floor.open_edges:
        a, b = (root(r) for r in edge.rooms)
        parent[max(a, b)] = min(a, b)
    members: dict[str, int] = {}
    for room in floor.rooms:
        members[root(room.id)] = members.get(root(room.id), 0) + 1
    names = {
        r: f"open{floor.index}_{k}" for k, r in enumerate(r for r, n in members.items() if n > 1)
    }
    for room in floor.rooms:
        room.open_group = names.get(root(room.id), "")
