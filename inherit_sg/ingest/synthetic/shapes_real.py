"""Composite shapes of the real-world catalogue: casework with doors and drawers,
appliances with doors, glass and cooktops, screens, frames, soft furnishings, fixtures.

Objects of real-world houses carry ``params["real"]``; their kinds take a builder from
:data:`REAL_SHAPES` when there is one (classic houses keep :mod:`inherit_sg.ingest.synthetic.shapes`).
Every shape fits the object's box ``[-w/2, w/2] × [-d/2, d/2] × [0, h]``, front at -y.
Parts in a fixed colour (a screen, a cooktop, a painting's canvas) have no material look
unless they name one (a mirror's glass).
"""

from __future__ import annotations

from typing import Any

from inherit_sg.ingest.synthetic.shapes import (
    SHAPES,
    Builder,
    Part,
    bookshelf,
    box,
    chair,
    column,
    cuboid,
    cylinder,
    legs,
    seat,
    stool,
    table,
)

SCREEN = (16, 17, 20)
DARK_GLASS = (28, 30, 34)
MIRROR = (196, 205, 210)
COOKTOP = (22, 22, 24)
FELT = (34, 112, 64)
LEAVES = (58, 110, 52)
PAPER_WHITE = (238, 238, 232)
STONE_TOP = (205, 203, 196)
METAL = (168, 170, 172)
P = dict[str, Any]


def _disc(cx: float, cy: float, cz: float, diameter: float, thick: float, **kw: Any) -> Part:
    """A disc facing the front (axis y)."""
    return Part("ycyl", (cx, cy, cz), (diameter, thick, diameter), **kw)


def _body(w: float, d: float, z0: float, z1: float, **kw: Any) -> Part:
    """The main block of a front-panelled shape: its front face 2 cm behind the box's."""
    return cuboid(0, 0.01, z0, w, d - 0.02, z1, **kw)


def _front(w: float, d: float, z0: float, z1: float, x0: float, x1: float, **kw: Any) -> Part:
    """A door, drawer or window panel on the front of a :func:`_body`."""
    return cuboid((x0 + x1) / 2, -d / 2 + 0.014, z0, x1 - x0, 0.012, z1, **kw)


def _handle(w: float, d: float, z0: float, z1: float, x0: float, x1: float) -> Part:
    """A metal handle proud of the front panels."""
    return cuboid(
        (x0 + x1) / 2, -d / 2 + 0.004, z0, x1 - x0, 0.008, z1, rgb=METAL, material="metal"
    )


def casework(w: float, d: float, h: float, p: P, rows: int = 0, cols: int = 2) -> list[Part]:
    """Carcass on a plinth with door (``cols`` side by side) or drawer (``rows``) fronts
    and handles."""
    plinth = min(0.08, 0.1 * h)
    parts = [
        cuboid(0, 0.01, 0.0, w - 0.04, d - 0.02, plinth, shade=0.55),
        cuboid(0, 0, plinth, w, d, h),
    ]
    gap = 0.012
    if rows:
        step = (h - plinth) / rows
        for i in range(rows):
            z0 = plinth + i * step + gap
            parts.append(
                _front(w, d, z0, z0 + step - 2 * gap, -w / 2 + gap, w / 2 - gap, shade=1.04)
            )
            parts.append(
                _front(
                    w,
                    d - 0.02,
                    z0 + step * 0.6,
                    z0 + step * 0.6 + 0.02,
                    -0.08,
                    0.08,
                    rgb=METAL,
                    material="metal",
                )
            )
    else:
        step = w / cols
        for i in range(cols):
            x0 = -w / 2 + i * step + gap
            parts.append(_front(w, d, plinth + gap, h - gap, x0, x0 + step - 2 * gap, shade=1.04))
            hx = x0 + step - 2 * gap - 0.05 if i % 2 == 0 else x0 + 0.05
            parts.append(
                _front(
                    w,
                    d - 0.02,
                    h * 0.55,
                    h * 0.55 + 0.12,
                    hx - 0.01,
                    hx + 0.01,
                    rgb=METAL,
                    material="metal",
                )
            )
    return parts


def _drawers(n: int) -> Builder:
    return lambda w, d, h, p: casework(w, d, h, p, rows=n)


