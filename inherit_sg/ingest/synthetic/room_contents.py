"""What the rooms of the real-world generator hold: functional groups (the ground truth's
areas) per room type, each with an anchor piece and members drawn with their own
chances and counts.

A member is written ``label@chance*min-max`` (``@`` and ``*`` optional: always one).
The first group of a room is always placed; the others come with their chance, as many
as the room's floor area allows. The chances follow how often Matterport3D annotates
each kind (pictures, pillows, chairs, lights, curtains, cabinets, plants and towels are
everywhere; pool tables and dartboards are rare); where a kind goes is the kind's own
business (:mod:`inherit_sg.ingest.synthetic.catalogue`: on which supporters, on a wall, at a window,
from the ceiling).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

_MEMBER = re.compile(
    r"^(?P<label>[a-z][a-z ]*?)(?:@(?P<p>[0-9.]+))?(?:\*(?P<a>\d+)(?:-(?P<b>\d+))?)?$"
)


@dataclass(frozen=True)
class Member:
    """A kind in a group: present with ``chance``, then ``count`` of them (inclusive)."""

    label: str
    chance: float = 1.0
    count: tuple[int, int] = (1, 1)


@dataclass(frozen=True)
class Group:
    """A functional group: one of ``anchors`` (the piece the others gather round) and
    the members; ``chance`` is that of the group in its room (the first is always)."""

    label: str
    anchors: tuple[str, ...]
    members: tuple[Member, ...]
    chance: float = 1.0


def parse_members(text: str) -> tuple[Member, ...]:
    """Members from ``"label@chance*min-max, ..."``."""
    out = []
    for token in (t.strip() for t in text.split(",")):
        if not token:
            continue
        m = _MEMBER.match(token)
        if m is None:
            raise ValueError(f"bad member {token!r}")
        a = int(m["a"]) if m["a"] else 1
        b = int(m["b"]) if m["b"] else a
        out.append(Member(m["label"], float(m["p"]) if m["p"] else 1.0, (a, b)))
    return tuple(out)


def _g(label: str, anchors: str, members: str, chance: float = 1.0) -> Group:
    return Group(
        label, tuple(a.strip() for a in anchors.split("|")), parse_members(members), chance
    )


_TV = "tv stand@0.8, tv@0.85, rug@0.6, pillow@0.95*2-5, remote@0.5, side table@0.55, table lamp@0.5, lamp@0.45, blanket@0.3, decoration@0.5*1-3, book@0.35*1-3, vase@0.3"
_LIVING_WALLS = "painting@0.8*1-3, curtain@0.6*1-2, ceiling light@0.65, light switch@0.35, plant@0.5*1-2, radiator@0.15, air conditioner@0.05, clock@0.2"
_DECOR = "vase@0.4, plant@0.35, decoration@0.6*1-3, statue@0.15, candle@0.25, flower pot@0.25, clock@0.2, book@0.3*1-3, box@0.2"

ROOM_CONTENTS: dict[str, tuple[Group, ...]] = {
    "bedroom": (
        _g(
            "sleeping area",
            "bed",
            "pillow*2-5, nightstand@0.9*1-2, table lamp@0.75*1-2, blanket@0.5, book@0.4*1-2, clock@0.35, phone@0.25, stuffed animal@0.15, tissue box@0.2, radiator@0.15, air conditioner@0.06, painting@0.75*1-2, curtain@0.65*1-2, blinds@0.2, ceiling light@0.65, ceiling fan@0.15, rug@0.4, light switch@0.35, clothes@0.2",
        ),
        _g(
            "storage area",
            "wardrobe|dresser",
            "dresser@0.45, mirror@0.5, guitar@0.05, clothes@0.35*1-2, box@0.3, handbag@0.25, hat@0.15, cosmetics@0.3*1-2, basket@0.25, shoe@0.35*1-2, trash can@0.3, tv@0.12, decoration@0.3",
            0.9,
        ),
        _g(
            "work area",
            "desk",
            "office chair@0.6, laptop@0.5, table lamp@0.5, book@0.4*1-2, monitor@0.15, mug@0.3, bag@0.2",
            0.35,
        ),
        _g("decoration area", "shelf|side table|cabinet", f"{_DECOR}, stuffed animal@0.2", 0.35),
        _g(
            "reading corner",
            "armchair",
            "lamp@0.7, side table@0.5, book@0.5, pillow@0.4, bookshelf@0.3, footstool@0.3",
            0.2,
        ),
    ),
    "bathroom": (
        _g(
            "washing area",
            "sink",
            "mirror@0.9, soap dispenser@0.6, soap@0.35, toothbrush@0.5*1-2, towel@0.75*1-2, cosmetics@0.3, toiletry@0.6*1-3, bathroom cabinet@0.45, towel rack@0.5, wall light@0.3, light switch@0.35, ceiling light@0.6, trash can@0.45, plant@0.1",
        ),
        _g(
            "toilet area",
            "toilet",
            "toilet paper@0.85*1-2, toilet brush@0.5, tissue box@0.15, painting@0.25",
            0.95,
        ),
        _g(
            "bathing area",
            "bathtub|shower",
            "shampoo@0.6*1-3, bath mat@0.55, scale@0.25, shelf@0.25, towel@0.35*1-2, blinds@0.15",
            0.85,
        ),
    ),
    "toilet": (
        _g(
            "toilet area",
            "toilet",
            "toilet paper*1-2, toilet brush@0.45, trash can@0.4, painting@0.35, ceiling light@0.55, plant@0.15",
        ),
        _g(
            "washing area",
            "sink",
            "mirror@0.85, soap dispenser@0.55, soap@0.3, towel@0.65, light switch@0.35, toiletry@0.3",
            0.9,
        ),
    ),
    "kitchen": (
        _g(
            "cooking area",
            "counter",
            "refrigerator@0.95, stove@0.8, sink, dishwasher@0.55, oven@0.3, range hood@0.45, kitchen cabinet@0.75*1-3, wall cabinet@0.6*1-2, microwave@0.65, kettle@0.5, toaster@0.35, coffee machine@0.45, cutting board@0.35, knife block@0.35, dish rack@0.35, paper towel@0.45, bottle@0.65*1-3, jar@0.4*1-3, bowl@0.4*1-2, plate@0.3*1-2, glass@0.3*1-2, pan@0.4, teapot@0.12, mug@0.4*1-2, spice rack@0.2, fruit bowl@0.25, fire extinguisher@0.08, trash can@0.7, ceiling light@0.75, blinds@0.3, light switch@0.35, plant@0.15",
        ),
        _g(
            "dining area",
            "table|kitchen island",
            "chair@0.6*2-4, bar stool@0.5*2-3, plate@0.35*1-2, fruit bowl@0.3, mug@0.3, glass@0.25, vase@0.15",
            0.55,
        ),
        _g(
            "storage area",
            "shelf|cabinet",
            "jar@0.5*1-3, bottle@0.5*1-3, box@0.25, plant@0.25, clock@0.25, bowl@0.3",
            0.35,
        ),
    ),
    "dining room": (
        _g(
            "dining area",
            "dining table",
            "dining chair@0.8*4-6, chair@0.3*2-4, chandelier@0.55, plate@0.5*1-4, bowl@0.35, glass@0.4*1-4, vase@0.4, candle@0.3*1-2, fruit bowl@0.25, bottle@0.25, painting@0.75*1-2, rug@0.35, curtain@0.5*1-2, ceiling light@0.35, plant@0.35",
        ),
        _g(
            "storage area",
            "sideboard|cabinet",
            f"{_DECOR}, plate@0.25, bottle@0.3, mirror@0.15",
            0.6,
        ),
    ),
    "living room": (
        _g(
            "tv area",
            "sofa",
            f"coffee table@0.85, armchair@0.6*1-2, {_TV}, mug@0.2, speaker@0.25*1-2, game console@0.12, ottoman@0.2, tray@0.15, {_LIVING_WALLS}",
        ),
        _g("decoration area", "cabinet|sideboard|console table|shelf", _DECOR, 0.55),
        _g(
            "reading corner",
            "armchair|recliner",
            "lamp@0.7, bookshelf@0.6, book@0.7*2-5, side table@0.4, pillow@0.35, plant@0.3, footstool@0.2",
            0.3,
        ),
        _g(
            "fireplace area",
            "fireplace",
            "decoration@0.6*1-3, candle@0.45*1-2, painting@0.55, clock@0.35, armchair@0.3",
            0.15,
        ),
        _g("music corner", "piano", "stool@0.6, lamp@0.3, book@0.3", 0.05),
    ),
    "family room": (
        _g(
            "tv area",
            "sofa|recliner",
            f"coffee table@0.7, armchair@0.4, recliner@0.3, {_TV}, speaker@0.3*1-2, game console@0.2, ottoman@0.25, {_LIVING_WALLS}",
        ),
        _g("play area", "shelf", "toy@0.9*1-4, stuffed animal@0.5*1-2, box@0.35, rug@0.4", 0.25),
        _g("decoration area", "cabinet|shelf|console table", _DECOR, 0.35),
        _g(
            "reading corner",
            "armchair",
            "lamp@0.6, bookshelf@0.5, book@0.6*2-4, side table@0.4",
            0.25,
        ),
    ),
    "tv room": (
        _g(
            "tv area",
            "sofa|recliner",
            f"tv stand, tv, speaker@0.45*1-2, game console@0.4, coffee table@0.6, armchair@0.4, recliner@0.3, ottoman@0.25, rug@0.5, pillow@0.85*2-4, remote@0.65, lamp@0.35, blanket@0.3, {_LIVING_WALLS}",
        ),
        _g("storage area", "shelf|cabinet", "box@0.3, book@0.4*1-4, decoration@0.4*1-2", 0.35),
    ),
    "office": (
        _g(
            "work area",
            "desk",
            "office chair@0.85, monitor@0.6*1-2, keyboard@0.55, mouse@0.5, laptop@0.35, table lamp@0.55, printer@0.3, phone@0.3, mug@0.35, book@0.4*1-3, computer@0.3, trash can@0.55, painting@0.6*1-2, plant@0.35, ceiling light@0.65, blinds@0.3, curtain@0.3, light switch@0.35, whiteboard@0.1, clock@0.2",
        ),
        _g(
            "storage area",
            "bookshelf|filing cabinet|shelf",
            "book@0.85*3-8, box@0.35*1-2, decoration@0.35*1-2, globe@0.12, clock@0.2, printer@0.15, plant@0.2",
            0.75,
        ),
        _g("meeting area", "table", "chair@0.9*2-3, plant@0.3", 0.15),
    ),
    "hallway": (
        _g(
            "decoration area",
            "console table|cabinet|bench",
            "mirror@0.45, painting@0.75*1-3, plant@0.35, vase@0.3, decoration@0.3, table lamp@0.2, rug@0.35, light switch@0.45, smoke detector@0.35, ceiling light@0.75, coat rack@0.12, thermostat@0.25, clock@0.15",
        ),
    ),
    "entryway": (
        _g(
            "entrance area",
            "console table|bench|shoe rack",
            "shoe@0.7*2-5, shoe rack@0.3, coat rack@0.5, umbrella@0.35, mirror@0.55, rug@0.65, bowl@0.2, table lamp@0.25, plant@0.35, painting@0.5*1-2, light switch@0.55, ceiling light@0.65, bag@0.25, backpack@0.25, handbag@0.2, hat@0.15, decoration@0.2",
        ),
    ),
    "closet": (
        _g(
            "storage area",
            "shelf|wardrobe",
            "clothes@0.8*1-4, shoe@0.6*2-4, box@0.6*1-3, hat@0.35, handbag@0.35, suitcase@0.35, shoe rack@0.3, vacuum cleaner@0.15, basket@0.25, storage bin@0.3, ceiling light@0.65, bag@0.2",
        ),
    ),
    "laundry room": (
        _g(
            "laundry area",
            "washing machine",
            "dryer@0.8, basket@0.65, laundry detergent@0.65*1-2, shelf@0.55, sink@0.35, ironing board@0.3, towel@0.4*1-2, clothes@0.35*1-2, trash can@0.25, bucket@0.25, broom@0.2, cabinet@0.4, wall cabinet@0.3, ceiling light@0.65, light switch@0.35, box@0.2",
        ),
    ),
    "utility room": (
        _g(
            "utility area",
            "water heater|furnace|shelf",
            "shelf@0.5, box@0.65*1-4, storage bin@0.45, vacuum cleaner@0.3, broom@0.3, mop@0.25, bucket@0.3, toolbox@0.3, ladder@0.3, electrical panel@0.45, paint can@0.25*1-2, ceiling light@0.55",
        ),
    ),
    "garage": (
        _g("parking area", "car", "bicycle@0.3, trash can@0.45"),
        _g(
            "workshop area",
            "workbench",
            "toolbox@0.6, tool cabinet@0.3, shelf@0.55, box@0.65*1-4, storage bin@0.45*1-2, ladder@0.3, lawn mower@0.25, paint can@0.35*1-3, broom@0.2, electrical panel@0.2, bucket@0.2",
            0.8,
        ),
    ),
    "library": (
        _g(
            "reading corner",
            "bookshelf",
            "bookshelf@0.9*1-2, book@0.95*5-10, armchair@0.8, lamp@0.6, side table@0.5, globe@0.3, rug@0.5, desk@0.3, painting@0.45, ceiling light@0.5, decoration@0.3*1-2",
        ),
    ),
    "rec room": (
        _g(
            "game area",
            "pool table|ping pong table",
            "dartboard@0.35, bar stool@0.35*2, guitar@0.2, painting@0.5*1-2, ceiling light@0.6",
        ),
        _g(
            "seating area",
            "sofa",
            "tv@0.35, tv stand@0.35, coffee table@0.4, pillow@0.65*2-3, game console@0.2, rug@0.4",
            0.6,
        ),
    ),
    "gym": (
        _g(
            "workout area",
            "treadmill|exercise bike|weight bench",
            "weight bench@0.4, exercise bike@0.3, dumbbell@0.65*2-4, yoga mat@0.5, exercise ball@0.35, mirror@0.55, fan@0.3, bottle@0.3, towel@0.25, ceiling light@0.65, tv@0.15",
        ),
    ),
    "bar": (
        _g(
            "bar area",
            "bar counter",
            "bar stool@0.9*2-4, wine rack@0.6, bottle@0.85*2-6, glass@0.75*2-4, mini fridge@0.5, shelf@0.45, painting@0.45, ceiling light@0.6",
        ),
    ),
    "porch": (
        _g(
            "patio seating area",
            "picnic table|outdoor chair",
            "outdoor chair@0.8*1-3, plant@0.65*1-2, flower pot@0.55*1-3, lantern@0.3, watering can@0.25, bench@0.3",
        ),
    ),
    "balcony": (
        _g(
            "patio seating area",
            "outdoor chair|picnic table",
            "outdoor chair@0.65*1-2, plant@0.65*1-2, flower pot@0.55*1-3, lantern@0.2",
        ),
    ),
}


def choose_groups(room_type: str, area: float, rng: np.random.Generator) -> list[Group]:
    """The groups a room of ``room_type`` and floor ``area`` (m²) gets: its first group
    and the others drawn by their chances, as many as its size allows."""
    groups = ROOM_CONTENTS.get(room_type, ())
    if not groups:
        return []
    room_for = int(np.clip(1 + (area - 4.0) // 4.0, 1, len(groups)))
    extra = [g for g in groups[1:] if rng.random() < g.chance]
    return [groups[0], *extra[: room_for - 1]]


def draw_members(group: Group, rng: np.random.Generator) -> tuple[str, list[str]]:
    """The anchor and the member labels of one placement of ``group``."""
    anchor = group.anchors[int(rng.integers(len(group.anchors)))]
    labels: list[str] = []
    for m in group.members:
        if rng.random() < m.chance:
            labels += [m.label] * int(rng.integers(m.count[0], m.count[1] + 1))
    return anchor, labels
