"""Depth image → world points → 2D band scan → ray casting into the BEV grid.

Every returned depth pixel is a 3D ray from the camera to a surface. Seen from above,
the part of that ray inside the obstacle height band is free space, and a surface point
inside the band is an obstacle. Points are binned by azimuth around the camera (a
virtual laser scan): along each azimuth the free range is the farthest in-band stretch
of any ray, cut at the nearest in-band obstacle. Walls, doors and tall furniture lie in
the band; floors, tables and ceilings do not, so they never close a doorway.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from inherit_sg.geometry.occupancy import OccupancyGrid
from inherit_sg.model import Frame, Intrinsics

_MIN_RANGE = 0.05  # points closer than this to the camera axis are ignored (m)


@lru_cache(maxsize=8)
def _pixel_rays(intr: Intrinsics, stride: int) -> tuple[np.ndarray, np.ndarray, int]:
    """Normalised image coordinates (x/z, y/z) of the sampled pixel centres."""
    off = stride // 2
    us = np.arange(off, intr.width, stride, dtype=np.float32)
    vs = np.arange(off, intr.height, stride, dtype=np.float32)
    xn = ((us - intr.cx) / intr.fx)[None, :].repeat(len(vs), axis=0)
    yn = ((vs - intr.cy) / intr.fy)[:, None].repeat(len(us), axis=1)
    return xn.reshape(-1), yn.reshape(-1), off


def world_points(frame: Frame, stride: int, max_depth: float) -> np.ndarray:
    """(N, 3) world points of every ``stride``-th valid depth pixel (metres)."""
    xn, yn, off = _pixel_rays(frame.intrinsics, stride)
    d = frame.depth[off::stride, off::stride].reshape(-1)
    ok = (d > 0.0) & (d < max_depth)
    d = d[ok].astype(np.float32)
    cam = np.empty((d.size, 3), dtype=np.float32)
    cam[:, 0] = xn[ok] * d
    cam[:, 1] = yn[ok] * d
    cam[:, 2] = d
    m = frame.pose.matrix.astype(np.float32)
    return cam @ m[:3, :3].T + m[:3, 3]


@dataclass(frozen=True)
class BandScan:
    """One frame's evidence: the camera position, obstacle points and free rays, plus
    what it saw of the lintel band (above door openings, below the ceiling)."""

    origin: np.ndarray  # (2,) camera x, y
    hits: np.ndarray  # (N, 2) x, y of in-band surface points
    dirs: np.ndarray  # (B, 2) unit ray directions
    ranges: np.ndarray  # (B,) free length along each ray (m)
    hit_ranges: np.ndarray  # (B,) distance of the nearest in-band obstacle, inf if none
    lintels: np.ndarray  # (M, 2) x, y of surface points in the lintel band
    open_dirs: np.ndarray  # (K, 2) directions of stretches where rays crossed the lintel band
    open_spans: np.ndarray  # (K, 2) start and end distance of each stretch (m)
    hit_dist: np.ndarray  # (N,) distance of every obstacle point from the camera (m)


def _union_spans(
    keys: np.ndarray, lo: np.ndarray, hi: np.ndarray, gap: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Union of intervals ``[lo, hi]`` grouped by integer ``keys`` (joining gaps < gap)."""
    if keys.size == 0:
        return keys, lo, hi
    big = float(hi.max()) + 2.0 * gap + 1.0
    klo = keys * big + lo
    khi = keys * big + hi
    order = np.argsort(klo, kind="stable")
    klo, khi, keys = klo[order], khi[order], keys[order]
    reach = np.maximum.accumulate(khi)
    start = np.r_[True, klo[1:] > reach[:-1] + gap]
    first = np.flatnonzero(start)
    ends = np.maximum.reduceat(khi, first)
    k = keys[first]
    return k, klo[first] - k * big, ends - k * big


