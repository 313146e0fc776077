"""Continuous colour distributions of real furnishings, sampled per object.

A palette is a mixture of HSV boxes (hue in degrees, saturation and value in 0–1), each
with a weight: wood tones, off-whites, greys and blacks dominate real homes, with some
saturated textiles and decorations. An object's palette comes from its kind when the
kind has one of its own (plants are green, toilets white) and otherwise from its
material (wood is mostly wood-toned, sometimes painted; leather is brown, black or tan).
Sampling returns sRGB 0–255; the ground truth names the colour with
:mod:`inherit_sg.ingest.synthetic.colour_naming`.
"""

from __future__ import annotations

import colorsys

import numpy as np

# (weight, (hue lo, hue hi), (saturation lo, hi), (value lo, hi)); hue ranges may wrap
# (lo > hi means lo..360 then 0..hi).
Box = tuple[float, tuple[float, float], tuple[float, float], tuple[float, float]]

_WOOD: list[Box] = [
    (0.35, (22, 34), (0.45, 0.65), (0.45, 0.70)),  # oak, pine
    (0.25, (15, 28), (0.50, 0.75), (0.22, 0.40)),  # walnut
    (0.15, (5, 18), (0.55, 0.75), (0.30, 0.50)),  # cherry, mahogany
    (0.15, (28, 40), (0.25, 0.45), (0.70, 0.88)),  # birch, maple
    (0.10, (20, 40), (0.05, 0.20), (0.08, 0.18)),  # espresso
]
_WHITE: list[Box] = [
    (0.6, (0, 360), (0.0, 0.05), (0.88, 0.97)),
    (0.4, (30, 55), (0.05, 0.14), (0.86, 0.96)),
]
_GREY: list[Box] = [(1.0, (0, 360), (0.0, 0.06), (0.35, 0.72))]
_BLACK: list[Box] = [(1.0, (0, 360), (0.0, 0.10), (0.05, 0.17))]
_STEEL: list[Box] = [(1.0, (190, 225), (0.02, 0.08), (0.55, 0.80))]
_BRASS: list[Box] = [(1.0, (38, 50), (0.45, 0.70), (0.60, 0.80))]
_BEIGE: list[Box] = [(1.0, (28, 45), (0.12, 0.30), (0.65, 0.88))]
_VIVID: list[Box] = [(1.0, (0, 360), (0.55, 0.90), (0.50, 0.90))]
_PASTEL: list[Box] = [(1.0, (0, 360), (0.20, 0.45), (0.78, 0.95))]
_DARK: list[Box] = [(1.0, (0, 360), (0.35, 0.80), (0.20, 0.45))]
_BLUE: list[Box] = [(1.0, (200, 232), (0.35, 0.75), (0.30, 0.75))]
_GREEN: list[Box] = [(1.0, (85, 150), (0.30, 0.65), (0.30, 0.60))]
_RED: list[Box] = [(1.0, (350, 10), (0.55, 0.85), (0.40, 0.75))]
_BROWN: list[Box] = [(1.0, (18, 34), (0.45, 0.75), (0.22, 0.50))]


def _mix(*parts: tuple[float, list[Box]]) -> list[Box]:
    """Weighted union of palettes."""
    out: list[Box] = []
    for weight, boxes in parts:
        total = sum(b[0] for b in boxes)
        out += [(weight * b[0] / total, b[1], b[2], b[3]) for b in boxes]
    return out


