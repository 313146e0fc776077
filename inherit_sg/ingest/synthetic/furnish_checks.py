"""The furnished room must stay walkable: every doorway and open border reachable from
every other through the room, with room to stand."""

from __future__ import annotations

from inherit_sg.ingest.synthetic.geom import Rect
from inherit_sg.ingest.synthetic.grid import Grid, components, free_space
from inherit_sg.ingest.synthetic.placement import RoomSpace
from inherit_sg.ingest.synthetic.planner import BODY, RADIUS

# Wider than the walker (by two grid cells) so the check holds on any grid alignment.
ROBOT_RADIUS = RADIUS + 0.1


def walkable(space: RoomSpace) -> bool:
    """Whether every doorway (and open border) of the room is reachable from every other
    through it."""
    grid = Grid(space.interior, 0.05)
    fl = space.floor
    obstacles: list[Rect] = [
        o.footprint for o in space.objects if not o.flat and o.z - fl.z < BODY and o.support is None
    ]
    obstacles += space.obstacles
    free = free_space(grid, obstacles, ROBOT_RADIUS)
    labels = components(free)
    seen = set()
    for door in fl.doors + fl.open_edges:
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
