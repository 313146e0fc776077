"""Colour naming from pixels.

An object's colour is estimated from its masked pixels in a way that is robust to
shading: Lambertian shading scales linear RGB, so the *chromaticity* (rgb / sum) of a
surface does not change with it while its luminance does. We take the median
chromaticity of the better-lit pixels and the upper-quartile luminance as the "lit"
brightness, rebuild one representative colour from them, convert it to CIELAB and name
it after the nearest prototype of a small named palette (several prototypes per name,
e.g. navy and sky blue are both "blue"; the names and prototypes are the colour
vocabulary, ``colours.toml``). A specular sheen adds white light that shading cannot: on
a surface whose lower quartile is dark, the lit brightness is capped near that
quartile, so a shiny black lamp is named black rather than grey.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from inherit_sg.vocab import colours as colour_vocab

# The named palette and its prototypes come from the colour vocabulary (colours.toml):
# sRGB prototypes per name, the typical shade first, then common variants.
COLOUR_NAMES: tuple[str, ...] = colour_vocab.colour_names()
_PROTOTYPES: dict[str, tuple[tuple[int, int, int], ...]] = colour_vocab.prototypes()

_LUMA = np.array([0.2126, 0.7152, 0.0722], dtype=np.float64)
# On dark surfaces (SHEEN_CAP × the lower-quartile luminance below DARK_LUMA) the lit
# brightness is at most SHEEN_CAP × that quartile: the spread above it comes from a
# specular sheen, not from the surface's own lightness. Calibrated on rendered views of
# training houses (black objects named grey: 59 of 2,287 views before, 17 after).
SHEEN_CAP = 1.25
DARK_LUMA = 0.05
_RGB_TO_XYZ = np.array(
    [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]
)
_WHITE = _RGB_TO_XYZ.sum(axis=1)
# Lightness differences count less than hue/chroma ones: shading moves lightness.
_L_WEIGHT = 0.6


def _decode(c: np.ndarray) -> np.ndarray:
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


_LINEAR_LUT = _decode(np.arange(256, dtype=np.float64) / 255.0)


def srgb_to_linear(rgb: np.ndarray | tuple[float, ...]) -> np.ndarray:
    """sRGB in [0, 255] (any shape, last axis 3) → linear RGB in [0, 1]."""
    arr = np.asarray(rgb)
    if arr.dtype == np.uint8:
        return _LINEAR_LUT[arr]
    return _decode(arr.astype(np.float64) / 255.0)


def linear_to_srgb(lin: np.ndarray) -> np.ndarray:
    """Linear RGB in [0, 1] → sRGB in [0, 255] (float)."""
    c = np.clip(np.asarray(lin, dtype=np.float64), 0.0, 1.0)
    return 255.0 * np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)


def linear_to_lab(lin: np.ndarray) -> np.ndarray:
    """Linear RGB (..., 3) → CIELAB (..., 3) under D65: L in [0, 100]."""
    xyz = np.asarray(lin, dtype=np.float64) @ _RGB_TO_XYZ.T / _WHITE
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.stack(
        [116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])],
        axis=-1,
    )


def _prototype_table() -> tuple[np.ndarray, list[str]]:
    names = [n for n in COLOUR_NAMES for _ in _PROTOTYPES[n]]
    rgb = np.array([p for n in COLOUR_NAMES for p in _PROTOTYPES[n]], dtype=np.float64)
    return linear_to_lab(srgb_to_linear(rgb)), names


_PROTO_LAB, _PROTO_NAMES = _prototype_table()


def representative_colour(
    rgb: np.ndarray, mask: np.ndarray | None = None, max_pixels: int = 4096, gain: float = 1.0
) -> np.ndarray | None:
    """Shading-robust representative sRGB colour (3 floats in [0, 255]) of the masked
    pixels of an (H, W, 3) uint8 image (all pixels when ``mask`` is None); None when
    the mask is empty. Large masks are subsampled to ``max_pixels`` with a fixed stride."""
    if mask is None:
        px = rgb.reshape(-1, 3)
    else:
        m = np.asarray(mask, dtype=bool)
        rows, cols = np.flatnonzero(m.any(axis=1)), np.flatnonzero(m.any(axis=0))
        if rows.size == 0:
            return None
        ys, xs = slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1)
        px = rgb[ys, xs][m[ys, xs]]
    if px.shape[0] == 0:
        return None
    if px.shape[0] > max_pixels:
        px = px[:: -(-px.shape[0] // max_pixels)]
    lin = srgb_to_linear(px)
    luma = lin @ _LUMA
    low, lit = (float(v) for v in np.percentile(luma, [25, 75]))
    # a highlight brightens a dark surface, it cannot darken it: when the upper quartile
    # is far above the lower one, the lit brightness is capped at a multiple of it
    if SHEEN_CAP * low < DARK_LUMA:
        lit = min(lit, SHEEN_CAP * low)
    if lit < 1e-4:
        return np.zeros(3)
    # Chromaticity of dim pixels is dominated by noise: use the better-lit ones.
    bright = luma >= np.percentile(luma, 20)
    sums = lin[bright].sum(axis=1, keepdims=True)
    chroma = np.median(lin[bright] / np.maximum(sums, 1e-6), axis=0)
    chroma = chroma / max(float(chroma.sum()), 1e-6)
    rep = chroma * (gain * lit / max(float(chroma @ _LUMA), 1e-6))
    return np.asarray(linear_to_srgb(rep), dtype=np.float64)


def name_rgb(colour: np.ndarray | tuple[float, float, float]) -> str:
    """Palette name of one sRGB colour (components in [0, 255])."""
    return rank_colours(colour)[0][0]


def rank_colours(colour: np.ndarray | tuple[float, float, float]) -> list[tuple[str, float]]:
    """Palette names ordered by weighted CIELAB distance to ``colour`` (best first),
    each with the distance to its nearest prototype."""
    lab = linear_to_lab(srgb_to_linear(np.asarray(colour, dtype=np.float64)))
    diff = _PROTO_LAB - lab
    diff[:, 0] *= _L_WEIGHT
    dist = np.sqrt((diff**2).sum(axis=1))
    best: dict[str, float] = {}
    for name, d in zip(_PROTO_NAMES, dist, strict=True):
        best[name] = min(best.get(name, np.inf), float(d))
    return sorted(best.items(), key=lambda kv: kv[1])


def colour_name(rgb: np.ndarray, mask: np.ndarray | None = None) -> str:
    """Name of the dominant colour of the masked pixels ("unknown" for an empty mask)."""
    rep = representative_colour(rgb, mask)
    return "unknown" if rep is None else name_rgb(rep)


# The luminance the frame's brightest surfaces are scaled to (above 1: those surfaces
# usually face the light less squarely than the object's lit side), and the most a dim
# frame is brightened; calibrated on rendered views of training houses.
WHITE_LUMA = 1.3
MAX_GAIN = 4.0


def exposure_gain(rgb: np.ndarray, mask: np.ndarray, max_pixels: int = 8192) -> float:
    """How much to brighten an object seen in ``rgb`` so that the frame's brightest
    surfaces (95th percentile outside ``mask``: walls, ceiling) read as white: a white
    object in a dim room then stays white instead of turning grey."""
    m = np.asarray(mask, dtype=bool)
    # a regular grid of about max_pixels pixels first: selecting the whole frame's
    # unmasked pixels and thinning them afterwards copied the frame for every object
    step = max(1, math.isqrt(m.size // max(max_pixels, 1)))
    px = rgb[::step, ::step][~m[::step, ::step]]
    if px.shape[0] == 0:
        px = rgb[~m]
        if px.shape[0] == 0:
            return 1.0
    ref = float(np.percentile(srgb_to_linear(px) @ _LUMA, 95))
    return float(np.clip(WHITE_LUMA / max(ref, 1e-6), 1.0, MAX_GAIN))


def colour_name_in_frame(rgb: np.ndarray, mask: np.ndarray) -> str:
    """Name of an object's colour in a whole frame, exposure-corrected by the frame's
    bright surfaces (:func:`exposure_gain`); "unknown" for an empty mask."""
    rep = representative_colour(rgb, mask, gain=exposure_gain(rgb, mask))
    return "unknown" if rep is None else name_rgb(rep)


# Two different colour names resemble each other at most this much (a beige sofa asked
# for as white still ranks above a black one), falling to nothing at NEIGHBOUR_DE apart.
NEIGHBOUR_MAX = 0.5
NEIGHBOUR_DE = 40.0


@functools.lru_cache(maxsize=4096)
def name_distance(a: str, b: str) -> float:
    """Smallest CIELAB distance between the prototypes of colour names ``a`` and ``b``
    (inf when either is not a palette name; remembered per pair: scoring asks it for
    every candidate of a colour request)."""
    rows_a = [i for i, n in enumerate(_PROTO_NAMES) if n == a]
    rows_b = [i for i, n in enumerate(_PROTO_NAMES) if n == b]
    if not rows_a or not rows_b:
        return float("inf")
    diff = _PROTO_LAB[rows_a][:, None, :] - _PROTO_LAB[rows_b][None, :, :]
    return float(np.sqrt((diff**2).sum(axis=-1)).min())


def name_similarity(a: str, b: str) -> float:
    """How well an object whose colour was named ``a`` answers a request for ``b``: 1 for
    the same name; for neighbouring names (beige and white, grey and silver-white) up to
    :data:`NEIGHBOUR_MAX`, falling linearly with the prototypes' CIELAB distance."""
    if a == b:
        return 1.0
    d = name_distance(a, b)
    return NEIGHBOUR_MAX * max(0.0, 1.0 - d / NEIGHBOUR_DE)
