"""Offline visual descriptor: a classical, training-free feature of masked crops.

Per object (256 values natively, one L2-normalised block each, weighted):
colour histogram of the masked pixels (16 hue × 4 saturation + 8 lightness of the
achromatic ones, 72), Lab means on a 3×3 grid over the mask box (27), HOG-like
orientation histograms on a 3×3 grid (108), global orientation + gradient-magnitude
histograms (20), colour moments (13) and shape statistics (16: grid occupancy, aspect,
fill, eccentricity, Hu moments). Whole images get a spatial-pyramid variant (256).
Other sizes come from a fixed orthonormal projection of the native vector.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from inherit_sg.errors import InputError
from inherit_sg.perception.base import check_image, check_masks, l2_normalise, mask_bbox
from inherit_sg.perception.histograms import (
    Planes,
    block,
    colour_histogram,
    compute_planes,
    grid_cells,
    magnitude_histogram,
    orientation_histogram,
    projection,
)
from inherit_sg.perception.preprocess import resize

NATIVE_DIM = 256
_IMAGE_SIDE = 160


def _shape_stats(mask_crop: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Grid occupancy (9), log aspect, fill ratio, eccentricity, 4 log-Hu moments."""
    h, w = mask_crop.shape
    occupancy = np.bincount(cells, minlength=9) / max(1.0, h * w / 9.0)
    m = cv2.moments(mask_crop.astype(np.uint8), binaryImage=True)
    area = max(m["m00"], 1.0)
    mu20, mu02, mu11 = m["mu20"] / area, m["mu02"] / area, m["mu11"] / area
    common = np.sqrt(max(0.0, (mu20 - mu02) ** 2 + 4 * mu11**2))
    lam1, lam2 = (mu20 + mu02 + common) / 2, (mu20 + mu02 - common) / 2
    ecc = np.sqrt(max(0.0, 1.0 - lam2 / lam1)) if lam1 > 1e-9 else 0.0
    hu = cv2.HuMoments(m).ravel()[:4]
    log_hu = -np.sign(hu) * np.log10(np.abs(hu) + 1e-12) / 12.0
    stats = [np.log(h / w), area / (h * w), ecc]
    return np.concatenate([occupancy, stats, log_hu])


def _colour_moments(lab: np.ndarray) -> np.ndarray:
    """Lab mean, std, median; L 10th/90th percentiles; chroma mean and std (13)."""
    chroma = np.hypot(lab[:, 1], lab[:, 2])
    p10, p90 = np.percentile(lab[:, 0], [10, 90])
    return np.concatenate(
        [
            lab.mean(axis=0),
            lab.std(axis=0),
            np.median(lab, axis=0),
            [p10, p90, chroma.mean(), chroma.std()],
        ]
    )


class DescriptorEncoder:
    """Classical colour + gradient + shape descriptor (the offline visual encoder)."""

    def __init__(self, dim: int = NATIVE_DIM, image_dim: int | None = None, max_pixels: int = 8192):
        self.name = "descriptor"
        self.dim = dim
        self.image_dim = dim if image_dim is None else image_dim
        self._max_pixels = max_pixels
        self._proj = None if dim == NATIVE_DIM else projection(NATIVE_DIM, dim)
        self._image_proj = (
            None if self.image_dim == NATIVE_DIM else projection(NATIVE_DIM, self.image_dim)
        )

    def encode(self, rgb: np.ndarray, masks: Sequence[np.ndarray]) -> np.ndarray:
        """(len(masks), dim) L2-normalised features of the masked regions of ``rgb``."""
        check_image(rgb)
        check_masks(masks, rgb.shape[:2])
        if not masks:
            return np.zeros((0, self.dim), dtype=np.float32)
        planes = compute_planes(rgb)
        native = np.stack([self._object(planes, m, i) for i, m in enumerate(masks)])
        out = native.astype(np.float32) if self._proj is None else native @ self._proj
        return l2_normalise(out)

    def _object(self, p: Planes, mask: np.ndarray, index: int) -> np.ndarray:
        box = mask_bbox(mask)
        if box is None:
            raise InputError(f"mask {index} is empty: nothing to describe")
        x0, y0, x1, y1 = box
        crop = np.asarray(mask[y0 : y1 + 1, x0 : x1 + 1], dtype=bool)
        ys, xs = np.nonzero(crop)
        ys, xs = ys + y0, xs + x0
        if ys.size > self._max_pixels:  # deterministic subsample of big masks
            step = int(np.ceil(ys.size / self._max_pixels))
            ys, xs = ys[::step], xs[::step]
        cells = grid_cells(ys, xs, box, 3)
        hue, sat, val, lab, mag, ori = p.gather(ys, xs)
        counts = np.bincount(cells, minlength=9)
        sums = np.stack([np.bincount(cells, lab[:, c], minlength=9) for c in range(3)], axis=1)
        layout = (sums / np.maximum(counts, 1)[:, None]).ravel()
        cy, cx = np.nonzero(crop)
        crop_cells = grid_cells(cy, cx, (0, 0, x1 - x0, y1 - y0), 3)
        return np.concatenate(
            [
                block(colour_histogram(hue, sat, val, 16, 4, 8), 1.0, power=0.5),
                block(layout, 0.45),
                block(orientation_histogram(ori, mag, cells, 9, 12), 0.5, power=0.5),
                block(
                    np.concatenate(
                        [
                            orientation_histogram(ori, mag, np.zeros_like(cells), 1, 12),
                            magnitude_histogram(mag, 8),
                        ]
                    ),
                    0.3,
                    power=0.5,
                ),
                block(_colour_moments(lab), 0.55),
                block(_shape_stats(crop, crop_cells), 0.35),
            ]
        )

    def encode_image(self, rgb: np.ndarray) -> np.ndarray:
        """(image_dim,) spatial-pyramid descriptor of the whole image."""
        check_image(rgb)
        h, w = rgb.shape[:2]
        scale = min(1.0, _IMAGE_SIDE / max(h, w))
        small = resize(rgb, max(8, round(h * scale)), max(8, round(w * scale)))
        p = compute_planes(small)
        sh, sw = small.shape[:2]
        ys, xs = np.mgrid[0:sh, 0:sw]
        ys, xs = ys.ravel(), xs.ravel()
        hue, sat, val, _, mag, ori = p.gather(ys, xs)
        quads = grid_cells(ys, xs, (0, 0, sw - 1, sh - 1), 2)
        quad_hists = [
            colour_histogram(hue[quads == q], sat[quads == q], val[quads == q], 8, 2, 4)
            for q in range(4)
        ]
        cells = grid_cells(ys, xs, (0, 0, sw - 1, sh - 1), 4)
        native = np.concatenate(
            [
                block(colour_histogram(hue, sat, val, 16, 4, 8), 1.0, power=0.5),
                block(np.concatenate(quad_hists), 0.8, power=0.5),
                block(orientation_histogram(ori, mag, cells, 16, 6), 0.7, 0.5),
                block(magnitude_histogram(mag, 8), 0.3, power=0.5),
            ]
        )
        out = native.astype(np.float32) if self._image_proj is None else native @ self._image_proj
        return l2_normalise(out)
