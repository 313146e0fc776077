"""Ground-truth spatial predicates over the objects of a synthetic :class:`Scene`.

Geometry uses each :class:`ObjectGT`'s axis-aligned box (``bbox_min``/``bbox_max``) and
centroid: world frame, z up, metres. The "footprint" is the box's xy rectangle and the
"horizontal gap" is the shortest xy distance between two footprints (0 when they touch or
overlap). An object is never in a relation with itself.

Thresholds (module constants):

- ``on(a, b)``: ``a.supported_by == b.id`` when ``a`` records its support; otherwise
  ``a``'s bottom lies within ``ON_Z_TOL`` (5 cm) of ``b``'s top and the footprints overlap
  with positive area (a chair standing on a rug).
- ``supports(a, b)`` ⇔ ``on(b, a)`` ("the table with a vase on it").
- ``above(a, b)``: same floor, the footprints overlap once each is grown by
  ``STACK_XY_MARGIN`` (10 cm), and ``a``'s bottom is no lower than ``b``'s top minus
  ``ON_Z_TOL``. ``under(a, b)`` ⇔ ``above(b, a)``: a rug is under the coffee table that
  stands on it, a mug on a table is above it, a painting hangs above the sofa.
- ``next_to(a, b)``: same room, horizontal gap ≤ ``NEXT_TO_GAP`` (0.5 m), vertical gap
  between the boxes' z ranges ≤ ``NEXT_TO_Z_GAP`` (0.3 m, so a desk is next to the window
  whose sill is just above it), and the two are not stacked (neither above the other).
- ``near(a, b)``: same floor, horizontal gap ≤ ``NEAR_GAP`` (1.5 m).
- ``between(a, b, c)``: all on one floor, ``b`` and ``c`` distinct with centres at most
  ``BETWEEN_MAX_SPAN`` (4 m) apart; ``a``'s centre projects strictly inside the xy segment
  ``b``–``c`` within ``BETWEEN_BAND`` (0.5 m) of it, and ``a`` is closer to each of ``b``
  and ``c`` than they are to each other.

Floors (``FloorGT.index``, 0 = lowest): a number names one floor with the US convention
("ground floor" = "first floor" = 0, "second floor" = 1, "third floor" = 2). Relative
words: "downstairs" and "ground" = floor 0; "upstairs" = every floor ≥ 1 (in a two-floor
house: the upper one); "top" = the highest floor.

Attributes match ``ObjectGT.attributes[key]`` case-insensitively (``colour``,
``material``, ``size`` ∈ small/medium/large). Superlatives rank by box volume
(largest/smallest) or box height (tallest/shortest). Functions ("sit", "wash hands")
come from the object kind's ``functions`` in ``vocabulary.OBJECT_KINDS``.
"""

from __future__ import annotations

import math

from inherit_sg.ingest.synthetic.scene import ObjectGT, RoomGT, Scene
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

ON_Z_TOL = 0.05
STACK_XY_MARGIN = 0.10
NEXT_TO_GAP = 0.5
NEXT_TO_Z_GAP = 0.3
NEAR_GAP = 1.5
BETWEEN_BAND = 0.5
BETWEEN_MAX_SPAN = 4.0

RELATIVE_FLOORS = ("upstairs", "downstairs", "ground", "top")
SUPERLATIVES = ("largest", "smallest", "tallest", "shortest")


def horizontal_gap(a: ObjectGT, b: ObjectGT) -> float:
    """Shortest xy distance between the two footprints (0 when they touch or overlap)."""
    dx = max(0.0, a.bbox_min[0] - b.bbox_max[0], b.bbox_min[0] - a.bbox_max[0])
    dy = max(0.0, a.bbox_min[1] - b.bbox_max[1], b.bbox_min[1] - a.bbox_max[1])
    return math.hypot(dx, dy)


def _footprints_overlap(a: ObjectGT, b: ObjectGT, margin: float) -> bool:
    for axis in (0, 1):
        low = max(a.bbox_min[axis], b.bbox_min[axis]) - margin
        high = min(a.bbox_max[axis], b.bbox_max[axis]) + margin
        if high - low <= 0.0:
            return False
    return True


def _vertical_gap(a: ObjectGT, b: ObjectGT) -> float:
    return max(0.0, a.bbox_min[2] - b.bbox_max[2], b.bbox_min[2] - a.bbox_max[2])


def on(a: ObjectGT, b: ObjectGT) -> bool:
    """``a`` stands on ``b``."""
    if a.id == b.id:
        return False
    if a.supported_by is not None:
        return a.supported_by == b.id
    return abs(a.bbox_min[2] - b.bbox_max[2]) <= ON_Z_TOL and _footprints_overlap(a, b, 0.0)


def supports(a: ObjectGT, b: ObjectGT) -> bool:
    """``b`` stands on ``a`` (``a`` has ``b`` on it)."""
    return on(b, a)


def above(a: ObjectGT, b: ObjectGT) -> bool:
    """``a`` is above ``b``: overlapping footprints, ``a`` higher up on the same floor."""
    if a.id == b.id or a.floor != b.floor:
        return False
    if a.bbox_min[2] < b.bbox_max[2] - ON_Z_TOL:
        return False
    return _footprints_overlap(a, b, STACK_XY_MARGIN)


