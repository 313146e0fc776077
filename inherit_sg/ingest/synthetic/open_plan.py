"""Open connections between rooms: spans of a shared border without a wall.

An open-plan ground floor joins the kitchen, the dining room and the living room (and
sometimes the entryway) into one space: the borders they share get no wall and no door,
while each keeps its own region (polygon and type) in the ground truth, as Matterport3D
annotators draw them. A foyer may also open onto the hallway. The open spans are
:class:`~inherit_sg.ingest.synthetic.plan.Opening` records of kind ``"open"`` in
``FloorPlan.open_edges``; wall lines leave them out, and furnishing keeps a strip along
them clear so the joined rooms stay one walkable space.
"""

from __future__ import annotations

from inherit_sg.ingest.synthetic.geom import EPS, Rect, shared_border, subtract_intervals
from inherit_sg.ingest.synthetic.plan import FloorPlan, Opening, WallLine

OPEN_MIN = 1.8  # shortest shared border that makes two rooms one open space
FOYER_MIN = 1.2  # shortest open span between a foyer and the hallway


def border_length(a: Rect, b: Rect) -> float:
    """Length of the border two rectangles share (0 when they do not touch)."""
    span = shared_border(a, b)
    return span[3] - span[2] if span is not None else 0.0


def open_edge(
    floor: FloorPlan,
    rooms: tuple[str, str],
    a: Rect,
    b: Rect,
    blocked: list[tuple[float, float]],
    minimum: float,
) -> Opening | None:
    """The open span between two rooms (their shared border minus ``blocked``
    intervals, the longest piece), or None when no piece is ``minimum`` long."""
    span = shared_border(a, b)
    if span is None:
        return None
    axis, coord, lo, hi = span
    pieces = subtract_intervals(lo, hi, blocked)
    if not pieces:
        return None
    p0, p1 = max(pieces, key=lambda p: p[1] - p[0])
    if p1 - p0 < minimum - EPS:
        return None
    return Opening(
        id="",
        kind="open",
        floor=floor.index,
        axis=axis,
        coord=coord,
        lo=round(p0, 4),
        hi=round(p1, 4),
        z0=0.0,
        z1=floor.height,
        rooms=list(rooms),
    )


def without_open_spans(floor: FloorPlan, walls: list[WallLine]) -> list[WallLine]:
    """``walls`` with the floor's open spans cut out."""
    out: list[WallLine] = []
    for wall in walls:
        gaps = [
            (o.lo, o.hi)
            for o in floor.open_edges
            if o.axis == wall.axis and abs(o.coord - wall.coord) < EPS
        ]
        for lo, hi in subtract_intervals(wall.lo, wall.hi, gaps):
            out.append(WallLine(wall.floor, wall.axis, wall.coord, lo, hi, wall.exterior))
    return out


def open_neighbours(floor: FloorPlan, room_id: str) -> list[str]:
    """Ids of the rooms ``room_id`` opens onto without a wall."""
    out = []
    for edge in floor.open_edges:
        if room_id in edge.rooms:
            out += [r for r in edge.rooms if r != room_id]
    return sorted(set(out))
