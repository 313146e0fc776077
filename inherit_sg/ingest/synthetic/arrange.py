"""Where each member of a functional group goes relative to the group's anchor: chairs
around tables, nightstands beside beds, a coffee table before the sofa, appliances in a
row along one wall, small things on surfaces."""

from __future__ import annotations

import numpy as np

from inherit_sg.ingest.synthetic.geom import Box, Rect
from inherit_sg.ingest.synthetic.placement import FRONT, SIDES, WALL_QUARTER, Placed, RoomSpace
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

TABLES = (
    "table",
    "dining table",
    "desk",
    "workbench",
    "coffee table",
    "kitchen island",
    "bar counter",
    "picnic table",
)
SEATS = ("chair", "stool", "dining chair", "office chair", "bar stool", "outdoor chair")
SHELF_LEVELS = (0.26, 0.51, 0.76)  # bookshelf board tops, as fractions of its height
# Where small objects rest on kinds that are not flat on top: (height, local x range and y
# range as fractions of the width and depth; the front is -y).
SUPPORT_TOPS: dict[str, tuple[float, tuple[float, float], tuple[float, float]]] = {
    "bed": (0.75, (-0.46, 0.46), (-0.46, 0.3)),
    "sofa": (0.45, (-0.36, 0.36), (-0.48, 0.26)),
    "armchair": (0.45, (-0.33, 0.33), (-0.48, 0.26)),
    "recliner": (0.45, (-0.33, 0.33), (-0.48, 0.26)),
    "toilet": (1.0, (-0.45, 0.45), (0.28, 0.48)),
}
# Supporters a small object prefers, best first.
PREFERRED: dict[str, tuple[str, ...]] = {
    "tv": ("tv stand",),
    "monitor": ("desk",),
    "laptop": ("desk", "table"),
    "table lamp": ("nightstand", "desk", "dresser"),
    "book": ("bookshelf", "nightstand", "coffee table"),
    "microwave": ("counter",),
    "kettle": ("counter",),
    "mug": ("coffee table", "table", "counter", "desk", "dining table"),
    "plate": ("dining table", "table"),
    "bowl": ("dining table", "table", "counter"),
    "toolbox": ("workbench",),
    "basket": ("washing machine", "dryer"),
    "vase": ("coffee table", "cabinet", "dining table"),
}


def set_pose(obj: Placed, x: float, y: float, quarter: int) -> Placed:
    """Move ``obj`` (in place) and return it."""
    obj.x, obj.y, obj.quarter = round(x, 3), round(y, 3), quarter % 4
    return obj


def side_of(space: RoomSpace, obj: Placed) -> str:
    """The wall side an object's back is against (by its quarter turn)."""
    return {v: k for k, v in WALL_QUARTER.items()}[obj.quarter]


def along(obj: Placed, side: str) -> tuple[float, float]:
    """(centre, half extent) of ``obj`` along wall ``side``."""
    ex, ey = obj.extent
    return (obj.x, ex / 2) if side in ("N", "S") else (obj.y, ey / 2)


def on_wall(space: RoomSpace, obj: Placed, side: str, t: float) -> bool:
    """Put ``obj`` against wall ``side`` centred at ``t``; whether it fits."""
    quarter = WALL_QUARTER[side]
    x, y = space.wall_spot(side, t, obj.dims)
    set_pose(obj, x, y, quarter)
    return space.fits(obj)


def random_wall(space: RoomSpace, obj: Placed, rng: np.random.Generator, tries: int = 40) -> bool:
    """Against a random wall at a random place."""
    for _ in range(tries):
        side = SIDES[int(rng.integers(4))]
        lo, hi = space.wall_range(side)
        half = obj.dims[0] / 2
        if hi - lo < 2 * half:
            continue
        if on_wall(space, obj, side, float(rng.uniform(lo + half, hi - half))):
            return True
    return False


