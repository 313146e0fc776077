"""Room segmentation of accumulated free space (paper §III-B, L1).

Euclidean distance transform (EDT) of the free cells, Gaussian smoothing, watershed of
the smoothed field (catchment basins of its maxima), then a merge of basins whose
shared border is not a constriction: two basins stay apart only when the passage
between them is at most a door wide and clearly narrower than both of them. Known door
positions (from the semantic stream) cut the free space with a disc, so they always
separate rooms. Each remaining pair of touching rooms yields a passage (door) at the
narrowest point of their border.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import cv2
import numpy as np
from scipy import ndimage as ndi

from inherit_sg.config import GeometryConfig
from inherit_sg.geometry.doorways import DoorEvidence
from inherit_sg.geometry.regions import UnionFind, adjacency, ascent_basins, region_peaks


@dataclass(frozen=True)
class SegmentParams:
    """Parameters of :func:`segment_rooms` in metres."""

    cell_size: float = 0.05
    edt_sigma: float = 0.15
    seed_min_clearance: float = 0.35
    door_max_width: float = 1.1
    plateau_ratio: float = 0.85
    min_room_area: float = 1.5
    speck_area: float = 0.03  # obstacles smaller than this inside free space are noise
    lintel_radius: float = 0.25  # open-above evidence is pooled over this radius
    unknown_margin: float = 0.25  # unobserved cells this close to free space are no walls
    min_wall: float = 1.0  # a door jamb belongs to an obstacle at least this long

    @classmethod
    def from_config(cls, cfg: GeometryConfig) -> SegmentParams:
        """Take the values of the geometry config section."""
        return cls(
            cell_size=cfg.cell_size,
            edt_sigma=cfg.edt_sigma,
            seed_min_clearance=cfg.seed_min_clearance,
            door_max_width=cfg.door_max_width,
            plateau_ratio=cfg.plateau_ratio,
            min_room_area=cfg.min_room_area,
        )


@dataclass(frozen=True)
class Passage:
    """The narrowest point between two touching rooms (labels ``a < b``)."""

    a: int
    b: int
    row: float
    col: float
    width: float  # metres


@dataclass(frozen=True)
class Segmentation:
    """Room labels (0 = no room) with the EDT used and the passages between rooms."""

    labels: np.ndarray
    edt: np.ndarray  # metres, door discs cut out
    passages: list[Passage]

    @property
    def count(self) -> int:
        """Number of rooms."""
        return int(self.labels.max()) if self.labels.size else 0


def _open2(mask: np.ndarray) -> np.ndarray:
    """Morphological opening with a 2×2 square: cells covered by a 2×2 block inside."""
    fit = mask[:-1, :-1] & mask[1:, :-1] & mask[:-1, 1:] & mask[1:, 1:]
    out = np.zeros_like(mask)
    out[:-1, :-1] |= fit
    out[1:, :-1] |= fit
    out[:-1, 1:] |= fit
    out[1:, 1:] |= fit
    return out


def clean_free(
    free: np.ndarray, speck_cells: int, occupied: np.ndarray | None = None
) -> np.ndarray:
    """Fill unobserved cells between free cells (gaps between rays; never obstacles),
    drop isolated free specks and fill tiny non-free islands (sensor noise)."""
    out = free
    if occupied is not None:
        kernel = np.ones((3, 3), dtype=np.uint8)
        closed = cv2.morphologyEx(free.astype(np.uint8), cv2.MORPH_CLOSE, kernel) > 0
        out = free | (closed & ~occupied)
    out = _open2(out)
    holes, n = ndi.label(~out)
    if n:
        sizes = np.bincount(holes.reshape(-1), minlength=n + 1)
        small = sizes < speck_cells
        small[0] = False
        border = np.unique(
            np.concatenate([holes[0], holes[-1], holes[:, 0], holes[:, -1]]).astype(np.int64)
        )
        small[border] = False
        out = out | small[holes]
    return out


def clearance(
    space: np.ndarray, occupied: np.ndarray | None, params: SegmentParams
) -> tuple[np.ndarray, np.ndarray]:
    """EDT (in cells) of free space to the nearest barrier, and the (row, col) of that
    barrier for every cell. Barriers are everything outside free space or, when
    ``occupied`` is known, obstacles and the unobserved cells farther than
    ``unknown_margin`` from free space: thin unobserved streaks between rays do not
    narrow a room."""
    barrier = ~space
    if occupied is not None:
        margin = params.unknown_margin / params.cell_size
        far = ndi.distance_transform_edt(~space) > margin
        barrier = occupied | (far & ~space)
    dist, nearest = ndi.distance_transform_edt(~barrier, return_indices=True)
    return np.asarray(dist), np.asarray(nearest)


def door_cut(shape: tuple[int, int], doors: Sequence[tuple[float, float, float]]) -> np.ndarray:
    """Mask of discs ``(row, col, radius_cells)`` around known doors."""
    cut = np.zeros(shape, dtype=bool)
    rows, cols = np.ogrid[: shape[0], : shape[1]]
    for r, c, rad in doors:
        r0, r1 = max(0, int(r - rad) - 1), min(shape[0], int(r + rad) + 2)
        c0, c1 = max(0, int(c - rad) - 1), min(shape[1], int(c + rad) + 2)
        if r0 >= r1 or c0 >= c1:
            continue
        sub = (rows[r0:r1] - r) ** 2 + (cols[:, c0:c1] - c) ** 2 <= rad * rad
        cut[r0:r1, c0:c1] |= sub
    return cut


def _merge(
    labels: np.ndarray, edt: np.ndarray, p: SegmentParams, evidence: DoorEvidence
) -> np.ndarray:
    """Join basins over borders that are not doorways.

    A border is a doorway when its widest crossing is at most a door wide, clearly
    narrower than both basins, and the evidence around it says so
    (:mod:`inherit_sg.geometry.doorways`).
    """
    n = int(labels.max())
    if n < 2:
        return labels
    peaks = region_peaks(labels, edt, n)
    adj = adjacency(labels, edt)
    uf = UnionFind(peaks)
    half_door = p.door_max_width / 2.0
    for i in np.argsort(-adj.value, kind="stable"):
        a, b = uf.find(int(adj.a[i])), uf.find(int(adj.b[i]))
        if a == b:
            continue
        saddle = adj.value[i]
        is_open = saddle > half_door or saddle >= p.plateau_ratio * min(uf.peak[a], uf.peak[b])
        if is_open or not evidence.is_doorway(adj.where[i, 0], adj.where[i, 1]):
            uf.union(a, b)
    return uf.relabel(labels)


def _prune(labels: np.ndarray, edt: np.ndarray, p: SegmentParams) -> np.ndarray:
    """Fold rooms that are too small or too thin into their most open neighbour; drop
    those with no neighbour."""
    min_cells = p.min_room_area / p.cell_size**2
    for _ in range(8):
        n = int(labels.max())
        sizes = np.bincount(labels.reshape(-1), minlength=n + 1)
        peaks = region_peaks(labels, edt, n)
        weak = (sizes < min_cells) | (peaks < p.seed_min_clearance)
        weak[0] = False
        if not weak.any():
            break
        adj = adjacency(labels, edt)
        best = np.full(n + 1, -1, dtype=np.int64)
        best_val = np.full(n + 1, -np.inf)
        for a, b, v in zip(adj.a, adj.b, adj.value, strict=True):
            for x, y in ((a, b), (b, a)):
                if weak[x] and v > best_val[x]:
                    best[x], best_val[x] = y, v
        uf = UnionFind(np.where(weak, 0.0, 1.0 + peaks))
        merged = False
        for x in np.flatnonzero(weak):
            if best[x] >= 0:
                uf.union(int(x), int(best[x]))
                merged = True
        if not merged:
            lut = np.where(weak, 0, np.arange(n + 1)).astype(np.int32)
            labels = lut[labels]
            break
        labels = uf.relabel(labels)
    n = int(labels.max())
    keep = np.bincount(labels.reshape(-1), minlength=n + 1) > 0
    keep[0] = False
    lut = np.zeros(n + 1, dtype=np.int32)
    lut[keep] = np.arange(1, int(keep.sum()) + 1, dtype=np.int32)
    return lut[labels]


def passages(labels: np.ndarray, edt: np.ndarray, cell_size: float) -> list[Passage]:
    """The narrowest crossing of every pair of touching rooms."""
    adj = adjacency(labels, edt)
    return [
        Passage(
            int(adj.a[i]),
            int(adj.b[i]),
            float(adj.where[i, 0]),
            float(adj.where[i, 1]),
            float(2.0 * adj.value[i] + cell_size),
        )
        for i in range(len(adj.a))
    ]


def segment_rooms(
    free: np.ndarray,
    params: SegmentParams,
    doors: Sequence[tuple[float, float, float]] = (),
    open_above: np.ndarray | None = None,
    lintel: np.ndarray | None = None,
    occupied: np.ndarray | None = None,
) -> Segmentation:
    """Segment free space into rooms. ``doors`` are ``(row, col, radius_cells)`` discs.

    ``open_above`` (optional) marks cells seen free above door height and ``lintel``
    cells where a surface was seen there. A narrow passage mostly open above and with no
    lintel near it is a gap between furniture, not a doorway: it does not separate rooms.
    """
    res = params.cell_size
    space = clean_free(free, max(1, round(params.speck_area / res**2)), occupied)
    cut = door_cut(space.shape, doors)
    dist, nearest = clearance(space, occupied, params)
    edt = dist.astype(np.float32) * np.float32(res)
    edt[cut] = 0.0
    sigma = params.edt_sigma / res
    smooth = ndi.gaussian_filter(edt, sigma) if sigma > 0 else edt
    basins = ascent_basins(smooth, space)
    evidence = DoorEvidence.build(
        space,
        cut,
        nearest if occupied is not None else None,
        open_above,
        lintel,
        occupied,
        round(params.lintel_radius / res),
        params.min_wall / res,
    )
    labels = _prune(_merge(basins, edt, params, evidence), edt, params)
    return Segmentation(labels=labels, edt=edt, passages=passages(labels, edt, res))
