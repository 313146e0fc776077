"""Material estimation from the texture of an object's pixels.

Shading varies slowly over a surface; a material's own pattern does not. Dividing the
luminance by its local median (which keeps the step edges between differently lit faces)
on the mask's interior leaves the *texture residual*, described by:

- ``contrast``: robust spread of the residual (wood grain, fabric weave, leather and
  stone patterns are textured; metal, ceramic, glass and plastic are smooth);
- ``fine``: how much of that spread survives a small (3 px) instead of a large window:
  pixel-scale weave (fabric) versus blotchy grain (leather);
- ``periodic``: the most negative autocorrelation of the residual along image rows or
  columns within a few pixels: stripes (wood grain) swing negative, noise does not;
- ``flecks``: share of pixels much darker than their surroundings (stone speckle);
- ``sheen``: share of pixels much brighter than their surroundings (specular highlights
  of metal, glaze, glass).

:func:`material_name` turns them into a name, or ``"unknown"`` when the pixels do not
say (too few of them, or a smooth surface without a telling highlight). A faint texture
without grain or flecks reads as plastic (moulding texture); since grain seen from afar
looks faint too, :func:`fuse_votes` lets plastic stand only when several views agree
and none showed a textured material. Sensor noise looks like texture too: the frame's
noise floor (:func:`frame_noise`) is taken out of the contrast, and in noisy frames
faint textures are not read at all.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import cv2
import numpy as np
from scipy import ndimage

from inherit_sg.perception.colour_names import srgb_to_linear

MATERIAL_NAMES: tuple[str, ...] = (
    "wood",
    "fabric",
    "leather",
    "stone",
    "metal",
    "ceramic",
    "plastic",
    "glass",
)
MIN_PIXELS = 80
MAX_SIDE = 160  # texture is read in a window of at most this many pixels a side
_LUMA = np.array([0.2126, 0.7152, 0.0722])
_LAGS = range(1, 6)
WIDE = 5  # median window (pixels) of the texture residual; noise is measured with it too
# Decision thresholds, calibrated on rendered views of training houses.
TEXTURED = 0.04  # residual spread above which a surface is patterned
STRIPES = -0.3  # autocorrelation dip of grain
FINE = 0.5  # share of the spread at pixel scale: weave rather than grain
WEAVE = (0.09, 0.145)  # residual spread of a woven surface
FLECKS = 0.05  # share of dark flecks of stone
FAINT = 0.008  # residual spread of a faint moulding texture (plastic), below TEXTURED
NO_GRAIN = -0.2  # a faint texture whose autocorrelation stays above this has no grain
FEW_FLECKS = 0.004  # ... and at most this share of dark flecks
NOISY = FAINT / 2  # frame noise floor above which a faint texture is not readable
# Plastic is a weak reading (faint texture is also what grain looks like from afar): it
# needs this many views, and no view may show a textured material.
WEAK_MATERIALS = frozenset({"plastic"})
MIN_WEAK_VOTES = 2


@dataclass(frozen=True)
class TextureStats:
    """Texture statistics of one object's pixels (see the module docstring)."""

    pixels: int
    contrast: float
    fine: float
    periodic: float
    flecks: float
    sheen: float


def _robust_spread(values: np.ndarray) -> float:
    return float(1.4826 * np.median(np.abs(values - np.median(values))))


def _autocorr_min(res: np.ndarray, inside: np.ndarray) -> float:
    """The lowest autocorrelation of ``res`` over row and column lags in ``_LAGS``."""
    r = np.where(inside, res, 0.0)
    var = float(np.mean(r[inside] ** 2))
    if var <= 1e-12:
        return 0.0
    low = 0.0
    for d in _LAGS:
        for a, b, ma, mb in (
            (r[:, d:], r[:, :-d], inside[:, d:], inside[:, :-d]),
            (r[d:, :], r[:-d, :], inside[d:, :], inside[:-d, :]),
        ):
            both = ma & mb
            if both.sum() >= MIN_PIXELS // 2:
                low = min(low, float(np.mean(a[both] * b[both])) / var)
    return low


def texture_residual(lum: np.ndarray, where: np.ndarray, size: int) -> np.ndarray:
    """Luminance over its local median in a ``size`` window (3 or 5), minus 1, at the
    pixels of ``where`` (in their row-major order): the surface's own pattern (and
    sensor noise), without shading or the steps between lit faces.

    The medians are those of ``scipy.ndimage.median_filter`` with its default "reflect"
    border (numpy's "symmetric" padding), taken by OpenCV's median blur in single
    precision: 5-10x faster than partitioning every window with numpy, which was a
    fifth of the semantic stream's time."""
    half = size // 2
    padded = np.pad(np.asarray(lum, dtype=np.float32), half, mode="symmetric")
    median = cv2.medianBlur(padded, size)[half:-half, half:-half][where]
    return lum[where] / np.maximum(median, 1e-6) - 1.0