def facing(dx: float, dy: float) -> int:
    """Quarter turn whose front points along (dx, dy)."""
    if abs(dx) > abs(dy):
        return 1 if dx > 0 else 3
    return 2 if dy > 0 else 0


def free_spot(
    space: RoomSpace, obj: Placed, rng: np.random.Generator, margin: float = 0.0, tries: int = 60
) -> bool:
    """Anywhere in the room, biased to the middle, facing the room centre; with ``margin``
    of clear floor all around (for chairs to come)."""
    r = space.interior
    for _ in range(tries):
        x = float(np.clip(rng.normal(r.cx, r.w / 5), r.x0, r.x1))
        y = float(np.clip(rng.normal(r.cy, r.h / 5), r.y0, r.y1))
        quarter = int(rng.integers(4)) if obj.label in TABLES else facing(r.cx - x, r.cy - y)
        set_pose(obj, x, y, quarter)
        if not space.fits(obj):
            continue
        if margin > 0:
            grown = obj.footprint.grown(margin)
            if not space.interior.contains_rect(grown):
                continue
            if not space.clear(Box(grown, obj.z, obj.top), ignore=(obj,)):
                continue
        return True
    return False


def beside_on_wall(space: RoomSpace, obj: Placed, anchor: Placed, rng: np.random.Generator) -> bool:
    """Next to ``anchor`` along the wall it stands against, either side."""
    side = side_of(space, anchor)
    centre, half = along(anchor, side)
    gap = float(rng.uniform(0.03, 0.25))
    for sign in rng.permutation([-1.0, 1.0]):
        t = centre + sign * (half + gap + obj.dims[0] / 2)
        if on_wall(space, obj, side, t):
            return True
    return False


def seat_slots(table: Placed, seat: Placed, wall_table: bool) -> list[tuple[float, float, int]]:
    """Chair positions around a table, each facing it; long sides first."""
    ex, ey = table.extent
    sd = seat.dims[1] / 2 + 0.06
    fx, fy = FRONT[table.quarter]
    if wall_table:
        x, y = (
            table.x + fx * (ex / 2 * abs(fx) + ey / 2 * abs(fy) + sd),
            table.y + fy * (ey / 2 * abs(fy) + ex / 2 * abs(fx) + sd),
        )
        return [(x, y, facing(table.x - x, table.y - y))]
    slots = []
    long_x = ex >= ey
    offs = (-ex / 4, ex / 4) if long_x and ex > 1.2 else (0.0,)
    for o in offs:
        slots += [(table.x + o, table.y - ey / 2 - sd, 2), (table.x + o, table.y + ey / 2 + sd, 0)]
    slots += [(table.x - ex / 2 - sd, table.y, 1), (table.x + ex / 2 + sd, table.y, 3)]
    if not long_x:
        slots = slots[-2:] + slots[:-2]
    return slots


def near_anchor(space: RoomSpace, obj: Placed, anchor: Placed, rng: np.random.Generator) -> bool:
    """Somewhere close to ``anchor``, facing it."""
    box = anchor.footprint
    for _ in range(40):
        dist = float(rng.uniform(0.1, 0.9))
        x = float(rng.uniform(box.x0 - dist - obj.extent[0], box.x1 + dist + obj.extent[0]))
        y = float(rng.uniform(box.y0 - dist - obj.extent[1], box.y1 + dist + obj.extent[1]))
        set_pose(obj, x, y, facing(anchor.x - x, anchor.y - y))
        if space.fits(obj):
            return True
    return False


def in_front(space: RoomSpace, obj: Placed, anchor: Placed, gap: float) -> bool:
    """Centred in front of ``anchor``, turned like it."""
    fx, fy = FRONT[anchor.quarter]
    reach = anchor.dims[1] / 2 + gap + obj.dims[1] / 2
    return _try(space, obj, anchor.x + fx * reach, anchor.y + fy * reach, anchor.quarter)