PALETTES: dict[str, list[Box]] = {
    "wood": _mix((0.8, _WOOD), (0.12, _WHITE), (0.08, _BLACK)),
    "natural wood": _WOOD,
    "white": _WHITE,
    "black": _BLACK,
    "grey": _GREY,
    "neutral": _mix((0.4, _WHITE), (0.3, _GREY), (0.25, _BLACK), (0.05, _BEIGE)),
    "metal": _mix((0.5, _STEEL), (0.3, _BLACK), (0.12, _WHITE), (0.08, _BRASS)),
    "appliance": _mix((0.45, _WHITE), (0.4, _STEEL), (0.15, _BLACK)),
    "electronics": _mix((0.75, _BLACK), (0.15, _GREY), (0.1, _WHITE)),
    "plastic": _mix((0.45, _WHITE), (0.15, _BLACK), (0.1, _GREY), (0.2, _VIVID), (0.1, _PASTEL)),
    "fabric": _mix(
        (0.28, _GREY),
        (0.18, _BEIGE),
        (0.15, _BLUE),
        (0.08, _GREEN),
        (0.07, _RED),
        (0.12, _BROWN),
        (0.07, _BLACK),
        (0.05, _WHITE),
    ),
    "textile": _mix((0.3, _WHITE), (0.25, _PASTEL), (0.2, _VIVID), (0.15, _GREY), (0.1, _BLUE)),
    "leather": _mix(
        (0.5, _BROWN),
        (0.3, _BLACK),
        (0.12, [(1.0, (26, 36), (0.45, 0.65), (0.60, 0.78))]),
        (0.08, [(1.0, (355, 8), (0.55, 0.75), (0.30, 0.45))]),
    ),
    "glass": _mix(
        (0.6, [(1.0, (185, 210), (0.05, 0.20), (0.60, 0.85))]),
        (0.25, [(1.0, (95, 150), (0.40, 0.75), (0.25, 0.50))]),
        (0.15, [(1.0, (25, 38), (0.60, 0.85), (0.35, 0.55))]),
    ),
    "ceramic": _mix((0.6, _WHITE), (0.15, _VIVID), (0.1, _PASTEL), (0.08, _BLACK), (0.07, _BLUE)),
    "stone": _mix((0.4, _GREY), (0.3, _BEIGE), (0.2, _BLACK), (0.1, _WHITE)),
    "wicker": [(1.0, (26, 40), (0.35, 0.60), (0.48, 0.75))],
    "paper": _mix((0.7, _WHITE), (0.3, _BEIGE)),
    "concrete": [(1.0, (0, 360), (0.0, 0.05), (0.45, 0.70))],
    "plant": [(1.0, (85, 140), (0.45, 0.80), (0.28, 0.58))],
    "terracotta": [(1.0, (10, 24), (0.55, 0.75), (0.50, 0.75))],
    "books": _mix((0.5, _VIVID), (0.35, _DARK), (0.15, _WHITE)),
    "decor": _mix((0.3, _VIVID), (0.2, _PASTEL), (0.2, _WHITE), (0.15, _BLACK), (0.15, _BRASS)),
    "vivid": _VIVID,
    "art": _mix((0.4, _VIVID), (0.3, _DARK), (0.3, _PASTEL)),
    "cardboard": [(1.0, (26, 36), (0.30, 0.50), (0.55, 0.75))],
    "red": _RED,
    "piano": _mix((0.7, _BLACK), (0.2, _WOOD), (0.1, _WHITE)),
    "tools": _mix((0.45, _RED), (0.3, _BLACK), (0.15, _GREY), (0.1, _BLUE)),
    "car": _mix(
        (0.25, _WHITE), (0.2, _BLACK), (0.25, _GREY), (0.12, _RED), (0.12, _BLUE), (0.06, _VIVID)
    ),
}
# Palette of a material when the kind names none of its own.
MATERIAL_PALETTES: dict[str, str] = {
    "wood": "wood",
    "metal": "metal",
    "plastic": "plastic",
    "fabric": "fabric",
    "leather": "leather",
    "glass": "glass",
    "ceramic": "ceramic",
    "stone": "stone",
    "wicker": "wicker",
    "paper": "paper",
    "concrete": "concrete",
}


# The classic twelve-colour palette's names nearest to each palette, for code that still
# draws a kind in one of those named colours (Matterport3D renders pick a kind's colour
# from ``ObjectKind.colours``).
CLASSIC_NAMES: dict[str, tuple[str, ...]] = {
    "wood": ("brown",),
    "natural wood": ("brown",),
    "white": ("white",),
    "black": ("black",),
    "grey": ("grey",),
    "neutral": ("white", "grey", "black"),
    "metal": ("grey", "black"),
    "appliance": ("white", "grey"),
    "electronics": ("black",),
    "plastic": ("white", "black", "blue", "red"),
    "fabric": ("grey", "beige", "blue", "brown"),
    "textile": ("white", "blue", "pink", "beige"),
    "leather": ("brown", "black"),
    "glass": ("grey", "green"),
    "ceramic": ("white", "blue"),
    "stone": ("grey", "beige"),
    "wicker": ("beige", "brown"),
    "paper": ("white", "beige"),
    "concrete": ("grey",),
    "plant": ("green",),
    "terracotta": ("orange", "brown"),
    "books": ("red", "blue", "green"),
    "decor": ("blue", "red", "yellow", "white"),
    "vivid": ("red", "blue", "yellow", "green", "orange"),
    "art": ("blue", "red", "green", "yellow"),
    "cardboard": ("beige", "brown"),
    "red": ("red",),
    "piano": ("black",),
    "tools": ("red", "black"),
    "car": ("white", "black", "grey", "red", "blue"),
}


def _uniform(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(rng.uniform(lo, hi))


def sample_colour(palette: str, rng: np.random.Generator) -> tuple[int, int, int]:
    """An sRGB colour (0–255) drawn from the named palette."""
    boxes = PALETTES[palette]
    weights = np.array([b[0] for b in boxes])
    _, (h0, h1), (s0, s1), (v0, v1) = boxes[int(rng.choice(len(boxes), p=weights / weights.sum()))]
    span = h1 - h0 if h1 > h0 else h1 + 360.0 - h0
    hue = (h0 + _uniform(rng, 0.0, span)) % 360.0
    r, g, b = colorsys.hsv_to_rgb(hue / 360.0, _uniform(rng, s0, s1), _uniform(rng, v0, v1))
    return (round(r * 255), round(g * 255), round(b * 255))


def palette_for(kind_palette: str, material: str) -> str:
    """The palette of an object: its kind's own, else its material's (else neutral)."""
    if kind_palette:
        return kind_palette
    return MATERIAL_PALETTES.get(material, "neutral")
