"""Doors of a floor plan, and the final pass that adds windows and wall lines.

Doors form a spanning tree over the room adjacency graph rooted at the hallway (every
room reachable), plus a few extra doors between rooms that often connect (kitchen and
dining room, …); rooms joined by an open border (:mod:`inherit_sg.ingest.synthetic.open_plan`)
need no door between them. Windows sit on exterior walls. Wall lines are the union of
room borders, open spans left out.
"""

from __future__ import annotations

import numpy as np

from inherit_sg.ingest.synthetic.geom import EPS, Rect, shared_border, subtract_intervals
from inherit_sg.ingest.synthetic.plan import DOOR_HEIGHT, WALL_T, FloorPlan, HousePlan, Opening
from inherit_sg.ingest.synthetic.walls import add_windows, build_walls

CORNER_MARGIN = 0.35  # keep openings this far from wall ends
EXTRA_DOOR_PAIRS = {
    frozenset(("kitchen", "dining room")),
    frozenset(("living room", "dining room")),
    frozenset(("bedroom", "bathroom")),
    frozenset(("kitchen", "laundry room")),
}


def blocked_intervals(
    floor: FloorPlan, stair_rects: list[Rect], axis: str, coord: float
) -> list[tuple[float, float]]:
    """Intervals of a wall line that stairs or stairwells make unusable for doors."""
    out: list[tuple[float, float]] = []
    if axis != "y":
        return out
    for r in stair_rects:
        if abs(r.x0 - WALL_T / 2 - coord) < 0.05 or abs(r.x1 + WALL_T / 2 - coord) < 0.05:
            out.append((r.y0 - 0.15, r.y1 + 0.15))
    return out


def _usable(
    span: tuple[str, float, float, float], blocked: list[tuple[float, float]], width: float
) -> list[tuple[float, float]]:
    _, _, lo, hi = span
    parts = subtract_intervals(lo + CORNER_MARGIN, hi - CORNER_MARGIN, blocked)
    return [(a, b) for a, b in parts if b - a >= width]


def _door(
    floor: FloorPlan,
    span: tuple[str, float, float, float],
    parts: list[tuple[float, float]],
    rooms: list[str],
    rng: np.random.Generator,
    width: float,
) -> Opening:
    a, b = parts[int(rng.integers(len(parts)))]
    lo = round(float(rng.uniform(a, max(a, b - width))), 3)
    return Opening(
        id="",
        kind="door",
        floor=floor.index,
        axis=span[0],
        coord=span[1],
        lo=lo,
        hi=round(lo + width, 3),
        z0=0.0,
        z1=DOOR_HEIGHT,
        rooms=rooms,
    )


def _spread(linked: set[int], open_pairs: frozenset[frozenset[int]]) -> None:
    """Add to ``linked`` every room joined to it through open borders."""
    grew = True
    while grew:
        grew = False
        for pair in open_pairs:
            if len(pair & linked) == 1:
                linked |= pair
                grew = True


def connect_rooms(
    floor: FloorPlan,
    stair_rects: list[Rect],
    rng: np.random.Generator,
    open_pairs: frozenset[frozenset[int]] = frozenset(),
) -> list[Opening] | None:
    """Doors joining every room of ``floor`` to its hallway (room 0); None if impossible.

    ``open_pairs`` (room indices) are joined by an open border already and get no door.
    """
    rooms = floor.rooms
    width = round(float(rng.uniform(0.85, 1.0)), 2)
    options: dict[
        tuple[int, int], tuple[tuple[str, float, float, float], list[tuple[float, float]]]
    ] = {}
    for i in range(len(rooms)):
        for j in range(i + 1, len(rooms)):
            span = shared_border(rooms[i].rect, rooms[j].rect)
            if span is None or frozenset((i, j)) in open_pairs:
                continue
            parts = _usable(span, blocked_intervals(floor, stair_rects, span[0], span[1]), width)
            if parts:
                options[(i, j)] = (span, parts)
    doors: list[Opening] = []
    linked = {0}
    for (i, j), (span, parts) in sorted(options.items()):
        if i == 0:
            doors.append(_door(floor, span, parts, [rooms[0].id, rooms[j].id], rng, width))
            linked.add(j)
    _spread(linked, open_pairs)
    while len(linked) < len(rooms):
        frontier = [(i, j) for (i, j) in sorted(options) if (i in linked) != (j in linked)]
        if not frontier:
            return None
        i, j = frontier[int(rng.integers(len(frontier)))]
        span, parts = options[(i, j)]
        doors.append(_door(floor, span, parts, [rooms[i].id, rooms[j].id], rng, width))
        linked |= {i, j}
        _spread(linked, open_pairs)
    doored = {frozenset(d.rooms) for d in doors}
    for (i, j), (span, parts) in sorted(options.items()):
        pair = frozenset((rooms[i].type, rooms[j].type))
        if frozenset((rooms[i].id, rooms[j].id)) in doored or i == 0:
            continue
        if (pair in EXTRA_DOOR_PAIRS and rng.random() < 0.6) or rng.random() < 0.1:
            doors.append(_door(floor, span, parts, [rooms[i].id, rooms[j].id], rng, width))
    return doors


def _front_door(plan: HousePlan, rng: np.random.Generator) -> Opening:
    """The front door: in the foyer's street wall when the house has a foyer (an
    entryway on the ground floor touching the front or back of the house), else at an
    end of the ground-floor hallway."""
    fp = plan.footprint
    entry = next(
        (
            r
            for r in plan.floors[0].rooms
            if r.type == "entryway"
            and (abs(r.rect.y0 - fp.y0) < EPS or abs(r.rect.y1 - fp.y1) < EPS)
        ),
        None,
    )
    width = 1.0
    if entry is not None:
        r = entry.rect
        y = r.y0 if abs(r.y0 - fp.y0) < EPS else r.y1
        a, b = r.x0 + CORNER_MARGIN, r.x1 - CORNER_MARGIN - width
        lo = round(float(rng.uniform(a, b)) if b > a else r.cx - width / 2, 3)
        room = entry
    else:
        room = plan.floors[0].rooms[0]
        hall = room.rect
        y = hall.y0 if rng.random() < 0.5 else hall.y1
        lo = round(hall.cx - width / 2, 3)
    return Opening(
        id="",
        kind="door",
        floor=0,
        axis="x",
        coord=y,
        lo=lo,
        hi=lo + width,
        z0=0.0,
        z1=DOOR_HEIGHT,
        rooms=[room.id],
    )


def add_openings(plan: HousePlan, rng: np.random.Generator) -> None:
    """Front door, windows, wall lines and opening ids for a plan whose doors are set."""
    plan.floors[0].doors.append(_front_door(plan, rng))
    for floor in plan.floors:
        add_windows(plan, floor, rng)
        build_walls(plan, floor)
    n_door = n_window = 0
    for floor in plan.floors:
        for door in floor.doors:
            door.id = f"d{n_door}"
            n_door += 1
        for window in floor.windows:
            window.id = f"w{n_window}"
            n_window += 1
    for n, edge in enumerate(e for floor in plan.floors for e in floor.open_edges):
        edge.id = f"p{n}"