def _doors(n: int) -> Builder:
    return lambda w, d, h, p: casework(w, d, h, p, cols=n)


def kitchen_base(w: float, d: float, h: float, p: P) -> list[Part]:
    """Base cabinet with a stone worktop."""
    return [
        *casework(w, d, h - 0.04, p, cols=1),
        cuboid(0, 0, h - 0.04, w, d, h, rgb=STONE_TOP, material="stone"),
    ]


def counter(w: float, d: float, h: float, p: P) -> list[Part]:
    """Counter run: doors below an overhanging top in the object's own finish."""
    return [
        *casework(w, d - 0.02, h - 0.04, p, cols=max(1, round(w / 0.6))),
        cuboid(0, 0, h - 0.04, w, d, h, shade=1.1),
    ]


def island(w: float, d: float, h: float, p: P) -> list[Part]:
    """Free-standing block with an overhanging top."""
    return [
        cuboid(0, 0, 0.0, w - 0.1, d - 0.1, h - 0.04, shade=0.85),
        cuboid(0, 0, h - 0.04, w, d, h),
    ]


def fridge(w: float, d: float, h: float, p: P) -> list[Part]:
    """Tall body with freezer and fridge doors and long handles."""
    split = 0.62 * h
    return [
        _body(w, d, 0.0, h),
        _front(w, d, 0.02, split - 0.01, -w / 2 + 0.01, w / 2 - 0.01, shade=1.03),
        _front(w, d, split + 0.01, h - 0.02, -w / 2 + 0.01, w / 2 - 0.01, shade=1.03),
        _front(
            w,
            d - 0.03,
            split - 0.45,
            split - 0.05,
            w / 2 - 0.08,
            w / 2 - 0.06,
            rgb=METAL,
            material="metal",
        ),
        _front(
            w,
            d - 0.03,
            split + 0.05,
            split + 0.3,
            w / 2 - 0.08,
            w / 2 - 0.06,
            rgb=METAL,
            material="metal",
        ),
    ]


