"""Placed objects and the free-space bookkeeping of one room while it is furnished.

Objects turn only by quarter turns, so their world boxes stay axis-aligned and exact.
An object's local frame has x along its width, y along its depth and z up, origin at
the centre of its footprint on its bottom; its front faces local -y.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from inherit_sg.ingest.synthetic.geom import Box, Rect
from inherit_sg.ingest.synthetic.plan import WALL_T, FloorPlan, RoomPlan
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

# Unit vector each quarter turn's front faces.
FRONT = {0: (0.0, -1.0), 1: (1.0, 0.0), 2: (0.0, 1.0), 3: (-1.0, 0.0)}
# Quarter turn that puts an object's back against the wall on that side of the room.
WALL_QUARTER = {"N": 0, "E": 3, "S": 2, "W": 1}
SIDES = ("N", "E", "S", "W")
GAP = 0.03  # minimum clearance between pieces of furniture
FLAT = 0.05  # objects lower than this (rugs) lie under furniture and are not obstacles
OPEN_CLEAR = 0.55  # depth kept clear on each side of an open border


@dataclass(eq=False)
class Placed:
    """One object instance in the world, before ids are final."""

    label: str
    floor: int
    room_id: str | None
    x: float
    y: float
    z: float  # bottom, world frame
    dims: tuple[float, float, float]  # width, depth, height before turning
    quarter: int
    colour: str  # a classic palette name, or the basic colour term of ``rgb``
    material: str
    scale: float = 1.0
    structural: bool = False
    support: Placed | None = None
    params: dict[str, Any] = field(default_factory=dict)
    id: str = ""
    instance_id: int = 0
    rgb: tuple[int, int, int] | None = None  # sampled sRGB albedo (None: the palette colour)
    raw: str = ""  # the Matterport3D raw category name it would be annotated with

    @property
    def extent(self) -> tuple[float, float]:
        """Footprint size along world x and y."""
        w, d, _ = self.dims
        return (w, d) if self.quarter % 2 == 0 else (d, w)

    @property
    def footprint(self) -> Rect:
        """World footprint."""
        ex, ey = self.extent
        return Rect(self.x - ex / 2, self.y - ey / 2, self.x + ex / 2, self.y + ey / 2)

    @property
    def top(self) -> float:
        """World height of the top."""
        return self.z + self.dims[2]

    @property
    def box(self) -> Box:
        """World bounding box."""
        return Box(self.footprint, self.z, self.top)

    @property
    def flat(self) -> bool:
        """Whether the object is a thin floor covering."""
        return self.dims[2] < FLAT


@dataclass
class AreaPlan:
    """A placed functional group."""

    label: str
    room_id: str
    members: list[Placed] = field(default_factory=list)
    id: str = ""


def size_word(scale: float) -> str:
    """small / medium / large from an object's scale relative to its kind."""
    if scale < 0.93:
        return "small"
    return "large" if scale > 1.1 else "medium"


@dataclass
class RoomSpace:
    """Free-space bookkeeping for furnishing one room."""

    room: RoomPlan
    floor: FloorPlan
    keepout: list[Box] = field(default_factory=list)  # heights relative to the floor
    objects: list[Placed] = field(default_factory=list)
    obstacles: list[Rect] = field(default_factory=list)  # stairs and stairwells

    @property
    def interior(self) -> Rect:
        """The room rectangle inside its walls."""
        return self.room.rect.grown(-WALL_T / 2 - 0.01)

    def fits(self, obj: Placed, ignore: tuple[Placed, ...] = (), keepout: bool = True) -> bool:
        """Whether ``obj`` stands inside the room without touching anything (keep-out
        zones left aside when not ``keepout``: things standing on a supporter)."""
        if not self.interior.contains_rect(obj.footprint):
            return False
        return obj.flat or self.clear(obj.box, ignore, keepout)

    def clear(self, box: Box, ignore: tuple[Placed, ...] = (), keepout: bool = True) -> bool:
        """Whether the world ``box`` is free of keep-out zones and placed objects."""
        rel = Box(box.rect, box.z0 - self.floor.z, box.z1 - self.floor.z)
        if keepout and any(rel.overlaps(k) for k in self.keepout):
            return False
        return not any(
            box.overlaps(o.box, GAP) for o in self.objects if not o.flat and o not in ignore
        )

    def wall_spot(
        self, side: str, along: float, dims: tuple[float, float, float]
    ) -> tuple[float, float]:
        """Centre of an object with ``dims`` whose back touches wall ``side`` at ``along``."""
        r = self.interior
        d = dims[1] / 2 + 0.01
        if side == "N":
            return along, r.y1 - d
        if side == "S":
            return along, r.y0 + d
        if side == "E":
            return r.x1 - d, along
        return r.x0 + d, along

    def wall_range(self, side: str) -> tuple[float, float]:
        """Interval along wall ``side`` (x for N/S, y for E/W)."""
        r = self.interior
        return (r.x0, r.x1) if side in ("N", "S") else (r.y0, r.y1)


def build_keepout(space: RoomSpace) -> None:
    """Keep doorways, the space in front of windows, stair zones and a strip along open
    borders clear."""
    fl, room = space.floor, space.room
    near = room.rect.grown(0.05)
    for door in fl.doors:
        rect = door.rect(2.0)
        grown = (
            Rect(rect.x0 - 0.15, rect.y0, rect.x1 + 0.15, rect.y1)
            if door.axis == "x"
            else Rect(rect.x0, rect.y0 - 0.15, rect.x1, rect.y1 + 0.15)
        )
        if grown.overlaps(near):
            space.keepout.append(Box(grown, 0.0, door.z1 + 0.15))
    for win in fl.windows:
        rect = win.rect(0.8)
        if rect.overlaps(near):
            space.keepout.append(Box(rect.grown(0.05), win.z0 - 0.02, win.z1))
    for zone in fl.stair_zones:
        if zone.overlaps(near):
            space.keepout.append(Box(zone, 0.0, fl.height))
    for edge in fl.open_edges:
        if room.id in edge.rooms:
            # an open border stays clear, like a wide doorway, on both sides
            space.keepout.append(Box(edge.rect(2 * OPEN_CLEAR), 0.0, fl.height - 0.3))


def make_placed(label: str, space: RoomSpace, scale: float, colour: str, material: str) -> Placed:
    """An unplaced object of kind ``label`` at ``scale`` in ``space``'s room."""
    kind = OBJECT_KINDS[label]
    w, d, h = (round(v * scale, 3) for v in kind.size)
    return Placed(
        label=label,
        floor=space.room.floor,
        room_id=space.room.id,
        x=0.0,
        y=0.0,
        z=space.floor.z + kind.mount_height,
        dims=(w, d, h),
        quarter=0,
        colour=colour,
        material=material,
        scale=scale,
    )
