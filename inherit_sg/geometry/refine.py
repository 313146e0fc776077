"""Global room-mask refinement on update events (paper §III-C).

1. Heuristic pruning: keep the main connected body of each room (drops noise patches),
   remove rooms that are too small or too thin to stand in (empty regions).
2. Line regularisation: rectilinear boundaries in the dominant wall frame
   (:mod:`inherit_sg.geometry.lines`).
3. Distance-field competition: a cell claimed by several regularised rooms goes to the
   room whose original mask is nearest (EDT), so the result is disjoint.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage as ndi

from inherit_sg.config import GeometryConfig
from inherit_sg.geometry.lines import dominant_angle, regularise


@dataclass(frozen=True)
class RefineParams:
    """Parameters of :func:`refine_rooms` (metres)."""

    cell_size: float = 0.05
    min_room_area: float = 1.5
    min_clearance: float = 0.35
    line_tolerance: float = 0.25
    min_segment: float = 0.3

    @classmethod
    def from_config(cls, cfg: GeometryConfig) -> RefineParams:
        """Take the values of the geometry config section."""
        return cls(
            cell_size=cfg.cell_size,
            min_room_area=cfg.min_room_area,
            min_clearance=cfg.seed_min_clearance,
            line_tolerance=cfg.refine_line_tolerance,
            min_segment=cfg.refine_min_segment,
        )


def largest_component(mask: np.ndarray) -> np.ndarray:
    """The largest 4-connected component of ``mask``."""
    lab, n = ndi.label(mask)
    if n <= 1:
        return mask.astype(bool)
    sizes = np.bincount(lab.reshape(-1))
    sizes[0] = 0
    return lab == int(np.argmax(sizes))


def _window(mask: np.ndarray, pad: int) -> tuple[slice, slice]:
    r, c = np.nonzero(mask)
    h, w = mask.shape
    return (
        slice(max(0, int(r.min()) - pad), min(h, int(r.max()) + pad + 1)),
        slice(max(0, int(c.min()) - pad), min(w, int(c.max()) + pad + 1)),
    )


def prune_rooms(ids: np.ndarray, free: np.ndarray, p: RefineParams) -> dict[int, np.ndarray]:
    """Step 1: the cleaned mask of every room that survives pruning, by id."""
    min_cells = p.min_room_area / p.cell_size**2
    out: dict[int, np.ndarray] = {}
    for rid, box in enumerate(ndi.find_objects(ids), start=1):
        if box is None:
            continue
        sub = largest_component((ids[box] == rid) & free[box])
        if sub.sum() < min_cells:
            continue
        clearance = ndi.distance_transform_edt(np.pad(sub, 1)).max() * p.cell_size
        if clearance < p.min_clearance:
            continue
        mask = np.zeros(ids.shape, dtype=bool)
        mask[box] = sub
        out[rid] = mask
    return out


def compete(
    originals: dict[int, np.ndarray], claims: dict[int, np.ndarray], shape: tuple[int, int]
) -> np.ndarray:
    """Step 3: resolve overlapping claims by distance to each room's original mask."""
    best = np.full(shape, np.inf, dtype=np.float32)
    out = np.zeros(shape, dtype=np.int32)
    for rid, claim in claims.items():
        if not claim.any():
            continue
        win = _window(claim | originals[rid], 2)
        dist = ndi.distance_transform_edt(~originals[rid][win]).astype(np.float32)
        c = claim[win]
        sub_best, sub_out = best[win], out[win]
        take = c & (dist < sub_best)
        sub_best[take] = dist[take]
        sub_out[take] = rid
    for rid in claims:
        mask = out == rid
        if mask.any():
            keep = largest_component(mask)
            out[mask & ~keep] = 0
    return out


def refine_rooms(
    ids: np.ndarray, free: np.ndarray, occupied: np.ndarray, params: RefineParams
) -> np.ndarray:
    """Refined, disjoint room id image from the live id grid of one floor."""
    originals = prune_rooms(ids, free, params)
    angle = dominant_angle(occupied)
    tol = params.line_tolerance / params.cell_size
    min_run = max(1, round(params.min_segment / params.cell_size))
    claims = {rid: regularise(m, angle, tol, min_run) for rid, m in originals.items()}
    return compete(originals, claims, ids.shape)