def facing_wall(space: RoomSpace, obj: Placed, anchor: Placed, rng: np.random.Generator) -> bool:
    """Against the wall opposite ``anchor``'s wall, looking at it (tv stand before a sofa)."""
    side = side_of(space, anchor)
    opposite = {"N": "S", "S": "N", "E": "W", "W": "E"}[side]
    centre, _ = along(anchor, side)
    for jitter in (0.0, *rng.uniform(-1.0, 1.0, 6)):
        if on_wall(space, obj, opposite, centre + float(jitter)):
            return True
    return False


def _try(space: RoomSpace, obj: Placed, x: float, y: float, quarter: int) -> bool:
    set_pose(obj, x, y, quarter)
    return space.fits(obj)


def has_shelves(obj: Placed) -> bool:
    """Whether ``obj`` has shelf boards at :data:`SHELF_LEVELS`."""
    return obj.label == "bookshelf" or OBJECT_KINDS[obj.label].shelves


def support_levels(obj: Placed) -> list[float]:
    """World heights small objects can stand at on ``obj``, preferred first."""
    h = obj.dims[2]
    if obj.label == "bookshelf":
        return [obj.z + h * SHELF_LEVELS[2], obj.z + h * SHELF_LEVELS[1]]
    if has_shelves(obj):
        return [obj.z + h * f for f in (1.0, SHELF_LEVELS[2], SHELF_LEVELS[1], SHELF_LEVELS[0])]
    return [obj.top]


def level_room(obj: Placed, level: float) -> float:
    """Clear height above a support level of ``obj``."""
    if has_shelves(obj):
        h = obj.dims[2]
        tops = [obj.z + h * f for f in (*SHELF_LEVELS, 1.0)]
        above = [t for t in tops if t > level + 1e-6]
        return (min(above) - 0.03 - level) if above else 10.0
    return 10.0


def local_rect(obj: Placed, x0: float, x1: float, y0: float, y1: float) -> Rect:
    """World footprint of the local rectangle ``[x0, x1] × [y0, y1]`` of ``obj``."""
    corners = [(x0, y0), (x1, y1)]
    for _ in range(obj.quarter % 4):
        corners = [(-y, x) for x, y in corners]
    xs, ys = [obj.x + c[0] for c in corners], [obj.y + c[1] for c in corners]
    return Rect(min(xs), min(ys), max(xs), max(ys))


def support_spots(obj: Placed) -> list[tuple[float, Rect]]:
    """Where small objects can stand on ``obj``: (world height, footprint) pairs,
    preferred first: its top or shelves, a bed's mattress, a sofa's seat, a toilet's tank."""
    top = SUPPORT_TOPS.get(obj.label)
    if top is None:
        rect = obj.footprint.grown(-0.02)
        return [(level, rect) for level in support_levels(obj)]
    f, (x0, x1), (y0, y1) = top
    w, d, h = obj.dims
    return [(obj.z + f * h, local_rect(obj, x0 * w, x1 * w, y0 * d, y1 * d))]


def on_surface(
    space: RoomSpace,
    obj: Placed,
    support: Placed,
    rng: np.random.Generator,
    keepout: bool = True,
) -> bool:
    """Stand ``obj`` on ``support`` (top, shelf or seat) without touching other things
    (nor keep-out zones, unless ``keepout`` is off: a vase on a counter under a window)."""
    obj.quarter = support.quarter
    ex, ey = obj.extent
    for level, top in support_spots(support):
        if ex > top.w or ey > top.h:
            continue
        if obj.dims[2] > level_room(support, level):
            continue
        for _ in range(25):
            x = float(rng.uniform(top.x0 + ex / 2, top.x1 - ex / 2))
            y = float(rng.uniform(top.y0 + ey / 2, top.y1 - ey / 2))
            set_pose(obj, x, y, support.quarter)
            obj.z = round(level, 4)
            if space.fits(obj, ignore=(support,), keepout=keepout):
                obj.support = support
                return True
    return False
