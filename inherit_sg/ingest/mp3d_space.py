"""Levels of an MP3D house and their occupancy at walking height.

A :class:`Level` groups the regions of one storey with clean counter-clockwise outlines.
A :class:`LevelSpace` rasterises it on a 5 cm grid: which region covers each cell and
which cells furniture blocks (object footprints whose boxes start lower than a walking
person's height; floor coverings and doors do not block). The wall planner asks it where
a doorway has room to pass, the walk builds its free space from it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from inherit_sg.ingest.mp3d_house import HouseFile
from inherit_sg.ingest.mp3d_polygons import clean_ccw, convex_hull, rasterise
from inherit_sg.ingest.synthetic.geom import Rect
from inherit_sg.ingest.synthetic.grid import Grid
from inherit_sg.ingest.synthetic.planner import BODY
from inherit_sg.ingest.synthetic.scene import RoomGT

RES = 0.05  # grid cell size, metres
MARGIN = 0.6  # grid margin around the regions, metres
# Objects one walks over or through: they never block the walk.
FLOOR_COVERINGS = {"rug", "carpet", "mat", "doormat", "floor mat", "bath mat", "shower floor"}


@dataclass
class Level:
    """One storey: its regions (rooms) and their floor height (median of the regions')."""

    index: int
    z: float
    rooms: list[RoomGT]
    outlines: dict[str, np.ndarray]  # room id -> (N, 2) counter-clockwise outline
    ceilings: dict[str, float]  # room id -> absolute ceiling height

    def bounds(self, margin: float = MARGIN) -> Rect:
        """Plan rectangle around all regions of the level."""
        pts = np.concatenate(list(self.outlines.values()))
        lo, hi = pts.min(axis=0) - margin, pts.max(axis=0) + margin
        return Rect(float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def house_levels(house: HouseFile) -> list[Level]:
    """The levels of a parsed house, lowest first (levels without regions are left out)."""
    out = []
    for floor in house.scene.floors:
        rooms = [r for r in house.scene.rooms if r.floor == floor.index]
        if not rooms:
            continue
        floor_z = {r.id: house.region_floor_z.get(r.id, floor.z) for r in rooms}
        out.append(
            Level(
                index=floor.index,
                z=float(np.median(list(floor_z.values()))),
                rooms=rooms,
                outlines={r.id: clean_ccw(r.polygon) for r in rooms},
                ceilings={r.id: floor_z[r.id] + house.region_heights[r.id] for r in rooms},
            )
        )
    return out


def blocks_walking(label: str, bottom: float, floor_z: float) -> bool:
    """Whether an object with this label and box bottom blocks a walking person."""
    return label != "door" and label not in FLOOR_COVERINGS and bottom - floor_z < BODY


class LevelSpace:
    """Region and furniture rasters of one level."""

    def __init__(self, house: HouseFile, level: Level) -> None:
        self.level = level
        self.grid = Grid(level.bounds(), RES)
        self.room_ids = [r.id for r in level.rooms]
        self.rooms = np.full(self.grid.shape, -1, dtype=np.int32)
        for k, room_id in enumerate(self.room_ids):
            self.rooms[rasterise(self.grid, level.outlines[room_id])] = k
        self.furniture = np.zeros(self.grid.shape, dtype=bool)
        for obj in house.scene.objects:
            if obj.floor != level.index or obj.id not in house.boxes:
                continue
            if blocks_walking(obj.label, obj.bbox_min[2], level.z):
                corners = house.boxes[obj.id].corners()
                self.furniture |= rasterise(self.grid, convex_hull(corners[:, :2]))
        self.furniture_clearance = self.grid.clearance(self.furniture)

    def block(self, corners: list[np.ndarray]) -> None:
        """Add the footprints of further furniture boxes ((8, 3) corners each): boxes
        drawn larger than annotated (:mod:`inherit_sg.ingest.mp3d_drawn`) must not be walked into."""
        for c in corners:
            self.furniture |= rasterise(self.grid, convex_hull(np.asarray(c)[:, :2]))
        self.furniture_clearance = self.grid.clearance(self.furniture)

    def clearance(self, points: np.ndarray) -> np.ndarray:
        """Distance (m) from each (N, 2) plan point to the nearest furniture."""
        cells = [self.grid.cell(float(x), float(y)) for x, y in points]
        return np.array([self.furniture_clearance[i, j] for i, j in cells])

    def room_at(self, x: float, y: float) -> str | None:
        """Id of the region covering a plan point (None between or outside regions)."""
        i, j = self.grid.cell(x, y)
        k = int(self.rooms[i, j])
        return self.room_ids[k] if k >= 0 else None
