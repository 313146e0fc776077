"""Which rectangle of a storey gets which room type, and which rooms join without walls.

Big rooms go to big rectangles (:data:`~inherit_sg.ingest.synthetic.taxonomy.ROOM_TYPES` size ranks),
with placement rules first: an open-plan ground floor puts the living room, the kitchen
and the dining room on rectangles that touch along at least
:data:`~inherit_sg.ingest.synthetic.open_plan.OPEN_MIN` (the biggest such group); a foyer
(entryway) takes a small rectangle beside the hallway at the front or back of the
house (its street wall gets the front door); a garage needs a side wall and room for a
car, a porch or balcony an exterior wall. A type that finds no place becomes a stand-in (:func:`~inherit_sg.ingest.synthetic.taxonomy.fallback`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import combinations

import numpy as np

from inherit_sg.ingest.synthetic.geom import EPS, Rect
from inherit_sg.ingest.synthetic.open_plan import FOYER_MIN, OPEN_MIN, border_length
from inherit_sg.ingest.synthetic.taxonomy import ROOM_TYPES, fallback

FOYER_OPENS_TO_HALL = 0.5  # chance a foyer opens onto the hallway without a door
FOYER_OPENS_TO_LIVING = 0.6  # in open-plan homes, chance it opens onto the living room


@dataclass
class Assignment:
    """Room types per rectangle and the open borders (pairs of rectangle indices; -1
    stands for the hallway)."""

    types: list[str]
    open_pairs: list[tuple[int, int]] = field(default_factory=list)

    @property
    def open_plan(self) -> bool:
        """Whether kitchen, dining or living spaces share an open space."""
        core = {"kitchen", "dining room", "living room"}
        return any(
            i >= 0 and self.types[i] in core and self.types[j] in core for i, j in self.open_pairs
        )


def _touches_front(r: Rect, footprint: Rect) -> bool:
    return abs(r.y0 - footprint.y0) < EPS or abs(r.y1 - footprint.y1) < EPS


def _exterior(r: Rect, footprint: Rect) -> bool:
    return _touches_front(r, footprint) or (
        abs(r.x0 - footprint.x0) < EPS or abs(r.x1 - footprint.x1) < EPS
    )


def _open_cluster(
    rects: list[Rect], free: list[int], with_dining: bool, rng: np.random.Generator
) -> tuple[dict[str, int], list[tuple[int, int]]] | None:
    """Rectangles for the living room, kitchen (and dining room) joined by open
    borders: the connected group of largest area, ties broken at random."""
    size = 3 if with_dining else 2
    best: tuple[float, dict[str, int], list[tuple[int, int]]] | None = None
    for group in combinations(free, size):
        links = [
            (a, b)
            for a, b in combinations(group, 2)
            if border_length(rects[a], rects[b]) >= OPEN_MIN
        ]
        if len(links) < size - 1:
            continue
        score = sum(rects[i].area for i in group) + float(rng.uniform(0.0, 0.5))
        if best is not None and score <= best[0]:
            continue
        living = max(group, key=lambda i: rects[i].area)
        rest = [i for i in group if i != living]
        rng.shuffle(rest)
        roles = {"living room": living, "kitchen": rest[0]}
        if with_dining:
            roles["dining room"] = rest[1]
        best = (score, roles, links)
    return None if best is None else (best[1], best[2])


def assign_rooms(
    rects: list[Rect],
    types: list[str],
    hall: Rect,
    footprint: Rect,
    rng: np.random.Generator,
    open_plan: bool,
    walled: bool = False,
) -> Assignment | None:
    """Types for ``rects`` (same order) from the storey's programme ``types``; None when
    ``open_plan`` is asked for and no group of rectangles allows it. A ``walled`` storey
    has no open border at all (not even a foyer open onto the hallway)."""
    todo = list(types)
    out: list[str | None] = [None] * len(rects)
    pairs: list[tuple[int, int]] = []

    def take(name: str, index: int) -> None:
        out[index] = name
        todo.remove(name)

    def free() -> list[int]:
        return [i for i, t in enumerate(out) if t is None]

    if open_plan:
        if "kitchen" not in todo or "living room" not in todo:
            return None
        cluster = _open_cluster(rects, free(), "dining room" in todo, rng)
        if cluster is None:
            return None
        roles, pairs = cluster
        for name, index in roles.items():
            take(name, index)
    if "entryway" in todo:
        _place_foyer(rects, out, todo, pairs, hall, footprint, rng, open_plan)
        if walled:
            pairs = [p for p in pairs if -1 not in p]
    for name, fits in (
        ("garage", lambda r: (abs(r.x0 - footprint.x0) < EPS or abs(r.x1 - footprint.x1) < EPS)
         and min(r.w, r.h) >= 2.8 and max(r.w, r.h) >= 4.8),
        ("porch", lambda r: _exterior(r, footprint)),
        ("balcony", lambda r: _exterior(r, footprint)),
    ):  # fmt: skip
        while name in todo:
            spots = [i for i in free() if fits(rects[i])]
            if not spots:
                todo[todo.index(name)] = fallback(todo + [t for t in out if t])
                continue
            pick = (
                max(spots, key=lambda i: rects[i].area)
                if name == "garage"
                else min(spots, key=lambda i: rects[i].area)
            )
            take(name, pick)
    todo.sort(key=lambda t: ROOM_TYPES[t].rank)
    for i in sorted(free(), key=lambda i: -rects[i].area):
        out[i] = todo.pop(0)
    return Assignment([t or "bedroom" for t in out], pairs)


def _place_foyer(
    rects: list[Rect],
    out: list[str | None],
    todo: list[str],
    pairs: list[tuple[int, int]],
    hall: Rect,
    footprint: Rect,
    rng: np.random.Generator,
    open_plan: bool,
) -> None:
    """Put the entryway beside the hallway at the front or back of the house."""
    spots = [
        i
        for i, t in enumerate(out)
        if t is None
        and _touches_front(rects[i], footprint)
        and border_length(rects[i], hall) >= FOYER_MIN
    ]
    if not spots:
        todo[todo.index("entryway")] = fallback(todo + [t for t in out if t])
        return
    living = out.index("living room") if "living room" in out else None
    near_living = [
        i
        for i in spots
        if living is not None and border_length(rects[i], rects[living]) >= FOYER_MIN
    ]
    pool = near_living if near_living and rng.random() < 0.5 else spots
    pick = min(pool, key=lambda i: rects[i].area)
    out[pick] = "entryway"
    todo.remove("entryway")
    if rng.random() < FOYER_OPENS_TO_HALL:
        pairs.append((-1, pick))
    if open_plan and pick in near_living and rng.random() < FOYER_OPENS_TO_LIVING:
        assert living is not None
        pairs.append((living, pick))
