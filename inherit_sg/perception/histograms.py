"""Vectorised histogram primitives of the offline visual descriptor: HSV colour
histograms, magnitude-weighted gradient-orientation histograms per cell, and the
per-image planes (HSV, Lab, gradients) they are computed from."""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

# A pixel is "chromatic" when saturation and value are both high enough for its hue
# to mean something; the others only count towards the lightness histogram.
MIN_SATURATION = 0.2
MIN_VALUE = 0.15


@dataclass(frozen=True)
class Planes:
    """Per-pixel planes of one image, computed once and shared by every mask. Colour
    planes stay uint8 (converted only for the pixels a mask gathers)."""

    hsv: np.ndarray  # uint8 (H, W, 3), OpenCV "full" hue range 0..255
    lab: np.ndarray  # uint8 (H, W, 3), OpenCV 8-bit Lab
    mag: np.ndarray  # float32 gradient magnitude of the grey image (per unit intensity)
    ori: np.ndarray  # float32 unsigned gradient orientation in [0, 1) (×π radians)

    def gather(self, ys: np.ndarray, xs: np.ndarray) -> tuple[np.ndarray, ...]:
        """(hue, sat, val) in [0, 1], Lab (N, 3) as L in [0, 1] and a, b centred in
        [-0.5, 0.5], gradient magnitude and orientation of the given pixels."""
        hsv = self.hsv[ys, xs].astype(np.float32) * np.float32(1 / 255)
        lab = self.lab[ys, xs].astype(np.float32) * np.float32(1 / 255)
        lab[:, 1:] -= np.float32(128 / 255)
        return hsv[:, 0], hsv[:, 1], hsv[:, 2], lab, self.mag[ys, xs], self.ori[ys, xs]


def compute_planes(rgb: np.ndarray) -> Planes:
    """HSV, Lab and gradient planes of an (H, W, 3) uint8 RGB image."""
    hsv = cv2.cvtColor(rgb, cv2.COLOR_RGB2HSV_FULL)
    lab = cv2.cvtColor(rgb, cv2.COLOR_RGB2LAB)
    grey = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    gx = cv2.Sobel(grey, cv2.CV_32F, 1, 0, ksize=3, scale=1 / 255)
    gy = cv2.Sobel(grey, cv2.CV_32F, 0, 1, ksize=3, scale=1 / 255)
    mag, ang = cv2.cartToPolar(gx, gy)
    ori = ang * np.float32(1 / np.pi)
    ori -= np.floor(ori)
    return Planes(hsv, lab, mag, np.minimum(ori, np.float32(0.99999), out=ori))


def colour_histogram(
    hue: np.ndarray, sat: np.ndarray, val: np.ndarray, n_hue: int, n_sat: int, n_val: int
) -> np.ndarray:
    """Hue×saturation histogram of chromatic pixels (soft, circular in hue) followed by a
    value histogram of achromatic pixels; counts are shares of all pixels given."""
    n = max(1, hue.size)
    chromatic = (sat >= MIN_SATURATION) & (val >= MIN_VALUE)
    h = hue[chromatic] * n_hue - 0.5
    lo = np.floor(h)
    frac = h - lo
    b0 = lo.astype(np.int64) % n_hue
    b1 = (b0 + 1) % n_hue
    s = (sat[chromatic] - MIN_SATURATION) / (1.0 - MIN_SATURATION)
    sb = np.minimum((s * n_sat).astype(np.int64), n_sat - 1)
    size = n_hue * n_sat
    hs = np.bincount(b0 * n_sat + sb, weights=1.0 - frac, minlength=size)
    hs += np.bincount(b1 * n_sat + sb, weights=frac, minlength=size)
    vb = np.minimum((val[~chromatic] * n_val).astype(np.int64), n_val - 1)
    vh = np.bincount(vb, minlength=n_val).astype(np.float64)
    return np.concatenate([hs, vh]) / n


def orientation_histogram(
    ori: np.ndarray, mag: np.ndarray, cell: np.ndarray, n_cells: int, n_bins: int
) -> np.ndarray:
    """Magnitude-weighted unsigned orientation histograms, ``n_bins`` per cell, with
    linear interpolation between neighbouring bins; ``cell`` gives each pixel's cell."""
    o = ori * n_bins - 0.5
    lo = np.floor(o)
    frac = o - lo
    b0 = lo.astype(np.int64) % n_bins
    b1 = (b0 + 1) % n_bins
    size = n_cells * n_bins
    hist = np.bincount(cell * n_bins + b0, weights=mag * (1.0 - frac), minlength=size)
    hist += np.bincount(cell * n_bins + b1, weights=mag * frac, minlength=size)
    return hist


def magnitude_histogram(mag: np.ndarray, n_bins: int) -> np.ndarray:
    """Share of pixels per log-spaced gradient-magnitude bin (texture strength)."""
    edges = np.geomspace(0.02, 2.0, n_bins - 1)
    idx = np.searchsorted(edges, mag)
    return np.bincount(idx, minlength=n_bins) / max(1, mag.size)


def grid_cells(
    ys: np.ndarray, xs: np.ndarray, box: tuple[int, int, int, int], n: int
) -> np.ndarray:
    """Cell index (row-major) of each pixel in an ``n``×``n`` grid over the inclusive box."""
    x0, y0, x1, y1 = box
    cy = np.minimum(((ys - y0) * n) // (y1 - y0 + 1), n - 1)
    cx = np.minimum(((xs - x0) * n) // (x1 - x0 + 1), n - 1)
    return (cy * n + cx).astype(np.int64)


def block(values: np.ndarray, weight: float, power: float = 1.0) -> np.ndarray:
    """One descriptor block: optionally power-compressed, L2-normalised, then weighted."""
    v = np.asarray(values, dtype=np.float64)
    if power != 1.0:
        v = np.sign(v) * np.abs(v) ** power
    norm = float(np.linalg.norm(v))
    return (v / norm * weight) if norm > 1e-12 else v


def projection(native: int, dim: int, seed: int = 7) -> np.ndarray:
    """Fixed (native, dim) matrix with orthonormal rows or columns, mapping descriptors
    to ``dim``: an isometry when dim ≥ native, a JL projection otherwise."""
    rng = np.random.default_rng(seed)
    if dim >= native:
        q, _ = np.linalg.qr(rng.standard_normal((dim, native)))
        return q.T.astype(np.float32)
    q, _ = np.linalg.qr(rng.standard_normal((native, dim)))
    return q.astype(np.float32)
