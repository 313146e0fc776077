"""Room types of the real-world generator (the Matterport3D region categories) and how
often homes have them.

Each house draws a programme: the room types of every storey, besides its hallway. Every
house has a kitchen, a living room, at least one bedroom and one bathroom; the other
types come with the chances below (per house; per upper storey for the upper-storey
types), which follow what homes have: dining rooms, toilets, closets, laundry rooms,
entryways, offices and TV or family rooms are common, gyms, libraries and bars rare.
The programme is trimmed to the rooms a storey has (least likely types dropped first)
or filled up with the types that grow with a home's size (bedrooms, bathrooms,
closets, offices).

Matterport3D's "stairs" regions are not drawn: the generator's staircases stand in the
hallway. Region codes are Matterport3D's ``R``-line label codes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class RoomType:
    """One region category: its Matterport3D label code, a size rank (0 = largest; big
    rooms get the big rectangles) and whether it needs an exterior wall."""

    name: str
    code: str
    rank: int
    edge: bool = False


ROOM_TYPES: dict[str, RoomType] = {
    t.name: t
    for t in (
        RoomType("garage", "g", 0, edge=True),
        RoomType("living room", "l", 1),
        RoomType("family room", "f", 2),
        RoomType("rec room", "r", 2),
        RoomType("kitchen", "k", 3),
        RoomType("dining room", "d", 4),
        RoomType("tv room", "v", 5),
        RoomType("bedroom", "b", 5),
        RoomType("library", "i", 6),
        RoomType("gym", "w", 6),
        RoomType("office", "o", 7),
        RoomType("bar", "B", 7),
        RoomType("porch", "p", 8, edge=True),
        RoomType("balcony", "y", 9, edge=True),
        RoomType("laundry room", "j", 9),
        RoomType("bathroom", "a", 10),
        RoomType("utility room", "u", 10),
        RoomType("entryway", "e", 11),
        RoomType("closet", "c", 12),
        RoomType("toilet", "t", 12),
        RoomType("hallway", "h", 13),
    )
}

# Optional types of the ground storey and of each upper storey: (type, chance). Order is
# priority: when a storey has fewer rooms than drawn types, the later ones go first.
GROUND_OPTIONS: tuple[tuple[str, float], ...] = (
    ("dining room", 0.75),
    ("entryway", 0.45),
    ("toilet", 0.55),
    ("garage", 0.3),
    ("laundry room", 0.35),
    ("office", 0.3),
    ("family room", 0.25),
    ("tv room", 0.15),
    ("closet", 0.25),
    ("utility room", 0.15),
    ("porch", 0.07),
    ("rec room", 0.06),
    ("library", 0.04),
    ("gym", 0.04),
    ("bar", 0.03),
)
UPPER_OPTIONS: tuple[tuple[str, float], ...] = (
    ("bedroom", 0.9),
    ("closet", 0.6),
    ("bathroom", 0.55),
    ("office", 0.35),
    ("bedroom", 0.45),
    ("laundry room", 0.25),
    ("closet", 0.25),
    ("tv room", 0.15),
    ("balcony", 0.12),
    ("family room", 0.1),
    ("gym", 0.05),
    ("rec room", 0.05),
    ("library", 0.04),
)
# Types that fill a storey with more rooms than its programme: (type, weight).
GROUND_FILL: tuple[tuple[str, float], ...] = (
    ("office", 1.0),
    ("family room", 1.0),
    ("closet", 1.0),
    ("laundry room", 0.6),
    ("bedroom", 1.0),
    ("bathroom", 0.6),
)
UPPER_FILL: tuple[tuple[str, float], ...] = (
    ("bedroom", 3.0),
    ("bathroom", 1.0),
    ("closet", 1.2),
    ("office", 0.8),
)
# At most this many rooms of a type on one storey.
CAPS = {
    **{t: 1 for t in ("kitchen", "living room", "dining room", "garage", "entryway", "toilet")},
    **{t: 1 for t in ("laundry room", "utility room", "family room", "tv room", "porch")},
    **{t: 1 for t in ("balcony", "rec room", "gym", "library", "bar")},
    "office": 2,
    "closet": 2,
}
# Stand-ins, in order, for a type that finds no place on its storey.
FALLBACKS = ("office", "family room", "closet", "bedroom")


def fallback(existing: list[str]) -> str:
    """The first stand-in type not yet at its cap among ``existing``."""
    for name in FALLBACKS:
        if existing.count(name) < CAPS.get(name, 99):
            return name
    return "bedroom"


def _draw(options: tuple[tuple[str, float], ...], rng: np.random.Generator) -> list[str]:
    return [name for name, chance in options if rng.random() < chance]


def _fit(
    required: list[str],
    drawn: list[str],
    fill: tuple[tuple[str, float], ...],
    slots: int,
    rng: np.random.Generator,
) -> list[str]:
    """``required`` then ``drawn`` cut or filled up to ``slots`` types."""
    types: list[str] = []
    for name in required + drawn:
        if len(types) < slots and types.count(name) < CAPS.get(name, 99):
            types.append(name)
    while len(types) < slots:
        pool = [(n, w) for n, w in fill if types.count(n) < CAPS.get(n, 99)]
        weights = np.array([w for _, w in pool])
        types.append(pool[int(rng.choice(len(pool), p=weights / weights.sum()))][0])
    return types


def draw_programme(rng: np.random.Generator, slots: list[int]) -> list[list[str]]:
    """Room types of every storey (hallways aside) for storeys with ``slots`` rooms each."""
    ground = ["living room", "kitchen"]
    if len(slots) == 1:
        ground += ["bedroom", "bathroom"]
    out = [_fit(ground, _draw(GROUND_OPTIONS, rng), GROUND_FILL, slots[0], rng)]
    for count in slots[1:]:
        out.append(_fit(["bedroom", "bathroom"], _draw(UPPER_OPTIONS, rng), UPPER_FILL, count, rng))
    return out


def region_code(room_type: str) -> str:
    """The Matterport3D region label code of a room type ("-" when unknown)."""
    spec = ROOM_TYPES.get(room_type)
    return spec.code if spec is not None else "-"
