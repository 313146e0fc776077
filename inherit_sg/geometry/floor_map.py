"""Everything the geometric stream keeps for one floor: occupancy, room ids, doors,
trajectory, and the latest refined room masks."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from inherit_sg.geometry.bev import BevScene
from inherit_sg.geometry.occupancy import LogOddsParams, OccupancyGrid
from inherit_sg.geometry.raycast import BandScan, integrate_scan
from inherit_sg.geometry.refine import RefineParams, refine_rooms
from inherit_sg.geometry.room_ids import RoomIdGrid
from inherit_sg.geometry.rooms import SegmentParams, segment_rooms
from inherit_sg.model import RoomMask


@dataclass(frozen=True)
class Door:
    """A door between two rooms (``rooms`` = persistent room numbers) or a known door
    position not yet between two rooms. ``source``: "semantic" (given) or "passage"
    (a narrow passage found by the segmentation)."""

    position: tuple[float, float]
    width: float
    rooms: tuple[int, int] | None
    source: str


class FloorMap:
    """BEV occupancy + persistent room ids of one floor."""

    def __init__(
        self,
        cell_size: float,
        logodds: LogOddsParams,
        margin: float,
        hysteresis: int,
        new_room_id: Callable[[], int],
        use_lintels: bool = True,
    ) -> None:
        self.grid = OccupancyGrid(cell_size, logodds, margin)
        self.rooms = RoomIdGrid(hysteresis, new_room_id)
        self.semantic_doors: list[tuple[float, float, float]] = []  # x, y, width
        self.passages: list[Door] = []  # narrow passages of the last segmentation
        self.refined: np.ndarray | None = None
        self.refined_origin: tuple[float, float] = (0.0, 0.0)
        self.trajectory: list[tuple[float, float]] = []
        self.segmentations = 0
        self._room_origin = (0.0, 0.0)
        self.use_lintels = use_lintels

    @property
    def resolution(self) -> float:
        """Cell size in metres."""
        return self.grid.resolution

    def integrate(self, scan: BandScan, sigma_1m: float = 0.0) -> None:
        """Ray-cast one scan into the occupancy grid (``sigma_1m``: depth noise at 1 m)."""
        integrate_scan(self.grid, scan, sigma_1m)

    def _align_rooms(self) -> None:
        g = self.grid
        h, w = self.rooms.ids.shape
        if (h, w) == g.shape:
            return
        if h == 0:
            self.rooms.align(g.shape, 0, 0)
            self._room_origin = (g.origin_x, g.origin_y)
            return
        ox, oy = self._room_origin
        rows = round((oy - g.origin_y) / g.resolution)
        cols = round((ox - g.origin_x) / g.resolution)
        self.rooms.align(g.shape, rows, cols)
        self._room_origin = (g.origin_x, g.origin_y)

    def _observed_window(self, pad: int = 4) -> tuple[slice, slice]:
        """Rows and columns spanning every observed cell (segmentation works there)."""
        known = self.grid.known_mask()
        rows = np.flatnonzero(known.any(axis=1))
        cols = np.flatnonzero(known.any(axis=0))
        h, w = known.shape
        if rows.size == 0:
            return slice(0, h), slice(0, w)
        return (
            slice(max(0, int(rows[0]) - pad), min(h, int(rows[-1]) + pad + 1)),
            slice(max(0, int(cols[0]) - pad), min(w, int(cols[-1]) + pad + 1)),
        )

    def cell_of(self, x: float, y: float) -> tuple[float, float]:
        """Fractional (row, col) of a world point."""
        g = self.grid
        return ((y - g.origin_y) / g.resolution - 0.5, (x - g.origin_x) / g.resolution - 0.5)

    def segment(self, params: SegmentParams) -> tuple[set[int], set[int]]:
        """Re-segment rooms, vote them into the id grid; returns (added, removed) ids."""
        if self.grid.empty:
            return set(), set()
        self._align_rooms()
        before = set(self.rooms.room_ids())
        g = self.grid
        win = self._observed_window()
        r0, c0 = win[0].start, win[1].start
        discs = []
        for x, y, width in self.semantic_doors:
            r, c = self.cell_of(x, y)
            discs.append((r - r0, c - c0, (width / 2.0 + 0.05) / self.resolution))
        above = g.open_above_mask()[win] if self.use_lintels else None
        lintel = (g.lintel_hits > 0)[win] if self.use_lintels else None
        free, occupied = g.free_mask()[win], g.occupied_mask()[win]
        seg = segment_rooms(free, params, discs, above, lintel, occupied)
        labels = np.zeros(g.shape, dtype=np.int32)
        labels[win] = seg.labels
        lut = self.rooms.match_table(labels)
        self.rooms.vote(lut[labels])
        # World positions now: the grid may grow (and its origin move) later.
        self.passages = []
        for p in seg.passages:
            a, b = sorted((int(lut[p.a]), int(lut[p.b])))
            if a and b:
                at = g.cell_center(p.row + r0, p.col + c0)
                self.passages.append(Door(at, p.width, (a, b), "passage"))
        self.segmentations += 1
        after = set(self.rooms.room_ids())
        return after - before, before - after

    def room_at(self, x: float, y: float, search: float = 0.5) -> int:
        """Room number at a world point, or of the nearest room cell within ``search``."""
        self._align_rooms()
        ids = self.rooms.ids
        if ids.size == 0:
            return 0
        r, c = (round(v) for v in self.cell_of(x, y))
        h, w = ids.shape
        if 0 <= r < h and 0 <= c < w and ids[r, c]:
            return int(ids[r, c])
        k = int(search / self.resolution)
        r0, r1, c0, c1 = max(0, r - k), min(h, r + k + 1), max(0, c - k), min(w, c + k + 1)
        if r0 >= r1 or c0 >= c1:
            return 0
        win = ids[r0:r1, c0:c1]
        rr, cc = np.nonzero(win)
        if rr.size == 0:
            return 0
        j = int(np.argmin((rr + r0 - r) ** 2 + (cc + c0 - c) ** 2))
        return int(win[rr[j], cc[j]])

    def refine(self, params: RefineParams) -> np.ndarray:
        """Refined room id image (kept until the next call)."""
        self._align_rooms()
        g = self.grid
        self.refined = refine_rooms(self.rooms.ids, g.free_mask(), g.occupied_mask(), params)
        self.refined_origin = (g.origin_x, g.origin_y)
        return self.refined

    def masks(self, refined: bool = False) -> dict[int, RoomMask]:
        """Room masks cropped to their bounding boxes, by room number."""
        if refined and self.refined is not None:
            ids, (ox, oy) = self.refined, self.refined_origin
        else:
            self._align_rooms()
            ids, (ox, oy) = self.rooms.ids, (self.grid.origin_x, self.grid.origin_y)
        res = self.resolution
        out: dict[int, RoomMask] = {}
        for rid in np.unique(ids):
            if rid == 0:
                continue
            m = ids == rid
            rows = np.flatnonzero(m.any(axis=1))
            cols = np.flatnonzero(m.any(axis=0))
            r0, r1, c0, c1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
            out[int(rid)] = RoomMask(ox + c0 * res, oy + r0 * res, res, m[r0:r1, c0:c1].copy())
        return out

    def bev_scene(
        self,
        refined: bool,
        labels: dict[int, str],
        update_points: list[tuple[float, float, float]],
        now: float,
    ) -> BevScene:
        """What the BEV picture of this floor shows (live or refined rooms)."""
        self._align_rooms()
        g = self.grid
        ids = self.rooms.ids
        if refined and self.refined is not None and self.refined.shape == g.shape:
            ids = self.refined
        return BevScene(
            free=g.free_mask(),
            occupied=g.occupied_mask(),
            rooms=ids,
            origin=(g.origin_x, g.origin_y),
            resolution=g.resolution,
            labels=labels,
            doors=[d.position for d in self.doors()],
            trajectory=self.trajectory,
            update_points=update_points,
            now=now,
        )

    def doors(self) -> list[Door]:
        """Known doors (with the rooms they join when they touch two) and passages."""
        out: list[Door] = []
        claimed: set[tuple[int, int]] = set()
        for x, y, width in self.semantic_doors:
            pair = self._rooms_around(x, y, width)
            out.append(Door((x, y), width, pair, "semantic"))
            if pair:
                claimed.add(pair)
        out += [d for d in self.passages if d.rooms not in claimed]
        return out

    def _rooms_around(self, x: float, y: float, width: float) -> tuple[int, int] | None:
        """The two rooms owning most cells in a ring just outside a door's disc."""
        self._align_rooms()
        ids = self.rooms.ids
        if ids.size == 0:
            return None
        r, c = self.cell_of(x, y)
        rad = (width / 2.0 + 0.05) / self.resolution
        k = int(rad * 1.6) + 2
        h, w = ids.shape
        r0, r1 = max(0, int(r) - k), min(h, int(r) + k + 1)
        c0, c1 = max(0, int(c) - k), min(w, int(c) + k + 1)
        if r0 >= r1 or c0 >= c1:
            return None
        rr, cc = np.mgrid[r0:r1, c0:c1]
        ring = ((rr - r) ** 2 + (cc - c) ** 2) <= (rad * 1.6) ** 2
        vals = ids[r0:r1, c0:c1][ring]
        vals = vals[vals > 0]
        if vals.size == 0:
            return None
        uniq, counts = np.unique(vals, return_counts=True)
        if len(uniq) < 2:
            return None
        top = uniq[np.argsort(-counts)[:2]]
        return (int(min(top)), int(max(top)))
