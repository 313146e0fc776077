"""Axis-aligned rectangles and boxes: the geometric vocabulary of the house generator."""

from __future__ import annotations

from dataclasses import dataclass

EPS = 1e-6


@dataclass(frozen=True)
class Rect:
    """Axis-aligned rectangle ``[x0, x1] × [y0, y1]`` in metres."""

    x0: float
    y0: float
    x1: float
    y1: float

    @property
    def w(self) -> float:
        """Extent along x."""
        return self.x1 - self.x0

    @property
    def h(self) -> float:
        """Extent along y."""
        return self.y1 - self.y0

    @property
    def area(self) -> float:
        """Area in m²."""
        return self.w * self.h

    @property
    def cx(self) -> float:
        """Centre x."""
        return (self.x0 + self.x1) / 2.0

    @property
    def cy(self) -> float:
        """Centre y."""
        return (self.y0 + self.y1) / 2.0

    def grown(self, margin: float) -> Rect:
        """The rectangle grown by ``margin`` on every side (shrunk if negative)."""
        return Rect(self.x0 - margin, self.y0 - margin, self.x1 + margin, self.y1 + margin)

    def overlaps(self, other: Rect, gap: float = 0.0) -> bool:
        """Whether the interiors overlap (or come closer than ``gap``)."""
        return (
            self.x0 < other.x1 + gap - EPS
            and other.x0 < self.x1 + gap - EPS
            and self.y0 < other.y1 + gap - EPS
            and other.y0 < self.y1 + gap - EPS
        )

    def contains_rect(self, other: Rect) -> bool:
        """Whether ``other`` lies inside this rectangle."""
        return (
            other.x0 >= self.x0 - EPS
            and other.x1 <= self.x1 + EPS
            and other.y0 >= self.y0 - EPS
            and other.y1 <= self.y1 + EPS
        )

    def contains(self, x: float, y: float) -> bool:
        """Whether the point lies inside (borders included)."""
        return self.x0 - EPS <= x <= self.x1 + EPS and self.y0 - EPS <= y <= self.y1 + EPS

    def polygon(self) -> list[list[float]]:
        """Counter-clockwise corner list."""
        return [
            [round(self.x0, 4), round(self.y0, 4)],
            [round(self.x1, 4), round(self.y0, 4)],
            [round(self.x1, 4), round(self.y1, 4)],
            [round(self.x0, 4), round(self.y1, 4)],
        ]


@dataclass(frozen=True)
class Box:
    """Axis-aligned box: a footprint rectangle and a height range."""

    rect: Rect
    z0: float
    z1: float

    def overlaps(self, other: Box, gap: float = 0.0) -> bool:
        """Whether the two boxes interpenetrate (or come closer than ``gap``)."""
        return (
            self.rect.overlaps(other.rect, gap)
            and self.z0 < other.z1 + gap - EPS
            and other.z0 < self.z1 + gap - EPS
        )


def subtract_intervals(
    lo: float, hi: float, holes: list[tuple[float, float]]
) -> list[tuple[float, float]]:
    """Parts of ``[lo, hi]`` not covered by any of ``holes``."""
    parts = [(lo, hi)]
    for h0, h1 in holes:
        nxt: list[tuple[float, float]] = []
        for a, b in parts:
            if h1 <= a or h0 >= b:
                nxt.append((a, b))
                continue
            if h0 > a:
                nxt.append((a, h0))
            if h1 < b:
                nxt.append((h1, b))
        parts = nxt
    return [(a, b) for a, b in parts if b - a > EPS]


def rect_minus(outer: Rect, hole: Rect) -> list[Rect]:
    """``outer`` minus ``hole`` as up to four disjoint rectangles."""
    if not outer.overlaps(hole):
        return [outer]
    hx0, hx1 = max(outer.x0, hole.x0), min(outer.x1, hole.x1)
    hy0, hy1 = max(outer.y0, hole.y0), min(outer.y1, hole.y1)
    pieces = [
        Rect(outer.x0, outer.y0, outer.x1, hy0),
        Rect(outer.x0, hy1, outer.x1, outer.y1),
        Rect(outer.x0, hy0, hx0, hy1),
        Rect(hx1, hy0, outer.x1, hy1),
    ]
    return [p for p in pieces if p.w > EPS and p.h > EPS]


def shared_border(a: Rect, b: Rect) -> tuple[str, float, float, float] | None:
    """The border two touching rectangles share: ``(axis, coord, lo, hi)``, where ``axis``
    is the direction the border runs ("x": the line ``y = coord``; "y": ``x = coord``)."""
    for xa, xb in ((a.x1, b.x0), (a.x0, b.x1)):
        if abs(xa - xb) < EPS:
            lo, hi = max(a.y0, b.y0), min(a.y1, b.y1)
            if hi - lo > EPS:
                return ("y", xa, lo, hi)
    for ya, yb in ((a.y1, b.y0), (a.y0, b.y1)):
        if abs(ya - yb) < EPS:
            lo, hi = max(a.x0, b.x0), min(a.x1, b.x1)
            if hi - lo > EPS:
                return ("x", ya, lo, hi)
    return None