def _window(occupied: np.ndarray, lo: int, hi: int) -> tuple[int, int]:
    """At most :data:`MAX_SIDE` rows (or columns) of ``lo:hi`` around the middle of the
    occupied ones: a surface's texture is the same all over it, and a large mask would
    otherwise cost its whole area in median windows."""
    if hi - lo <= MAX_SIDE:
        return lo, hi
    where = np.flatnonzero(occupied)
    mid = lo + int(where[where.size // 2]) if where.size else (lo + hi) // 2
    start = min(max(lo, mid - MAX_SIDE // 2), hi - MAX_SIDE)
    return start, start + MAX_SIDE


def texture_stats(rgb: np.ndarray, mask: np.ndarray) -> TextureStats | None:
    """Statistics of the pixels of ``mask`` in an (H, W, 3) uint8 image (None when too
    few pixels are left after dropping the mask's border)."""
    m = np.asarray(mask, dtype=bool)
    rows, cols = np.flatnonzero(m.any(axis=1)), np.flatnonzero(m.any(axis=0))
    if rows.size == 0:
        return None
    y0, y1 = max(0, rows[0] - 4), rows[-1] + 5
    x0, x1 = max(0, cols[0] - 4), cols[-1] + 5
    y0, y1 = _window(np.asarray(m[y0:y1, x0:x1].any(axis=1)), y0, y1)
    x0, x1 = _window(np.asarray(m[y0:y1, x0:x1].any(axis=0)), x0, x1)
    m = m[y0:y1, x0:x1]
    # medians keep the step edges between differently lit faces, so that only the
    # surface's own pattern is left in the residual
    inside = ndimage.binary_erosion(m, iterations=2)
    n = int(inside.sum())
    if n < MIN_PIXELS:
        return None
    lum = srgb_to_linear(rgb[y0:y1, x0:x1]) @ _LUMA
    vals = texture_residual(lum, inside, WIDE)
    small = texture_residual(lum, inside, 3)
    contrast = _robust_spread(vals)
    fine = _robust_spread(small) / max(contrast, 1e-6)
    centred = np.zeros(lum.shape)
    centred[inside] = vals - float(np.median(vals))
    return TextureStats(
        pixels=n,
        contrast=contrast,
        fine=fine,
        periodic=_autocorr_min(centred, inside),
        flecks=float(np.mean(vals < -0.25)),
        sheen=float(np.mean(vals > 0.35)),
    )


def frame_noise(
    rgb: np.ndarray, exclude: np.ndarray | None = None, bands: int = 3, rows: int = 16
) -> float:
    """The sensor-noise floor of a frame in texture-residual units: the robust spread of
    the residual over a few horizontal bands of the image, leaving out ``exclude`` (most
    of a frame is smooth walls, floors and furniture, so the median sees noise, not
    texture). 0 for a noiseless rendering or when no pixel is left; about 0.01 for
    Gaussian noise of half a grey level."""
    h = rgb.shape[0]
    rows = min(rows, h)
    if rows < 5:
        return 0.0
    vals = []
    for y in np.linspace(0, h - rows, bands).astype(int):
        lum = srgb_to_linear(rgb[y : y + rows]) @ _LUMA
        keep = np.zeros(lum.shape, dtype=bool)
        keep[2:-2, 2:-2] = True
        if exclude is not None:
            keep &= ~np.asarray(exclude, dtype=bool)[y : y + rows]
        vals.append(texture_residual(lum, keep, WIDE))
    v = np.concatenate(vals)
    return _robust_spread(v) if v.size >= MIN_PIXELS else 0.0


def classify(stats: TextureStats, noise: float = 0.0) -> str:
    """A material name from texture statistics, or "unknown" (smooth surfaces: metal,
    ceramic and glass rarely show a telling highlight inside the mask). ``noise`` is
    the frame's noise floor (:func:`frame_noise`): it is taken out of the contrast, and
    above ``NOISY`` a faint texture (plastic) cannot be told from noise."""
    contrast = math.sqrt(max(0.0, stats.contrast**2 - noise**2))
    if contrast >= TEXTURED:
        if stats.periodic <= STRIPES or stats.fine < FINE or contrast > WEAVE[1]:
            return "wood"
        return "fabric" if contrast >= WEAVE[0] else "unknown"
    if stats.flecks >= FLECKS:
        return "stone"
    faint = contrast >= FAINT and noise < NOISY
    if faint and stats.periodic > NO_GRAIN and stats.flecks < FEW_FLECKS:
        return "plastic"
    return "unknown"


def fuse_votes(votes: Mapping[str, int]) -> str | None:
    """An object's material from the names its views voted ("unknown" views do not
    vote): the majority of the textured materials when any was seen (None without a
    majority), else a weak material seen in at least ``MIN_WEAK_VOTES`` views."""
    strong = {m: n for m, n in votes.items() if m not in WEAK_MATERIALS and n > 0}
    if strong:
        best = max(strong, key=lambda m: strong[m])
        return best if 2 * strong[best] > sum(strong.values()) else None
    weak = {m: n for m, n in votes.items() if m in WEAK_MATERIALS and n >= MIN_WEAK_VOTES}
    return max(weak, key=lambda m: weak[m]) if weak else None


def material_name(rgb: np.ndarray, mask: np.ndarray, noise: float | None = None) -> str:
    """The material an object's pixels look like ("unknown" when they do not say);
    ``noise`` is the frame's :func:`frame_noise` (estimated from the pixels of ``rgb``
    outside ``mask`` when None)."""
    stats = texture_stats(rgb, mask)
    if stats is None:
        return "unknown"
    return classify(stats, frame_noise(rgb, exclude=mask) if noise is None else noise)