def under(a: ObjectGT, b: ObjectGT) -> bool:
    """``a`` is under ``b`` (``b`` is above ``a``)."""
    return above(b, a)


def next_to(a: ObjectGT, b: ObjectGT) -> bool:
    """``a`` is next to ``b``: same room, close beside it, not stacked on or under it."""
    if a.id == b.id or a.room_id is None or a.room_id != b.room_id:
        return False
    if horizontal_gap(a, b) > NEXT_TO_GAP or _vertical_gap(a, b) > NEXT_TO_Z_GAP:
        return False
    return not (above(a, b) or above(b, a) or on(a, b) or on(b, a))


def near(a: ObjectGT, b: ObjectGT) -> bool:
    """``a`` is near ``b``: same floor, footprints at most ``NEAR_GAP`` apart."""
    return a.id != b.id and a.floor == b.floor and horizontal_gap(a, b) <= NEAR_GAP


def between(a: ObjectGT, b: ObjectGT, c: ObjectGT) -> bool:
    """``a`` is between ``b`` and ``c`` (see the module docstring for the band test)."""
    if len({a.id, b.id, c.id}) < 3 or not a.floor == b.floor == c.floor:
        return False
    ax, ay = a.centroid[0], a.centroid[1]
    bx, by = b.centroid[0], b.centroid[1]
    cx, cy = c.centroid[0], c.centroid[1]
    span = math.hypot(cx - bx, cy - by)
    if span <= 1e-9 or span > BETWEEN_MAX_SPAN:
        return False
    t = ((ax - bx) * (cx - bx) + (ay - by) * (cy - by)) / (span * span)
    if not 0.0 < t < 1.0:
        return False
    offset = abs((ax - bx) * (cy - by) - (ay - by) * (cx - bx)) / span
    if offset > BETWEEN_BAND:
        return False
    return math.hypot(ax - bx, ay - by) < span and math.hypot(ax - cx, ay - cy) < span


# Binary predicates by the names the constraint form uses.
BINARY_PREDICATES = {
    "on": on,
    "supports": supports,
    "above": above,
    "under": under,
    "next_to": next_to,
    "near": near,
}
# The predicate that holds with the arguments swapped.
INVERSE = {
    "on": "supports",
    "supports": "on",
    "above": "under",
    "under": "above",
    "next_to": "next_to",
    "near": "near",
}


def room_matches(room: RoomGT | None, room_type: str | None, name: str | None) -> bool:
    """Whether ``room`` has ``room_type`` and ``name`` (each ignored when None)."""
    if room is None:
        return False
    if room_type is not None and room.type.lower() != room_type.lower():
        return False
    return name is None or room.name.lower() == name.lower()


def scene_floor_levels(scene: Scene) -> list[int]:
    """The floor indices of ``scene`` (from its floors, else from its objects and rooms)."""
    levels = {f.index for f in scene.floors}
    if not levels:
        levels = {o.floor for o in scene.objects} | {r.floor for r in scene.rooms}
    return sorted(levels) or [0]


def floor_levels(scene: Scene, level: int | None, relative: str | None) -> set[int]:
    """Floor indices named by a number or a relative word (see the module docstring)."""
    levels = scene_floor_levels(scene)
    if relative is None:
        return {level} if level is not None else set(levels)
    word = relative.lower()
    if word in ("downstairs", "ground"):
        return {levels[0]}
    if word == "upstairs":
        return {lv for lv in levels if lv > levels[0]}
    if word == "top":
        return {levels[-1]}
    raise ValueError(f"unknown relative floor word {relative!r}; expected one of {RELATIVE_FLOORS}")


def has_attribute(obj: ObjectGT, key: str, value: str) -> bool:
    """Whether ``obj.attributes[key]`` equals ``value`` (case-insensitive)."""
    have = obj.attributes.get(key)
    return isinstance(have, str) and have.lower() == value.lower()


def serves(obj: ObjectGT, function: str) -> bool:
    """Whether ``obj``'s kind serves ``function`` ("sit", "wash hands", …)."""
    kind = OBJECT_KINDS.get(obj.label)
    return kind is not None and function in kind.functions


def volume(obj: ObjectGT) -> float:
    """Box volume in cubic metres."""
    return math.prod(max(0.0, hi - lo) for lo, hi in zip(obj.bbox_min, obj.bbox_max, strict=True))


def height(obj: ObjectGT) -> float:
    """Box height in metres."""
    return max(0.0, obj.bbox_max[2] - obj.bbox_min[2])


def superlative_score(obj: ObjectGT, superlative: str) -> float:
    """A score the superlative maximises: volume or height, negated for smallest/shortest."""
    if superlative == "largest":
        return volume(obj)
    if superlative == "smallest":
        return -volume(obj)
    if superlative == "tallest":
        return height(obj)
    if superlative == "shortest":
        return -height(obj)
    raise ValueError(f"unknown superlative {superlative!r}; expected one of {SUPERLATIVES}")
