"""Plain data of a house floor plan: rooms, wall lines, openings, stairs, storeys.

The plan is the single source the furnisher, the mesh builder and the trajectory
planner read. Walls run along room borders (their centre lines), so a room's polygon
is the rectangle between wall centre lines.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from inherit_sg.ingest.synthetic.geom import Rect

WALL_T = 0.12  # wall thickness
SLAB_T = 0.2  # floor slab thickness
DOOR_HEIGHT = 2.05  # clear height of a door opening
STAIR_WIDTH = 1.0  # width of a straight staircase


@dataclass
class RoomPlan:
    """One rectangular room."""

    id: str
    type: str
    floor: int
    rect: Rect
    name: str = ""
    open_group: str = ""  # rooms of one open-plan space share it ("" = walled room)


@dataclass
class Opening:
    """A door or window hole in the wall line ``axis``/``coord`` spanning ``[lo, hi]``.

    ``axis`` is the direction the wall runs: ``"x"`` is the line ``y = coord``, ``"y"`` the
    line ``x = coord``. ``z0``/``z1`` are heights above the storey's floor.
    """

    id: str
    kind: str  # "door" | "window" | "open" (a border without a wall)
    floor: int
    axis: str
    coord: float
    lo: float
    hi: float
    z0: float
    z1: float
    rooms: list[str] = field(default_factory=list)

    @property
    def width(self) -> float:
        """Opening width along the wall."""
        return self.hi - self.lo

    @property
    def center_xy(self) -> tuple[float, float]:
        """Centre of the opening in plan."""
        mid = (self.lo + self.hi) / 2.0
        return (mid, self.coord) if self.axis == "x" else (self.coord, mid)

    def rect(self, depth: float) -> Rect:
        """Plan rectangle of the opening, ``depth`` thick across the wall."""
        d = depth / 2.0
        if self.axis == "x":
            return Rect(self.lo, self.coord - d, self.hi, self.coord + d)
        return Rect(self.coord - d, self.lo, self.coord + d, self.hi)


@dataclass
class WallLine:
    """A straight wall segment along a wall line."""

    floor: int
    axis: str
    coord: float
    lo: float
    hi: float
    exterior: bool = False


@dataclass
class StairPlan:
    """A straight staircase from ``from_floor`` to the storey above, running along y."""

    id: str
    from_floor: int
    rect: Rect  # footprint of the steps
    direction: int  # +1: climbs towards +y, -1: towards -y
    n_steps: int
    z0: float  # floor surface at the bottom
    z1: float  # floor surface at the top
    room_bottom: str
    room_top: str

    @property
    def rise(self) -> float:
        """Height of one step."""
        return (self.z1 - self.z0) / self.n_steps

    @property
    def tread(self) -> float:
        """Depth of one step."""
        return self.rect.h / self.n_steps

    @property
    def y_bottom(self) -> float:
        """y of the first step's front edge."""
        return self.rect.y0 if self.direction > 0 else self.rect.y1

    @property
    def y_top(self) -> float:
        """y of the last step's back edge."""
        return self.rect.y1 if self.direction > 0 else self.rect.y0

    def surface_z(self, y: float) -> float:
        """Height of the walking ramp (step nosings) at ``y`` along the run."""
        s = (y - self.y_bottom) * self.direction / self.rect.h
        s = min(max(s, 0.0), 1.0)
        return self.z0 + s * (self.z1 - self.z0)


@dataclass
class FloorPlan:
    """One storey: floor surface at ``z``, ceiling at ``z + height``."""

    index: int
    z: float
    height: float
    rooms: list[RoomPlan] = field(default_factory=list)
    walls: list[WallLine] = field(default_factory=list)
    doors: list[Opening] = field(default_factory=list)
    windows: list[Opening] = field(default_factory=list)
    holes: list[Rect] = field(default_factory=list)  # stairwell openings in this slab
    stair_zones: list[Rect] = field(default_factory=list)  # stairs + landings, kept clear
    open_edges: list[Opening] = field(default_factory=list)  # borders without walls

    def room_at(self, x: float, y: float) -> RoomPlan | None:
        """The room containing the plan point, if any."""
        for room in self.rooms:
            if room.rect.contains(x, y):
                return room
        return None


@dataclass
class HousePlan:
    """The whole building."""

    footprint: Rect
    level_spacing: float
    floors: list[FloorPlan] = field(default_factory=list)
    stairs: list[StairPlan] = field(default_factory=list)
    style: str = "classic"  # the generator that drew it ("real" or "classic")

    def room(self, room_id: str) -> RoomPlan:
        """The room with ``room_id`` (KeyError if absent)."""
        for floor in self.floors:
            for room in floor.rooms:
                if room.id == room_id:
                    return room
        raise KeyError(room_id)

    @property
    def all_rooms(self) -> list[RoomPlan]:
        """Rooms of every storey, lowest first."""
        return [room for floor in self.floors for room in floor.rooms]
