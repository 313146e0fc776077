"""Masks + depth + intrinsics + pose → robust 3D object observations.

Depth at mask borders mixes foreground and background, and depth holes read as 0, so a
mask is eroded first, holes and far readings are dropped, and depth outliers are cut
with a median/MAD test along the viewing ray before points go to the world frame. The
box is taken between low and high percentiles so a few stray points do not inflate it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import cv2
import numpy as np

from inherit_sg.model import BBox3D, Frame
from inherit_sg.perception.base import mask_bbox

MIN_POINTS = 20
# Voxel downsampling counts into a dense grid while its box has at most this many cells
# per point (a sort-free path); sparser boxes are reduced with np.unique.
DENSE_CELLS_PER_POINT = 4


@dataclass
class Observation:
    """One object seen in one keyframe."""

    label: str
    points: np.ndarray  # (N, 3) world points, voxel-downsampled
    bbox: BBox3D
    centroid: np.ndarray  # (3,)
    pixel_count: int
    centre_offset: (
        float  # mask centre distance from the image centre, as a fraction of the half-diagonal
    )
    score: float = 1.0
    visual_feature: np.ndarray | None = None
    keyframe_id: str = ""
    timestamp: float = 0.0
    mask: np.ndarray | None = field(default=None, repr=False)


def voxel_downsample(points: np.ndarray, voxel: float) -> np.ndarray:
    """One point (the mean) per occupied voxel."""
    if len(points) == 0:
        return points
    keys = np.floor(points / voxel).astype(np.int64)
    keys -= keys.min(axis=0)
    dims = keys.max(axis=0) + 1
    # one integer per voxel: a 1-D unique is much faster than np.unique(axis=0)
    flat = (keys[:, 0] * dims[1] + keys[:, 1]) * dims[2] + keys[:, 2]
    cells = int(dims[0] * dims[1] * dims[2])
    if cells <= DENSE_CELLS_PER_POINT * len(points):
        # a compact box: count into every cell of it, no sort (the same voxels, in the
        # same ascending order as np.unique)
        in_cell = np.bincount(flat, minlength=cells)
        occupied = np.flatnonzero(in_cell)
        weights = [np.bincount(flat, weights=points[:, a], minlength=cells) for a in range(3)]
        return np.stack([w[occupied] for w in weights], axis=1) / in_cell[occupied][:, None]
    _, inverse, counts = np.unique(flat, return_inverse=True, return_counts=True)
    sums = np.zeros((len(counts), 3))
    for axis in range(3):
        sums[:, axis] = np.bincount(inverse, weights=points[:, axis], minlength=len(counts))
    return sums / counts[:, None]


def robust_box(points: np.ndarray, low: float = 2.0, high: float = 98.0) -> BBox3D:
    """Box between per-axis percentiles of ``points``."""
    lo = np.percentile(points, low, axis=0)
    hi = np.percentile(points, high, axis=0)
    return BBox3D(tuple(lo), tuple(np.maximum(hi, lo)))


def _grown_box(mask: np.ndarray, margin: int) -> tuple[int, int, int, int] | None:
    """Rows ``y0:y1`` and columns ``x0:x1`` of a mask's bounding box grown by
    ``margin`` pixels (clipped to the image); None for an empty mask."""
    box = mask_bbox(np.asarray(mask, dtype=bool))
    if box is None:
        return None
    x0, y0, x1, y1 = box
    rows, cols = mask.shape[:2]
    return (
        max(y0 - margin, 0),
        min(y1 + 1 + margin, rows),
        max(x0 - margin, 0),
        min(x1 + 1 + margin, cols),
    )


def backproject_mask(
    frame: Frame,
    mask: np.ndarray,
    *,
    erode_px: int = 2,
    max_depth: float = 8.0,
    mad_k: float = 3.0,
    voxel: float = 0.03,
) -> np.ndarray | None:
    """World points of the masked pixels, cleaned; None when too few remain.

    Everything is done on the mask's bounding box (with a margin as wide as the
    erosion, so the result is the same as on the whole frame): a mask covers a small
    part of most frames."""
    box = _grown_box(mask, max(erode_px, 0))
    if box is None:
        return None
    y0, y1, x0, x1 = box
    m: np.ndarray = np.ascontiguousarray(mask[y0:y1, x0:x1], dtype=np.uint8)
    if erode_px > 0:
        eroded = cv2.erode(m, np.ones((2 * erode_px + 1, 2 * erode_px + 1), np.uint8))
        if int(eroded.sum()) >= MIN_POINTS:
            m = eroded
    depth = frame.depth[y0:y1, x0:x1]
    valid = (m > 0) & (depth > 0.1) & (depth < max_depth)
    rows, cols = np.nonzero(valid)
    if len(rows) < MIN_POINTS:
        return None
    z = depth[rows, cols].astype(np.float64)
    rows, cols = rows + y0, cols + x0
    med = np.median(z)
    mad = np.median(np.abs(z - med)) * 1.4826 + 0.02
    keep = np.abs(z - med) <= mad_k * mad + 0.05 * med
    rows, cols, z = rows[keep], cols[keep], z[keep]
    if len(z) < MIN_POINTS:
        return None
    k = frame.intrinsics
    cam = np.stack([(cols - k.cx) / k.fx * z, (rows - k.cy) / k.fy * z, z], axis=1)
    world = frame.pose.transform_points(cam)
    return voxel_downsample(world, voxel)


def observe(frame: Frame, mask: np.ndarray, label: str, score: float = 1.0) -> Observation | None:
    """Build an :class:`Observation` from one detection; None when depth is unusable."""
    points = backproject_mask(frame, mask)
    if points is None or len(points) < 3:
        return None
    box = robust_box(points)
    y0, y1, x0, x1 = _grown_box(mask, 0) or (0, 0, 0, 0)
    rows, cols = np.nonzero(mask[y0:y1, x0:x1])
    rows, cols = rows + y0, cols + x0
    h, w = mask.shape
    offset = np.hypot(cols.mean() - (w - 1) / 2, rows.mean() - (h - 1) / 2) / np.hypot(w / 2, h / 2)
    return Observation(
        label=label,
        points=points,
        bbox=box,
        centroid=box.center,
        pixel_count=len(rows),
        centre_offset=float(offset),
        score=score,
        keyframe_id=frame.frame_id,
        timestamp=frame.timestamp,
        mask=mask,
    )