def oven(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body with a control strip, a dark glass door window and a handle."""
    return [
        cuboid(0, 0, 0.0, w, d, h),
        _front(w, d, h - 0.12, h - 0.02, -w / 2 + 0.02, w / 2 - 0.02, rgb=SCREEN),
        _front(
            w, d, 0.15 * h, 0.7 * h, -w / 2 + 0.08, w / 2 - 0.08, rgb=DARK_GLASS, material="glass"
        ),
        _front(
            w,
            d - 0.03,
            0.76 * h,
            0.78 * h,
            -w / 2 + 0.06,
            w / 2 - 0.06,
            rgb=METAL,
            material="metal",
        ),
    ]


def stove(w: float, d: float, h: float, p: P) -> list[Part]:
    """An oven with a black cooktop and four burners."""
    parts = oven(w, d, h - 0.02, p)
    parts.append(cuboid(0, 0, h - 0.02, w, d, h, rgb=COOKTOP, material="glass"))
    for sx in (-1, 1):
        for sy in (-1, 1):
            parts.append(column(sx * w / 4, sy * d / 4, h - 0.005, 0.16, h, rgb=(60, 60, 62)))
    return parts


def dishwasher(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body with a control strip and a handle."""
    return [
        cuboid(0, 0, 0.0, w, d, h),
        _front(w, d, h - 0.1, h - 0.02, -w / 2 + 0.02, w / 2 - 0.02, shade=0.7),
        _front(
            w,
            d - 0.03,
            h - 0.16,
            h - 0.14,
            -w / 2 + 0.08,
            w / 2 - 0.08,
            rgb=METAL,
            material="metal",
        ),
    ]


def washer(w: float, d: float, h: float, p: P) -> list[Part]:
    """Front loader: body, control strip and a round glass door."""
    return [
        _body(w, d, 0.0, h),
        _front(w, d, h - 0.12, h - 0.02, -w / 2 + 0.02, w / 2 - 0.02, shade=0.8),
        _disc(0, -d / 2 + 0.014, 0.45 * h, 0.62 * w, 0.012, rgb=(150, 152, 156), material="metal"),
        _disc(0, -d / 2 + 0.004, 0.45 * h, 0.46 * w, 0.008, rgb=DARK_GLASS, material="glass"),
    ]


def microwave(w: float, d: float, h: float, p: P) -> list[Part]:
    """Box with a dark window and a control panel."""
    return [
        cuboid(0, 0, 0.0, w, d, h),
        _front(w, d, 0.15 * h, 0.85 * h, -w / 2 + 0.04, w / 4, rgb=DARK_GLASS, material="glass"),
    ]


def range_hood(w: float, d: float, h: float, p: P) -> list[Part]:
    """Canopy with a chimney."""
    return [cuboid(0, 0, 0.0, w, d, 0.35 * h), cuboid(0, d / 2 - 0.14, 0.35 * h, 0.3 * w, 0.26, h)]


def screen(w: float, d: float, h: float, p: P) -> list[Part]:
    """A flat screen with a thin bezel in the object's colour (and a foot unless hung)."""
    foot = 0.0 if p.get("hung") else min(0.12, 0.18 * h)
    depth = min(d, 0.06)
    parts = [
        cuboid(0, 0.004, foot, w, depth - 0.008, h),
        cuboid(
            0,
            -depth / 2 + 0.004,
            foot + 0.025,
            w - 0.05,
            0.008,
            h - 0.025,
            rgb=SCREEN,
            material="glass",
        ),
    ]
    if foot:
        parts += [cuboid(0, 0, 0.0, 0.35 * w, d, 0.02), cuboid(0, 0, 0.02, 0.05, 0.04, foot)]
    return parts


def framed(
    inner: tuple[int, int, int] | None, material: str | None, frame: float = 0.05
) -> Builder:
    """A wall-hung frame around a panel (``inner``: its colour, None for the object's)."""

    def build(w: float, d: float, h: float, p: P) -> list[Part]:
        f = min(frame, 0.15 * w, 0.15 * h)
        parts = [cuboid(0, 0.004, 0.0, w, d - 0.008, h, shade=0.45 if inner is None else 1.0)]
        kw: dict[str, Any] = {"material": material}
        if inner is not None:
            kw["rgb"] = inner
        parts.append(cuboid(0, -d / 2 + 0.004, f, w - 2 * f, 0.008, h - f, **kw))
        return parts

    return build


def clock(w: float, d: float, h: float, p: P) -> list[Part]:
    """A round face with hands."""
    return [
        _disc(0, 0.005, h / 2, min(w, h), d - 0.01),
        cuboid(0, -d / 2 + 0.003, h / 2 - 0.005, 0.3 * w, 0.006, h / 2 + 0.005, rgb=SCREEN),
        cuboid(0, -d / 2 + 0.003, h / 2, 0.01, 0.006, h / 2 + 0.35 * h, rgb=SCREEN),
    ]


def curtain(w: float, d: float, h: float, p: P) -> list[Part]:
    """A hanging panel in folds."""
    n = 4
    return [
        cuboid(
            -w / 2 + (i + 0.5) * w / n,
            (d / 4) * (1 if i % 2 else -1),
            0.0,
            w / n,
            d / 2,
            h,
            shade=1.0 if i % 2 else 0.88,
        )
        for i in range(n)
    ]


def blinds(w: float, d: float, h: float, p: P) -> list[Part]:
    """Slats under a head rail."""
    parts = [cuboid(0, 0, h - 0.05, w, d, h, shade=0.85)]
    n = max(3, int((h - 0.05) / 0.06))
    for i in range(n):
        z0 = i * (h - 0.05) / n
        parts.append(cuboid(0, 0, z0, w - 0.02, d * 0.8, z0 + 0.045))
    return parts


def pillow(w: float, d: float, h: float, p: P) -> list[Part]:
    """A soft squashed ball."""
    return [Part("ball", (0, 0, h / 2), (w, d, h))]


def ceiling_fan(w: float, d: float, h: float, p: P) -> list[Part]:
    """Rod, motor and four blades."""
    blade = 0.4 * w
    return [
        column(0, 0, 0.5 * h, 0.05, h, shade=0.8),
        column(0, 0, 0.2 * h, 0.2, 0.5 * h),
        cuboid(blade / 2 + 0.08, 0, 0.3 * h, blade, 0.12, 0.36 * h),
        cuboid(-blade / 2 - 0.08, 0, 0.3 * h, blade, 0.12, 0.36 * h),
        cuboid(0, blade / 2 + 0.08, 0.3 * h, 0.12, blade, 0.36 * h),
        cuboid(0, -blade / 2 - 0.08, 0.3 * h, 0.12, blade, 0.36 * h),
    ]


def chandelier(w: float, d: float, h: float, p: P) -> list[Part]:
    """Rod, body and a ring of glass drops."""
    parts = [
        column(0, 0, 0.5 * h, 0.04, h),
        Part("ball", (0, 0, 0.35 * h), (0.45 * w, 0.45 * d, 0.35 * h)),
    ]
    for sx, sy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        parts.append(
            Part(
                "ball",
                (sx * 0.38 * w, sy * 0.38 * d, 0.15 * h),
                (0.2 * w, 0.2 * d, 0.3 * h),
                rgb=(235, 232, 215),
                material="glass",
            )
        )
    return parts


def wall_light(w: float, d: float, h: float, p: P) -> list[Part]:
    """A back plate and a glowing shade."""
    return [
        cuboid(0, d / 2 - 0.01, 0.2 * h, 0.5 * w, 0.02, 0.8 * h, shade=0.8),
        column(0, -0.01, 0.3 * h, min(w, d - 0.02), h, rgb=(245, 236, 205), material="glass"),
    ]


def flower_pot(w: float, d: float, h: float, p: P) -> list[Part]:
    """A pot in the object's colour with green leaves."""
    return [
        column(0, 0, 0.0, 0.75 * min(w, d), 0.45 * h),
        Part("ball", (0, 0, 0.7 * h), (w, d, 0.6 * h), rgb=LEAVES),
    ]


def bottle_shape(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body, shoulder and neck."""
    return [
        column(0, 0, 0.0, min(w, d), 0.65 * h),
        column(0, 0, 0.65 * h, 0.45 * min(w, d), h, shade=0.85),
    ]


def fireplace(w: float, d: float, h: float, p: P) -> list[Part]:
    """Surround, dark firebox and mantel shelf."""
    return [
        cuboid(0, 0, 0.0, w, d - 0.05, h - 0.06),
        cuboid(0, -d / 2 + 0.02, 0.0, 0.55 * w, 0.02, 0.6 * h, rgb=(18, 16, 15)),
        cuboid(0, 0, h - 0.06, w, d, h, shade=0.8),
    ]


def radiator(w: float, d: float, h: float, p: P) -> list[Part]:
    """Vertical fins."""
    n = max(4, int(w / 0.08))
    return [cuboid(-w / 2 + (i + 0.5) * w / n, 0, 0.0, w / n * 0.7, d, h) for i in range(n)]


def treadmill(w: float, d: float, h: float, p: P) -> list[Part]:
    """Belt deck, two uprights and a console."""
    return [
        cuboid(0, 0.1 * d, 0.0, w, 0.8 * d, 0.18, shade=0.6),
        cuboid(-w / 2 + 0.04, -0.35 * d, 0.18, 0.06, 0.06, 0.9 * h),
        cuboid(w / 2 - 0.04, -0.35 * d, 0.18, 0.06, 0.06, 0.9 * h),
        cuboid(0, -0.38 * d, 0.82 * h, w, 0.2 * d, h),
    ]


def exercise_bike(w: float, d: float, h: float, p: P) -> list[Part]:
    """Base, flywheel, seat post and handlebars."""
    return [
        cuboid(0, 0, 0.0, w, d, 0.06),
        Part("xcyl", (0, -0.25 * d, 0.25 * h), (0.08, min(0.45 * h, 0.45 * d), 0.4 * h)),
        cuboid(0, 0.2 * d, 0.06, 0.06, 0.06, 0.65 * h),
        cuboid(0, 0.2 * d, 0.65 * h, 0.25, 0.3, 0.7 * h, shade=0.6),
        cuboid(0, -0.35 * d, 0.06, 0.06, 0.06, h),
        cuboid(0, -0.35 * d, 0.95 * h, w, 0.05, h),
    ]


def bench_shape(w: float, d: float, h: float, p: P) -> list[Part]:
    """A padded or slatted seat on legs."""
    return [cuboid(0, 0, h - 0.08, w, d, h), *legs(w, d, h - 0.08, 0.05)]


def dumbbell(w: float, d: float, h: float, p: P) -> list[Part]:
    """Two weights on a bar (along x)."""
    return [
        Part("xcyl", (-w / 2 + 0.04, 0, h / 2), (0.08, d, h)),
        Part("xcyl", (w / 2 - 0.04, 0, h / 2), (0.08, d, h)),
        Part("xcyl", (0, 0, h / 2), (w - 0.16, 0.03, 0.03), shade=0.7),
    ]


def bicycle(w: float, d: float, h: float, p: P) -> list[Part]:
    """Two wheels (along y), a frame and a saddle."""
    r = 0.38 * h
    return [
        Part("xcyl", (0, -d / 2 + r, r), (0.05, 2 * r, 2 * r), rgb=SCREEN),
        Part("xcyl", (0, d / 2 - r, r), (0.05, 2 * r, 2 * r), rgb=SCREEN),
        cuboid(0, 0, r, 0.04, d - 2 * r, r + 0.05),
        cuboid(0, 0.15 * d, r, 0.04, 0.04, 0.88 * h),
        cuboid(0, 0.15 * d, 0.88 * h, 0.1, 0.25, 0.92 * h, rgb=SCREEN),
        cuboid(0, -d / 2 + r, r, 0.04, 0.04, h),
        cuboid(0, -d / 2 + r, h - 0.03, w, 0.04, h),
    ]


def ladder(w: float, d: float, h: float, p: P) -> list[Part]:
    """Two rails and rungs."""
    parts = [cuboid(-w / 2 + 0.03, 0, 0.0, 0.05, d, h), cuboid(w / 2 - 0.03, 0, 0.0, 0.05, d, h)]
    for i in range(1, int(h / 0.3) + 1):
        parts.append(cuboid(0, 0, i * 0.3 - 0.02, w - 0.06, 0.04, i * 0.3 + 0.02))
    return parts


def pole_with_head(w: float, d: float, h: float, p: P) -> list[Part]:
    """Broom, mop, coat rack: a pole on a base with a head."""
    return [
        cuboid(0, 0, 0.0, w, d, 0.12, shade=0.7),
        column(0, 0, 0.12, 0.04, h),
        Part("ball", (0, 0, h - 0.06), (min(0.16, w), min(0.16, d), 0.12)),
    ]


def pool_table(w: float, d: float, h: float, p: P) -> list[Part]:
    """Frame with cushions, a green cloth and legs."""
    return [
        cuboid(0, 0, 0.6 * h, w, d, h - 0.03),
        cuboid(0, 0, h - 0.03, w - 0.16, d - 0.16, h - 0.02, rgb=FELT, material="fabric"),
        *legs(w - 0.2, d - 0.2, 0.6 * h, 0.14),
    ]


def ping_pong(w: float, d: float, h: float, p: P) -> list[Part]:
    """Top on legs with a net across."""
    return [*table(w, d, h - 0.12, p), cuboid(0, 0, h - 0.12, 0.02, d, h, rgb=PAPER_WHITE)]


def office_chair(w: float, d: float, h: float, p: P) -> list[Part]:
    """Star base, gas column, seat and back."""
    s = 0.48 * h
    return [
        cuboid(0, 0, 0.0, w, 0.06, 0.06, rgb=SCREEN),
        cuboid(0, 0, 0.0, 0.06, d, 0.06, rgb=SCREEN),
        column(0, 0, 0.06, 0.06, s - 0.06, rgb=METAL, material="metal"),
        cuboid(0, -0.03, s - 0.08, 0.85 * w, 0.85 * d, s),
        cuboid(0, d / 2 - 0.06, s, 0.8 * w, 0.08, h),
    ]


def bar_stool(w: float, d: float, h: float, p: P) -> list[Part]:
    """Round seat on a pole and a foot disc."""
    return [
        column(0, 0, 0.0, 0.8 * w, 0.03),
        column(0, 0, 0.03, 0.06, h - 0.06, rgb=METAL, material="metal"),
        column(0, 0, h - 0.06, w, h),
    ]


def suitcase(w: float, d: float, h: float, p: P) -> list[Part]:
    """Case and handle."""
    return [
        cuboid(0, 0, 0.02, w, d, h - 0.1),
        cuboid(0, 0, 0.0, w - 0.1, d - 0.06, 0.02, rgb=SCREEN),
        cuboid(0, 0, h - 0.1, 0.2, 0.03, h, shade=0.6),
    ]


def bag(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body and strap."""
    return [
        cuboid(0, 0, 0.0, w, d, 0.75 * h),
        cuboid(-w / 2 + 0.06, 0, 0.75 * h, 0.03, 0.03, h, shade=0.7),
        cuboid(w / 2 - 0.06, 0, 0.75 * h, 0.03, 0.03, h, shade=0.7),
        cuboid(0, 0, h - 0.03, w - 0.1, 0.03, h, shade=0.7),
    ]


def shoe(w: float, d: float, h: float, p: P) -> list[Part]:
    """A pair: two low shoes side by side."""
    sw = 0.45 * w
    return [
        cuboid(-w / 4, 0, 0.0, sw, d, 0.6 * h),
        cuboid(-w / 4, d / 4, 0.6 * h, sw, d / 2, h),
        cuboid(w / 4, 0, 0.0, sw, d, 0.6 * h),
        cuboid(w / 4, d / 4, 0.6 * h, sw, d / 2, h),
    ]


def hat(w: float, d: float, h: float, p: P) -> list[Part]:
    """Brim and crown."""
    return [column(0, 0, 0.0, min(w, d), 0.02), column(0, 0, 0.02, 0.6 * min(w, d), h)]


def stuffed_animal(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body, head and ears."""
    return [
        Part("ball", (0, 0, 0.3 * h), (w, d, 0.6 * h)),
        Part("ball", (0, 0, 0.78 * h), (0.6 * w, 0.6 * d, 0.44 * h)),
        Part("ball", (-0.2 * w, 0, 0.97 * h), (0.18 * w, 0.18 * d, 0.06 * h)),
        Part("ball", (0.2 * w, 0, 0.97 * h), (0.18 * w, 0.18 * d, 0.06 * h)),
    ]


def globe(w: float, d: float, h: float, p: P) -> list[Part]:
    """A ball on a stand."""
    return [
        column(0, 0, 0.0, 0.5 * w, 0.03, rgb=(80, 60, 40)),
        column(0, 0, 0.03, 0.03, 0.25 * h, rgb=(80, 60, 40)),
        Part("ball", (0, 0, 0.62 * h), (w, d, 0.76 * h)),
    ]


def speaker(w: float, d: float, h: float, p: P) -> list[Part]:
    """Cabinet with two cones."""
    return [
        _body(w, d, 0.0, h),
        _disc(0, -d / 2 + 0.014, 0.3 * h, 0.6 * w, 0.012, rgb=SCREEN),
        _disc(0, -d / 2 + 0.014, 0.75 * h, 0.3 * w, 0.012, rgb=SCREEN),
    ]


def tissue_box(w: float, d: float, h: float, p: P) -> list[Part]:
    """Box with a tissue sticking out."""
    return [
        cuboid(0, 0, 0.0, w, d, h - 0.005),
        cuboid(0, 0, h - 0.03, 0.1, 0.05, h, rgb=PAPER_WHITE),
    ]


def fruit_bowl(w: float, d: float, h: float, p: P) -> list[Part]:
    """A bowl with fruit."""
    return [
        column(0, 0, 0.0, min(w, d), 0.6 * h),
        Part("ball", (-0.15 * w, 0, 0.75 * h), (0.3 * w, 0.3 * d, 0.5 * h), rgb=(200, 60, 40)),
        Part(
            "ball", (0.15 * w, 0.05 * d, 0.75 * h), (0.3 * w, 0.3 * d, 0.5 * h), rgb=(230, 190, 50)
        ),
    ]


def sink_vanity(w: float, d: float, h: float, p: P) -> list[Part]:
    """Vanity cabinet, a white basin top and a metal tap."""
    return [
        *casework(w, d, h - 0.13, p, cols=2),
        cuboid(0, 0, h - 0.13, w, d, h - 0.08, rgb=(236, 236, 232), material="ceramic"),
        column(0, d / 2 - 0.08, h - 0.08, 0.04, h, rgb=METAL, material="metal"),
    ]


def shower(w: float, d: float, h: float, p: P) -> list[Part]:
    """A tray with glass panels and a head."""
    return [
        cuboid(0, 0, 0.0, w, d, 0.08),
        cuboid(0, -d / 2 + 0.01, 0.08, w, 0.02, h, rgb=(200, 215, 222), material="glass"),
        cuboid(-w / 2 + 0.01, 0, 0.08, 0.02, d, h, rgb=(200, 215, 222), material="glass"),
        column(0, d / 2 - 0.1, h - 0.12, 0.15, h - 0.08, rgb=METAL, material="metal"),
    ]


def whiteboard(w: float, d: float, h: float, p: P) -> list[Part]:
    """A white board in a frame."""
    return framed(PAPER_WHITE, "plastic", 0.03)(w, d, h, p)


def piano(w: float, d: float, h: float, p: P) -> list[Part]:
    """Upright body, keyboard and lid."""
    return [
        cuboid(0, 0.1 * d, 0.0, w, 0.8 * d, h),
        cuboid(0, -0.25 * d, 0.6 * h, w - 0.1, 0.5 * d, 0.62 * h, rgb=PAPER_WHITE),
        cuboid(0, -0.35 * d, 0.62 * h, w - 0.1, 0.3 * d, 0.64 * h, rgb=SCREEN),
    ]


def guitar(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body and neck."""
    return [
        Part("ball", (0, 0, 0.25 * h), (w, d, 0.5 * h)),
        cuboid(0, 0, 0.45 * h, 0.06, 0.03, h, shade=0.6),
    ]


def vacuum(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body, handle and floor head."""
    return [
        cuboid(0, -0.1 * d, 0.0, w, 0.4 * d, 0.06, shade=0.6),
        column(0, 0.1 * d, 0.06, 0.6 * w, 0.45 * h),
        column(0, 0.1 * d, 0.45 * h, 0.04, h, shade=0.6),
    ]


def ironing_board(w: float, d: float, h: float, p: P) -> list[Part]:
    """A padded board on crossed legs."""
    return [
        cuboid(0, 0, h - 0.04, w, d, h),
        cuboid(-0.2 * w, 0, 0.0, 0.03, 0.8 * d, h - 0.04, rgb=METAL, material="metal"),
        cuboid(0.2 * w, 0, 0.0, 0.03, 0.8 * d, h - 0.04, rgb=METAL, material="metal"),
    ]


def shelf(w: float, d: float, h: float, p: P) -> list[Part]:
    """Open shelving (boards at the shelf levels)."""
    return bookshelf(w, d, h, p)


def towel_rack(w: float, d: float, h: float, p: P) -> list[Part]:
    """A bar on two brackets."""
    return [
        cuboid(0, -d / 2 + 0.02, 0.4 * h, w, 0.03, 0.8 * h),
        cuboid(-w / 2 + 0.02, 0, 0.0, 0.03, d, h),
        cuboid(w / 2 - 0.02, 0, 0.0, 0.03, d, h),
    ]


def mirror(w: float, d: float, h: float, p: P) -> list[Part]:
    """A frame around silvered glass."""
    return framed(MIRROR, "glass", 0.03)(w, d, h, p)


def painting(w: float, d: float, h: float, p: P) -> list[Part]:
    """A canvas in the object's colours inside a darker frame."""
    return framed(None, None, 0.05)(w, d, h, p)


def toaster(w: float, d: float, h: float, p: P) -> list[Part]:
    """Body with two dark slots."""
    return [
        cuboid(0, 0, 0.0, w, d, h - 0.005),
        cuboid(-0.2 * w, 0, h - 0.01, 0.3 * w, 0.04, h, rgb=SCREEN),
        cuboid(0.2 * w, 0, h - 0.01, 0.3 * w, 0.04, h, rgb=SCREEN),
    ]


def coffee_machine(w: float, d: float, h: float, p: P) -> list[Part]:
    """Tower with a dark spout recess."""
    return [
        cuboid(0, 0.15 * d, 0.0, w, 0.7 * d, h),
        cuboid(0, -0.2 * d, 0.0, w, 0.6 * d, 0.12),
        cuboid(0, -0.35 * d, 0.12, 0.6 * w, 0.02, 0.6 * h, rgb=SCREEN),
    ]


def lantern(w: float, d: float, h: float, p: P) -> list[Part]:
    """Frame with a glass body and a handle."""
    return [
        cuboid(0, 0, 0.0, w, d, 0.05),
        column(0, 0, 0.05, 0.8 * min(w, d), 0.8 * h, rgb=(240, 230, 200), material="glass"),
        cuboid(0, 0, 0.8 * h, w, d, 0.85 * h),
        cuboid(0, 0, 0.85 * h, 0.03, 0.03, h),
    ]


REAL_SHAPES: dict[str, Builder] = {
    # casework
    "cabinet": _doors(2),
    "kitchen cabinet": kitchen_base,
    "wall cabinet": _doors(2),
    "bathroom cabinet": _doors(2),
    "sideboard": _doors(3),
    "tv stand": _doors(3),
    "nightstand": _drawers(2),
    "dresser": _drawers(4),
    "filing cabinet": _drawers(4),
    "tool cabinet": _drawers(5),
    "wardrobe": _doors(2),
    "mini fridge": _doors(1),
    "counter": counter,
    "kitchen island": island,
    "bar counter": island,
    "shelf": shelf,
    "shoe rack": shelf,
    "wine rack": shelf,
    "spice rack": shelf,
    # appliances
    "refrigerator": fridge,
    "oven": oven,
    "stove": stove,
    "dishwasher": dishwasher,
    "washing machine": washer,
    "dryer": washer,
    "microwave": microwave,
    "range hood": range_hood,
    "toaster": toaster,
    "coffee machine": coffee_machine,
    "water heater": cylinder,
    "tv": screen,
    "sink": sink_vanity,
    "shower": shower,
    # seats and tables
    "dining chair": chair,
    "outdoor chair": chair,
    "office chair": office_chair,
    "recliner": seat,
    "ottoman": box,
    "footstool": stool,
    "bench": bench_shape,
    "weight bench": bench_shape,
    "bar stool": bar_stool,
    "side table": table,
    "console table": table,
    "picnic table": table,
    "pool table": pool_table,
    "ping pong table": ping_pong,
    # walls, windows, ceilings
    "painting": painting,
    "mirror": mirror,
    "whiteboard": whiteboard,
    "clock": clock,
    "dartboard": clock,
    "curtain": curtain,
    "blinds": blinds,
    "ceiling light": cylinder,
    "smoke detector": cylinder,
    "ceiling fan": ceiling_fan,
    "chandelier": chandelier,
    "wall light": wall_light,
    "radiator": radiator,
    "fireplace": fireplace,
    "towel rack": towel_rack,
    # small things and the rest
    "pillow": pillow,
    "flower pot": flower_pot,
    "toilet paper": cylinder,
    "trash can": cylinder,
    "bucket": cylinder,
    "paint can": cylinder,
    "candle": cylinder,
    "glass": cylinder,
    "jar": cylinder,
    "teapot": pillow,
    "soap dispenser": bottle_shape,
    "shampoo": bottle_shape,
    "toiletry": bottle_shape,
    "laundry detergent": bottle_shape,
    "fire extinguisher": bottle_shape,
    "toothbrush": cylinder,
    "umbrella": bottle_shape,
    "exercise ball": pillow,
    "mouse": pillow,
    "fruit bowl": fruit_bowl,
    "tissue box": tissue_box,
    "speaker": speaker,
    "globe": globe,
    "stuffed animal": stuffed_animal,
    "hat": hat,
    "shoe": shoe,
    "bag": bag,
    "handbag": bag,
    "backpack": bag,
    "suitcase": suitcase,
    "treadmill": treadmill,
    "exercise bike": exercise_bike,
    "dumbbell": dumbbell,
    "bicycle": bicycle,
    "ladder": ladder,
    "broom": pole_with_head,
    "mop": pole_with_head,
    "coat rack": pole_with_head,
    "vacuum cleaner": vacuum,
    "ironing board": ironing_board,
    "piano": piano,
    "guitar": guitar,
    "lantern": lantern,
}


def parts_for(label: str, dims: tuple[float, float, float], params: dict[str, Any]) -> list[Part]:
    """The parts of an object of kind ``label`` with box ``dims``: a real-world object's
    composite shape when its kind has one, else the classic shape."""
    builder = REAL_SHAPES.get(label) if params.get("real") else None
    if builder is None:
        builder = SHAPES.get(label, box)
    return builder(*dims, params)
