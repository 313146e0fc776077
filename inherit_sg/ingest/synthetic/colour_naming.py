"""Names for sampled colours: the eleven basic colour terms of English, each object colour
named by the nearest reference colour in CIELAB.

The terms are Berlin and Kay's basic colour terms (B. Berlin, P. Kay, *Basic Color
Terms*, 1969): black, white, red, green, yellow, blue, brown, purple, pink, orange, grey.
The reference colours are centroid colours of the ISCC–NBS colour designations (K. L.
Kelly, D. B. Judd, *Color: Universal Language and Dictionary of Names*, NBS Special
Publication 440, 1976), given here as sRGB; each designation counts for the basic term
its hue name names ("moderate olive green" is green, "light yellowish brown" is brown,
"pinkish white" is white). A colour takes the term of its nearest centroid (CIE 1976
colour difference, D65 white).

This naming is the ground truth's own: it shares no reference colour, name list or code
with the system's colour describer.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

RGB = tuple[int, int, int]

BASIC_TERMS: tuple[str, ...] = (
    "black",
    "white",
    "red",
    "green",
    "yellow",
    "blue",
    "brown",
    "purple",
    "pink",
    "orange",
    "grey",
)

# ISCC–NBS centroid colours (NBS SP 440) grouped by the basic term of their hue name.
CENTROIDS: dict[str, tuple[tuple[str, RGB], ...]] = {
    "black": (("black", (34, 34, 34)), ("brownish black", (40, 32, 28))),
    "white": (
        ("white", (242, 243, 244)),
        ("pinkish white", (234, 227, 225)),
        ("bluish white", (233, 233, 237)),
        ("greenish white", (223, 237, 232)),
        ("purplish white", (232, 227, 229)),
        ("yellowish white", (240, 234, 214)),
    ),
    "grey": (
        ("light gray", (185, 184, 181)),
        ("medium gray", (132, 132, 130)),
        ("dark gray", (85, 85, 85)),
        ("light bluish gray", (180, 188, 192)),
        ("pinkish gray", (193, 182, 179)),
        ("brownish gray", (91, 80, 79)),
        ("light brownish gray", (142, 130, 121)),
        ("yellowish gray", (191, 184, 165)),
    ),
    "red": (
        ("vivid red", (190, 0, 50)),
        ("strong red", (188, 63, 74)),
        ("moderate red", (171, 78, 82)),
        ("deep red", (132, 27, 45)),
        ("dark red", (114, 47, 55)),
    ),
    "pink": (
        ("vivid pink", (255, 181, 186)),
        ("strong pink", (234, 147, 153)),
        ("light pink", (249, 204, 202)),
        ("moderate pink", (222, 165, 164)),
        ("deep pink", (228, 113, 122)),
        ("strong purplish pink", (230, 143, 172)),
    ),
    "orange": (
        ("vivid orange", (243, 132, 0)),
        ("strong orange", (237, 135, 45)),
        ("deep orange", (190, 101, 22)),
        ("light orange", (250, 181, 127)),
        ("moderate orange", (217, 144, 88)),
    ),
    "brown": (
        ("strong brown", (128, 70, 27)),
        ("moderate brown", (111, 78, 55)),
        ("deep brown", (89, 51, 25)),
        ("dark brown", (66, 37, 24)),
        ("light brown", (166, 123, 91)),
        ("light yellowish brown", (193, 154, 107)),
        ("moderate yellowish brown", (130, 102, 68)),
        ("light grayish yellowish brown", (174, 155, 130)),
    ),
    "yellow": (
        ("vivid yellow", (243, 195, 0)),
        ("strong yellow", (212, 175, 55)),
        ("light yellow", (248, 222, 126)),
        ("moderate yellow", (201, 174, 93)),
        ("pale yellow", (243, 229, 171)),
    ),
    "green": (
        ("vivid green", (0, 136, 86)),
        ("strong green", (0, 121, 89)),
        ("light green", (106, 171, 142)),
        ("moderate green", (59, 120, 97)),
        ("dark green", (27, 77, 62)),
        ("strong yellowish green", (68, 148, 74)),
        ("moderate olive green", (74, 93, 35)),
    ),
    "blue": (
        ("vivid blue", (0, 161, 194)),
        ("strong blue", (0, 103, 165)),
        ("light blue", (112, 163, 204)),
        ("moderate blue", (67, 107, 149)),
        ("dark blue", (0, 48, 78)),
        ("very light blue", (161, 202, 241)),
        ("strong purplish blue", (84, 90, 167)),
    ),
    "purple": (
        ("vivid purple", (154, 78, 174)),
        ("strong purple", (135, 86, 146)),
        ("light purple", (182, 149, 192)),
        ("moderate purple", (134, 96, 142)),
        ("dark purple", (86, 60, 92)),
        ("deep purple", (96, 47, 107)),
    ),
}

# Below this gap (ΔE) between the nearest centroid of the best term and of the runner-up,
# a colour sits on a category border: people would hesitate to name it.
CLEAR_MARGIN = 6.0

_D65 = np.array([0.95047, 1.0, 1.08883])
_SRGB_TO_XYZ = np.array(
    [
        [0.4124564, 0.3575761, 0.1804375],
        [0.2126729, 0.7151522, 0.0721750],
        [0.0193339, 0.1191920, 0.9503041],
    ]
)


def srgb_to_lab(rgb: np.ndarray | tuple[float, ...]) -> np.ndarray:
    """sRGB in 0–255 (last axis 3) to CIELAB (D65)."""
    c = np.asarray(rgb, dtype=np.float64) / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    xyz = lin @ _SRGB_TO_XYZ.T / _D65
    eps = (6.0 / 29.0) ** 3
    f = np.where(xyz > eps, np.cbrt(xyz), xyz / (3 * (6.0 / 29.0) ** 2) + 4.0 / 29.0)
    lab = np.empty_like(f)
    lab[..., 0] = 116.0 * f[..., 1] - 16.0
    lab[..., 1] = 500.0 * (f[..., 0] - f[..., 1])
    lab[..., 2] = 200.0 * (f[..., 1] - f[..., 2])
    return lab


@lru_cache(maxsize=1)
def _reference() -> tuple[np.ndarray, tuple[str, ...]]:
    terms = tuple(term for term, refs in CENTROIDS.items() for _ in refs)
    labs = srgb_to_lab(np.array([rgb for refs in CENTROIDS.values() for _, rgb in refs]))
    return labs, terms


def _distances(rgb: RGB | tuple[float, ...]) -> dict[str, float]:
    labs, terms = _reference()
    d = np.linalg.norm(labs - srgb_to_lab(np.asarray(rgb, dtype=np.float64)), axis=1)
    best: dict[str, float] = {}
    for term, dist in zip(terms, d, strict=True):
        best[term] = min(best.get(term, np.inf), float(dist))
    return best


def colour_term(rgb: RGB | tuple[float, ...]) -> str:
    """The basic colour term of an sRGB colour (0–255)."""
    best = _distances(rgb)
    return min(BASIC_TERMS, key=lambda t: best[t])


def naming_margin(rgb: RGB | tuple[float, ...]) -> float:
    """ΔE between the nearest centroid of the runner-up term and of the best term."""
    gaps = sorted(_distances(rgb).values())
    return gaps[1] - gaps[0]


def is_clear(rgb: RGB | tuple[float, ...]) -> bool:
    """Whether the colour is well inside its term (margin at least ``CLEAR_MARGIN``)."""
    return naming_margin(rgb) >= CLEAR_MARGIN
