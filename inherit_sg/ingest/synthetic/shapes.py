"""Part lists of object shapes: boxes, cylinders and ellipsoids in an object's local frame.

Every shape fits its object's box ``[-w/2, w/2] × [-d/2, d/2] × [0, h]``; the front faces
local -y. A part may carry its own sRGB colour (a window's glass) or a shade factor
(darker legs).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from inherit_sg.ingest.synthetic.arrange import SHELF_LEVELS

GLASS = (170, 200, 215)


@dataclass(frozen=True)
class Part:
    """One primitive: ``prim`` is ``box``, ``cyl`` (axis z), ``ycyl`` / ``xcyl`` (axis y /
    x: a disc facing the front or the side) or ``ball``. ``material`` gives the part a
    material look of its own (a mirror's glass); otherwise parts in their own ``rgb`` have
    none and the others take the object's."""

    prim: str
    center: tuple[float, float, float]
    size: tuple[float, float, float]  # full extents
    shade: float = 1.0
    rgb: tuple[int, int, int] | None = None
    material: str | None = None


def cuboid(cx: float, cy: float, z0: float, sx: float, sy: float, z1: float, **kw: Any) -> Part:
    """A box part from its centre in plan, bottom, extents in plan and top."""
    return Part("box", (cx, cy, (z0 + z1) / 2), (sx, sy, z1 - z0), **kw)


def column(cx: float, cy: float, z0: float, diameter: float, z1: float, **kw: Any) -> Part:
    """An upright cylinder part from its centre in plan, bottom, diameter and top."""
    return Part("cyl", (cx, cy, (z0 + z1) / 2), (diameter, diameter, z1 - z0), **kw)


def legs(w: float, d: float, z1: float, size: float) -> list[Part]:
    """Four square legs at the corners of a ``w`` × ``d`` top, ``z1`` high."""
    return [
        cuboid(sx * (w / 2 - size / 2), sy * (d / 2 - size / 2), 0.0, size, size, z1, shade=0.8)
        for sx in (-1, 1)
        for sy in (-1, 1)
    ]


def table(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Top slab on four legs."""
    t = min(0.05, h * 0.1)
    return [cuboid(0, 0, h - t, w, d, h), *legs(w, d, h - t, min(0.06, w * 0.1))]


def chair(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Seat on legs with a back rest at +y."""
    seat = 0.5 * h
    return [
        cuboid(0, 0, seat - 0.04, w, d, seat),
        *legs(w, d, seat - 0.04, min(0.05, w * 0.1)),
        cuboid(0, d / 2 - 0.025, seat, w, 0.05, h),
    ]


def stool(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Seat on legs."""
    return [cuboid(0, 0, h - 0.04, w, d, h), *legs(w, d, h - 0.04, min(0.05, w * 0.12))]


def seat(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Sofa or armchair: cushion block, back and arms."""
    arm = min(0.15, w * 0.12)
    return [
        cuboid(0, -0.1 * d, 0.0, w - 2 * arm, 0.8 * d, 0.45 * h),
        cuboid(0, 0.4 * d, 0.0, w, 0.2 * d, h),
        cuboid(-(w - arm) / 2, -0.1 * d, 0.0, arm, 0.8 * d, 0.65 * h),
        cuboid((w - arm) / 2, -0.1 * d, 0.0, arm, 0.8 * d, 0.65 * h),
    ]


def bed(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Base with mattress, a headboard at +y and a pillow (unless ``p["pillow"]`` is
    false: real-world beds get pillows of their own)."""
    parts = [
        cuboid(0, -0.03, 0.0, w, d - 0.06, 0.75 * h),
        cuboid(0, d / 2 - 0.03, 0.0, w, 0.06, h, shade=0.75),
    ]
    if p.get("pillow", True):
        parts.append(cuboid(0, d / 2 - 0.25, 0.75 * h, 0.7 * w, 0.3, 0.9 * h, rgb=(235, 235, 230)))
    return parts


def floor_lamp(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Round base, thin pole, cylindrical shade."""
    return [
        column(0, 0, 0.0, 0.7 * w, 0.03),
        column(0, 0, 0.03, 0.05, 0.72 * h, shade=0.7),
        column(0, 0, 0.7 * h, w, h),
    ]


def table_lamp(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Base, stem and shade."""
    return [
        column(0, 0, 0.0, 0.6 * w, 0.05),
        column(0, 0, 0.05, 0.04, 0.55 * h),
        column(0, 0, 0.5 * h, w, h),
    ]


def plant(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Pot with a ball of leaves."""
    return [
        column(0, 0, 0.0, 0.6 * min(w, d), 0.35 * h, shade=0.6),
        Part("ball", (0, 0, 0.67 * h), (w, d, 0.66 * h)),
    ]


def cylinder(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Mugs, vases, bowls, plates."""
    return [column(0, 0, 0.0, min(w, d), h)]


def bottle(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Body and neck."""
    return [column(0, 0, 0.0, min(w, d), 0.7 * h), column(0, 0, 0.7 * h, 0.35 * min(w, d), h)]


def bookshelf(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Open-front shelf unit with boards at ``SHELF_LEVELS``."""
    t = 0.03
    parts = [
        cuboid(-(w - t) / 2, 0, 0.0, t, d, h),
        cuboid((w - t) / 2, 0, 0.0, t, d, h),
        cuboid(0, d / 2 - 0.01, 0.0, w, 0.02, h, shade=0.85),
    ]
    for level in (t / h, *SHELF_LEVELS, 1.0):
        parts.append(cuboid(0, 0, level * h - t, w - 2 * t, d, level * h))
    return parts


def monitor(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Foot, neck and screen."""
    return [
        cuboid(0, 0, 0.0, 0.4 * w, d, 0.02),
        cuboid(0, 0, 0.02, 0.06, 0.05, 0.35 * h),
        cuboid(0, 0, 0.3 * h, w, 0.04, h),
    ]


def toilet(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Bowl block and tank at +y."""
    return [
        cuboid(0, -0.12 * d, 0.0, 0.9 * w, 0.76 * d, 0.5 * h),
        cuboid(0, 0.38 * d, 0.0, w, 0.24 * d, h),
    ]


def bathtub(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """A hollow tub."""
    t = 0.07
    return [
        cuboid(0, 0, 0.0, w, d, 0.12),
        cuboid(0, -(d - t) / 2, 0.0, w, t, h),
        cuboid(0, (d - t) / 2, 0.0, w, t, h),
        cuboid(-(w - t) / 2, 0, 0.0, t, d, h),
        cuboid((w - t) / 2, 0, 0.0, t, d, h),
    ]


def car(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Body on wheels with a cabin."""
    wheels = [
        cuboid(sx * (w / 2 - 0.08), sy * (d / 2 - 0.5), 0.0, 0.16, 0.55, 0.2 * h, rgb=(25, 25, 25))
        for sx in (-1, 1)
        for sy in (-1, 1)
    ]
    return [
        cuboid(0, 0, 0.15 * h, w, d, 0.55 * h),
        cuboid(0, 0.05 * d, 0.55 * h, 0.85 * w, 0.5 * d, h),
        *wheels,
    ]


def door(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """A frame around a free door opening."""
    j = float(p.get("jamb", 0.06))
    return [
        cuboid(-(w - j) / 2, 0, 0.0, j, d, h),
        cuboid((w - j) / 2, 0, 0.0, j, d, h),
        cuboid(0, 0, h - j, w, d, h),
    ]


def window(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Frame and a glass pane in the middle of the wall."""
    j = float(p.get("jamb", 0.06))
    return [
        *door(w, d, h, p),
        cuboid(0, 0, 0.0, w, d, j),
        cuboid(0, 0, j, w - 2 * j, 0.02, h - j, rgb=GLASS),
    ]


def stairs(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """Solid steps climbing towards the front (-y)."""
    n = int(p.get("n_steps", 16))
    tread, rise = d / n, h / n
    return [cuboid(0, d / 2 - (i + 0.5) * tread, 0.0, w, tread, (i + 1) * rise) for i in range(n)]


def box(w: float, d: float, h: float, p: dict[str, Any]) -> list[Part]:
    """A plain block."""
    return [cuboid(0, 0, 0.0, w, d, h)]


Builder = Callable[[float, float, float, dict[str, Any]], list[Part]]
SHAPES: dict[str, Builder] = {
    "table": table,
    "dining table": table,
    "desk": table,
    "coffee table": table,
    "workbench": table,
    "chair": chair,
    "stool": stool,
    "sofa": seat,
    "armchair": seat,
    "bed": bed,
    "lamp": floor_lamp,
    "table lamp": table_lamp,
    "plant": plant,
    "mug": cylinder,
    "vase": cylinder,
    "bowl": cylinder,
    "plate": cylinder,
    "bottle": bottle,
    "bookshelf": bookshelf,
    "monitor": monitor,
    "toilet": toilet,
    "bathtub": bathtub,
    "car": car,
    "door": door,
    "window": window,
    "stairs": stairs,
}


def parts_for(label: str, dims: tuple[float, float, float], params: dict[str, Any]) -> list[Part]:
    """The parts of an object of kind ``label`` with box ``dims``."""
    return SHAPES.get(label, box)(*dims, params)
