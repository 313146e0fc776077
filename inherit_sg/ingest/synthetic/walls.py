"""Windows on exterior walls and the wall lines of a floor plan (the union of room
borders)."""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from inherit_sg.ingest.synthetic.geom import EPS, Rect, subtract_intervals
from inherit_sg.ingest.synthetic.open_plan import without_open_spans
from inherit_sg.ingest.synthetic.plan import FloorPlan, HousePlan, Opening, WallLine

# Rooms of real-world houses whose windows sit above worktops.
WORKTOP_ROOMS = frozenset({"kitchen", "bar"})
# Rooms whose windows are small and high.
SMALL_WINDOW_ROOMS = frozenset({"bathroom", "laundry room", "toilet", "closet", "utility room"})


def _exterior_edges(rect: Rect, fp: Rect) -> list[tuple[str, float, float, float]]:
    edges = []
    if abs(rect.y0 - fp.y0) < EPS:
        edges.append(("x", rect.y0, rect.x0, rect.x1))
    if abs(rect.y1 - fp.y1) < EPS:
        edges.append(("x", rect.y1, rect.x0, rect.x1))
    if abs(rect.x0 - fp.x0) < EPS:
        edges.append(("y", rect.x0, rect.y0, rect.y1))
    if abs(rect.x1 - fp.x1) < EPS:
        edges.append(("y", rect.x1, rect.y0, rect.y1))
    return edges


def add_windows(plan: HousePlan, floor: FloorPlan, rng: np.random.Generator) -> None:
    """Put one or two windows on the exterior walls of each room."""
    for room in floor.rooms:
        edges = _exterior_edges(room.rect, plan.footprint)
        if not edges:
            continue
        longest = max(e[3] - e[2] for e in edges)
        count = 2 if longest > 3.6 else 1
        if room.type == "hallway":
            count = int(rng.random() < 0.5)
        if room.type == "closet":
            count = int(rng.random() < 0.3)
        small = room.type in SMALL_WINDOW_ROOMS
        for _ in range(count):
            width = round(float(rng.uniform(0.6, 0.8) if small else rng.uniform(0.9, 1.5)), 2)
            sill, top = (1.4, 2.1) if small else (0.9, 2.1)
            if plan.style == "real" and room.type in WORKTOP_ROOMS:
                sill = 1.05  # above the worktops
            choices = []
            for axis, coord, lo, hi in edges:
                taken = [
                    (o.lo - 0.4, o.hi + 0.4)
                    for o in floor.doors + floor.windows
                    if o.axis == axis and abs(o.coord - coord) < EPS
                ]
                parts = subtract_intervals(lo + 0.45, hi - 0.45, taken)
                choices += [(axis, coord, a, b) for a, b in parts if b - a >= width]
            if not choices:
                break
            axis, coord, a, b = choices[int(rng.integers(len(choices)))]
            lo = round(float(rng.uniform(a, max(a, b - width))), 3)
            floor.windows.append(
                Opening(
                    id="",
                    kind="window",
                    floor=floor.index,
                    axis=axis,
                    coord=coord,
                    lo=lo,
                    hi=round(lo + width, 3),
                    z0=sill,
                    z1=top,
                    rooms=[room.id],
                )
            )


def build_walls(plan: HousePlan, floor: FloorPlan) -> None:
    """Union the room borders of ``floor`` into wall lines, leaving its open spans out."""
    lines: dict[tuple[str, float], list[tuple[float, float]]] = defaultdict(list)
    for room in floor.rooms:
        r = room.rect
        lines[("x", round(r.y0, 4))].append((r.x0, r.x1))
        lines[("x", round(r.y1, 4))].append((r.x0, r.x1))
        lines[("y", round(r.x0, 4))].append((r.y0, r.y1))
        lines[("y", round(r.x1, 4))].append((r.y0, r.y1))
    fp = plan.footprint
    for (axis, coord), spans in sorted(lines.items()):
        spans.sort()
        merged: list[list[float]] = []
        for lo, hi in spans:
            if merged and lo <= merged[-1][1] + EPS:
                merged[-1][1] = max(merged[-1][1], hi)
            else:
                merged.append([lo, hi])
        ext = (axis == "x" and coord in (round(fp.y0, 4), round(fp.y1, 4))) or (
            axis == "y" and coord in (round(fp.x0, 4), round(fp.x1, 4))
        )
        for lo, hi in merged:
            floor.walls.append(WallLine(floor.index, axis, coord, lo, hi, exterior=ext))
    floor.walls = without_open_spans(floor, floor.walls)