def band_scan(
    points: np.ndarray,
    camera: np.ndarray,
    floor_z: float,
    band: tuple[float, float],
    max_range: float,
    angle_res_deg: float,
    lintel_band: tuple[float, float] = (2.1, 2.4),
) -> BandScan:
    """Reduce world points to a 2D scan for the band ``band`` (heights above ``floor_z``).

    The band is widened to include the camera height so that every ray starts inside it.
    For the lintel band the scan keeps the surface points in it and the stretches where
    rays to higher points crossed it: a wall has a lintel over a doorway, a gap between
    furniture is open above.
    """
    cam_h = float(camera[2]) - floor_z
    b0 = min(band[0], cam_h - 0.1)
    b1 = max(band[1], cam_h + 0.1)
    rel = points[:, :2] - camera[None, :2].astype(np.float32)
    dist = np.hypot(rel[:, 0], rel[:, 1])
    z = points[:, 2] - np.float32(floor_z)
    keep = (dist > _MIN_RANGE) & (dist <= max_range)
    rel, dist, z = rel[keep], dist[keep], z[keep]
    in_band = (z >= b0) & (z <= b1)
    frac = np.ones_like(dist)
    low = z < b0
    high = z > b1
    frac[low] = (cam_h - b0) / (cam_h - z[low])
    frac[high] = (b1 - cam_h) / (z[high] - cam_h)
    res = math.radians(angle_res_deg)
    n_bins = math.ceil(2.0 * math.pi / res)
    bins = ((np.arctan2(rel[:, 1], rel[:, 0]) + math.pi) / res).astype(np.int64)
    np.clip(bins, 0, n_bins - 1, out=bins)
    hit_r = np.full(n_bins, np.inf, dtype=np.float32)
    np.minimum.at(hit_r, bins[in_band], dist[in_band])
    free_r = np.zeros(n_bins, dtype=np.float32)
    np.maximum.at(free_r, bins, dist * frac)
    ranges = np.minimum(free_r, hit_r)
    active = np.flatnonzero(ranges > 0.0)
    kept = points[keep]
    l0, l1 = lintel_band
    in_lintel = (z >= l0) & (z <= l1)
    if cam_h < l0:
        up = z > l0
        rise = z[up] - cam_h
        lo = (l0 - cam_h) / rise * dist[up]
        hi = np.minimum(1.0, (l1 - cam_h) / rise) * dist[up]
        ob, olo, ohi = _union_spans(bins[up], lo, hi, 0.05)
    else:
        ob = np.zeros(0, dtype=np.int64)
        olo = ohi = np.zeros(0, dtype=np.float32)
    return BandScan(
        origin=np.asarray(camera[:2], dtype=np.float32),
        hits=kept[in_band, :2],
        hit_dist=dist[in_band],
        dirs=_directions(active, res),
        ranges=ranges[active],
        hit_ranges=hit_r[active],
        lintels=kept[in_lintel, :2],
        open_dirs=_directions(ob, res),
        open_spans=np.stack([olo, ohi], axis=1).astype(np.float32),
    )


def _directions(bins: np.ndarray, res: float) -> np.ndarray:
    ang = (bins + 0.5) * res - math.pi
    return np.stack([np.cos(ang), np.sin(ang)], axis=1).astype(np.float32)


def _samples(
    origin: np.ndarray, dirs: np.ndarray, start: np.ndarray, stop: np.ndarray, step: float
) -> np.ndarray:
    """Points every ``step`` metres from ``start`` to ``stop`` along each direction."""
    counts = np.maximum(((stop - start) / step).astype(np.int64), 0) + 1
    total = int(counts.sum())
    ray = np.repeat(np.arange(len(counts)), counts)
    first = np.repeat(np.cumsum(counts) - counts, counts)
    k = (np.arange(total) - first).astype(np.float32) * step + start[ray]
    return origin[None, :] + dirs[ray] * k[:, None]


def integrate_scan(grid: OccupancyGrid, scan: BandScan, sigma_1m: float = 0.0) -> None:
    """Ray-cast ``scan`` into ``grid`` (misses along rays, hits at obstacle points,
    lintel sightings and open-above stretches).

    ``sigma_1m`` is the depth noise at 1 m, growing with the squared range: far hits
    count less (by the share of their spread one cell holds) and free rays stop two
    standard deviations short of the return.
    """
    res = grid.resolution
    ends = scan.origin[None, :] + scan.dirs * scan.ranges[:, None]
    pts = np.concatenate([scan.hits, scan.lintels, ends, scan.origin[None, :]], axis=0)
    lo = pts.min(axis=0)
    hi = pts.max(axis=0)
    grid.ensure_contains(float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
    step = 0.7 * res
    # Stop one cell short of an obstacle so grazing rays do not erode walls.
    margin = np.maximum(res, 2.0 * sigma_1m * scan.ranges**2)
    stop = scan.ranges - np.where(
        np.isfinite(scan.hit_ranges), margin, 2.0 * sigma_1m * scan.ranges**2
    )
    free = _samples(scan.origin, scan.dirs, np.zeros_like(stop), stop, step)
    w = grid.shape[1]
    fr, fc = grid.cells_of(free)
    hr, hc = grid.cells_of(scan.hits)
    lr, lc = grid.cells_of(scan.lintels)
    spans = scan.open_spans
    limit = np.linalg.norm(hi - lo) + res
    opened = _samples(
        scan.origin, scan.open_dirs, spans[:, 0], np.minimum(spans[:, 1] - res, limit), step
    )
    opened = opened[
        (opened[:, 0] >= lo[0])
        & (opened[:, 0] <= hi[0])
        & (opened[:, 1] >= lo[1])
        & (opened[:, 1] <= hi[1])
    ]
    orr, occ = grid.cells_of(opened)
    weight = None
    if sigma_1m > 0:
        weight = np.minimum(1.0, res / (2.0 * sigma_1m * scan.hit_dist**2 + 1e-9))
    grid.update(fr * w + fc, hr * w + hc, lr * w + lc, orr * w + occ, weight)
