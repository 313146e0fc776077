"""Placements: is a node against a wall, in a corner or in the centre of its room?

Measured on the room's floor mask (:class:`~inherit_sg.model.RoomMask`). Per room, once
per snapshot, the mask's holes are filled (furniture standing in a room leaves holes in
free-space masks) and the Euclidean distance transform of the room cells gives each
cell's distance to the room's boundary.

- ``wall``: the distance from the node's box footprint to the boundary (the least over
  points along the footprint's edges; 0 where the footprint leaves the room) — 1 up to
  ``WALL_NEAR``, falling linearly to 0 at ``WALL_FAR``.
- ``corner``: rays marched along ±x and ±y from the footprint's sides give the nearest
  boundary along each axis; the score is the worse of the two axes, graded like a wall
  (rooms are taken as axis-aligned).
- ``centre``: ``1 - d / (CENTRE_SCALE · extent)`` clipped to [0, 1], with ``d`` the
  distance from the node's centre to the room's centroid and ``extent`` the longer side
  of the room's bounding box.

Nodes without a room or a mask get no value (``None``): the scorer counts them as
unknown, between a match and a mismatch.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from inherit_sg.model import AreaNode, ObjectNode, RoomMask
from inherit_sg.retrieval.snapshot import MapSnapshot

WALL_NEAR = 0.25
WALL_FAR = 1.0
CENTRE_SCALE = 0.35


def wall_grade(distance: float) -> float:
    """1 up to ``WALL_NEAR`` metres from a wall, linearly down to 0 at ``WALL_FAR``."""
    return float(np.clip((WALL_FAR - distance) / (WALL_FAR - WALL_NEAR), 0.0, 1.0))


@dataclass
class RoomField:
    """One room's filled mask (padded by one empty cell all round), the distance of each
    cell centre to the boundary in metres, its centroid and its longer side."""

    origin: tuple[float, float]
    resolution: float
    inside: np.ndarray
    wall: np.ndarray
    centroid: tuple[float, float]
    extent: float

    @classmethod
    def of(cls, mask: RoomMask) -> RoomField | None:
        """The field of ``mask`` (None when it covers no cell)."""
        filled = ndimage.binary_fill_holes(np.asarray(mask.cells, dtype=bool))
        if not filled.any():
            return None
        res = float(mask.resolution)
        inside = np.pad(filled, 1, constant_values=False)
        # distance between cell centres, less half a cell: centre to the boundary line
        wall = np.maximum(ndimage.distance_transform_edt(inside) - 0.5, 0.0) * res
        rows, cols = np.nonzero(inside)
        origin = (mask.origin_x - res, mask.origin_y - res)
        cx = origin[0] + (cols.mean() + 0.5) * res
        cy = origin[1] + (rows.mean() + 0.5) * res
        extent = max(np.ptp(cols) + 1, np.ptp(rows) + 1) * res
        return cls(origin, res, inside, wall, (float(cx), float(cy)), float(extent))

    def cell(self, x: float, y: float) -> tuple[int, int] | None:
        """(row, col) of a world point, None outside the grid."""
        c = math.floor((x - self.origin[0]) / self.resolution)
        r = math.floor((y - self.origin[1]) / self.resolution)
        h, w = self.inside.shape
        return (r, c) if 0 <= r < h and 0 <= c < w else None

    def wall_distance(self, lo: tuple[float, float], hi: tuple[float, float]) -> float:
        """Least distance from the footprint's edges to the boundary (0 when the
        footprint leaves the room)."""
        step = self.resolution / 2
        xs = np.linspace(lo[0], hi[0], max(2, math.ceil((hi[0] - lo[0]) / step) + 1))
        ys = np.linspace(lo[1], hi[1], max(2, math.ceil((hi[1] - lo[1]) / step) + 1))
        pts = [(x, y) for x in xs for y in (lo[1], hi[1])]
        pts += [(x, y) for y in ys for x in (lo[0], hi[0])]
        best = math.inf
        for x, y in pts:
            at = self.cell(x, y)
            if at is None or not self.inside[at]:
                return 0.0
            best = min(best, float(self.wall[at]))
        return best

    def ray(self, lo: tuple[float, float], hi: tuple[float, float], axis: int, sign: int) -> float:
        """Distance from the footprint's side facing ``sign`` along ``axis`` (0 = x,
        1 = y) to the nearest boundary straight ahead, over the footprint's span."""
        start = hi[axis] if sign > 0 else lo[axis]
        span = np.linspace(lo[1 - axis], hi[1 - axis], 5)
        best = math.inf
        for s in span:
            x, y = (start, s) if axis == 0 else (s, start)
            at = self.cell(x, y)
            if at is None or not self.inside[at]:
                return 0.0
            line = self.inside[at[0], :] if axis == 0 else self.inside[:, at[1]]
            i = at[1 - axis]
            ahead = line[i:] if sign > 0 else line[i::-1]
            steps = int(np.argmin(ahead))  # the first cell outside (the pad guarantees one)
            edge = i + steps if sign > 0 else i - steps + 1
            boundary = self.origin[axis] + edge * self.resolution
            best = min(best, abs(boundary - start))
        return best


class PlacementMeter:
    """Placement similarities over one snapshot; room fields are built on first use
    and kept. Safe to share between threads."""

    def __init__(self, snap: MapSnapshot) -> None:
        self.snap = snap
        self._fields: dict[str, RoomField | None] = {}
        self._lock = threading.Lock()

    def field(self, room_id: str) -> RoomField | None:
        """The room's field (None without a mask)."""
        with self._lock:
            if room_id not in self._fields:
                room = self.snap.rooms.get(room_id)
                mask = room.mask if room is not None else None
                self._fields[room_id] = RoomField.of(mask) if mask is not None else None
            return self._fields[room_id]

    def _footprint(self, node_id: str) -> tuple[tuple[float, float], tuple[float, float]] | None:
        node = self.snap.node(node_id)
        if isinstance(node, ObjectNode):
            lo, hi = node.bbox.min, node.bbox.max
            return (float(lo[0]), float(lo[1])), (float(hi[0]), float(hi[1]))
        if isinstance(node, AreaNode):
            x, y = float(node.position[0]), float(node.position[1])
            return (x, y), (x, y)
        return None

    def sim(self, node_id: str, where: str) -> tuple[float | None, str]:
        """Similarity of ``node_id`` to the placement ``where`` (``wall``, ``corner``,
        ``centre``) with the measure in words; None when it cannot be measured."""
        foot = self._footprint(node_id)
        if foot is None:
            return None, "placement is measured for objects and areas only"
        room_id = self.snap.room_of.get(node_id)
        fld = self.field(room_id) if room_id else None
        if fld is None:
            return None, "not in a room with a floor mask; placement unknown"
        lo, hi = foot
        if where == "wall":
            d = fld.wall_distance(lo, hi)
            return wall_grade(d), f"{d:.2f} m from the nearest wall of {room_id}"
        if where == "corner":
            dx = min(fld.ray(lo, hi, 0, 1), fld.ray(lo, hi, 0, -1))
            dy = min(fld.ray(lo, hi, 1, 1), fld.ray(lo, hi, 1, -1))
            sim = min(wall_grade(dx), wall_grade(dy))
            return sim, f"walls {dx:.2f} m away along x and {dy:.2f} m along y in {room_id}"
        cx, cy = (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2
        d = math.dist((cx, cy), fld.centroid)
        sim = float(np.clip(1.0 - d / (CENTRE_SCALE * fld.extent), 0.0, 1.0))
        return sim, f"{d:.2f} m from the centre of {room_id} ({fld.extent:.1f} m across)"
