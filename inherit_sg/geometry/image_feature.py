"""Offline global image descriptor for keyframe gating (the default for DINOv3).

The image is shrunk to 64×48; the descriptor concatenates a colour histogram (2×2
spatial cells × 8 hues × 2 saturations × 2 values) and a gradient-orientation histogram
(4×4 cells × 8 orientations weighted by magnitude). Each histogram is turned into its
square root (so the cosine of two descriptors is the Bhattacharyya coefficient) and the
two halves are weighted equally. Other sizes than 256 are reached with a fixed seeded
random projection. The result is L2-normalised float32.
"""

from __future__ import annotations

from functools import lru_cache

import cv2
import numpy as np

NATIVE_DIM = 256
_W, _H = 64, 48


def _cell_hist(values: np.ndarray, weights: np.ndarray, grid: int, bins: int) -> np.ndarray:
    """Per spatial cell histograms of ``values`` (int bins) on an (H, W) image."""
    h, w = values.shape
    cy = (np.arange(h) * grid // h)[:, None]
    cx = (np.arange(w) * grid // w)[None, :]
    key = ((cy * grid + cx) * bins + values).reshape(-1)
    return np.bincount(key, weights=weights.reshape(-1), minlength=grid * grid * bins)


def _root_normalise(hist: np.ndarray) -> np.ndarray:
    total = float(hist.sum())
    if total <= 0:
        return np.zeros_like(hist)
    return np.sqrt(hist / total)


@lru_cache(maxsize=4)
def _projection(dim: int) -> np.ndarray:
    rng = np.random.default_rng(20240917 + dim)
    return (rng.standard_normal((NATIVE_DIM, dim)) / np.sqrt(dim)).astype(np.float32)


def global_image_feature(rgb: np.ndarray, dim: int = NATIVE_DIM) -> np.ndarray:
    """Descriptor of an (H, W, 3) uint8 RGB image, L2-normalised, ``dim`` floats."""
    step = max(1, rgb.shape[1] // (2 * _W))  # cheap pre-shrink of large images
    small = cv2.resize(rgb[::step, ::step], (_W, _H), interpolation=cv2.INTER_AREA)
    hsv = cv2.cvtColor(small, cv2.COLOR_RGB2HSV)
    hue = (hsv[..., 0].astype(np.int64) * 8) // 180
    sat = (hsv[..., 1] >= 64).astype(np.int64)
    val = (hsv[..., 2] >= 128).astype(np.int64)
    colour = _cell_hist(hue * 4 + sat * 2 + val, np.ones(hue.shape), 2, 32)
    gray = cv2.cvtColor(small, cv2.COLOR_RGB2GRAY).astype(np.float32)
    gx = cv2.Sobel(gray, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(gray, cv2.CV_32F, 0, 1, ksize=3)
    mag = np.hypot(gx, gy)
    ori = ((np.arctan2(gy, gx) % np.pi) / np.pi * 8).astype(np.int64) % 8
    grad = _cell_hist(ori, mag, 4, 8)
    feat = np.concatenate([_root_normalise(colour), _root_normalise(grad)]).astype(np.float32)
    if dim != NATIVE_DIM:
        feat = feat @ _projection(dim)
    norm = float(np.linalg.norm(feat))
    return feat / norm if norm > 0 else feat


def cosine(a: np.ndarray, b: np.ndarray) -> float:
    """Cosine similarity of two vectors (0 when either is zero)."""
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na == 0 or nb == 0:
        return 0.0
    return float(np.dot(a, b) / (na * nb))
