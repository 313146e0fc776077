"""Object sizes as requests mean them: robust to flat boxes and relative to the kind.

Map boxes come from the depth points the cameras saw: a wall clock seen from the front
has a box a fraction of a millimetre deep, and a part seen in a single view can be a
sliver of a larger object. Hence:

- "the biggest" / "the smallest" compare :func:`bulk`, the geometric mean of a box's
  face area (its two longest sides) and its robust volume: a box seen from one side
  measures its depth worst;
- size words ("a large mug") use :func:`robust_volume`, the box volume with every side
  floored at a share of the longest side, so that flat boxes keep the area they show;
- :func:`measured_in_views` keeps single-view objects out of a comparison when objects
  seen from several views can be compared instead;
- size words are relative to the kind: "a large mug" is smaller than "a small table".
  :func:`kind_sizes` gives the median linear size of each label in the map, and
  :func:`size_word` names an object's size relative to it.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Iterable

from inherit_sg.model import ObjectNode

# Each side counts at least this share of the longest side (flat boxes keep an area).
FLAT_SHARE = 0.1
# Linear size relative to the kind's median: below SMALL is small, above LARGE is large.
SMALL_BELOW = 0.93
LARGE_ABOVE = 1.1
# How fast a size word's match falls off outside its band (share of linear size).
SIZE_SOFTNESS = 0.15
# Inside the "large" / "small" band a size word scores 1 - IN_BAND_SPREAD at the band's
# edge, rising to 1 at EXTREME_SPAN beyond it (ratio to the kind's median).
IN_BAND_SPREAD = 0.1
EXTREME_SPAN = 0.5
# Fewest objects of a label that make a reference for relative size words (two: "the
# large TV" of a pair is the bigger one).
MIN_PEERS = 2
# Views needed before a box counts as measured for size comparisons.
MIN_VIEWS = 2


def robust_volume(extent: Iterable[float]) -> float:
    """Box volume with every side floored at ``FLAT_SHARE`` of the longest side."""
    sides = [max(0.0, float(v)) for v in extent]
    longest = max(sides, default=0.0)
    return math.prod(max(s, FLAT_SHARE * longest) for s in sides)


def face_area(extent: Iterable[float]) -> float:
    """Product of the box's two longest sides: how big a thing looks."""
    sides = sorted((max(0.0, float(v)) for v in extent), reverse=True)
    return math.prod(sides[:2]) if len(sides) >= 2 else 0.0


def bulk(extent: Iterable[float]) -> float:
    """How big a thing is, as "the biggest" / "the smallest" compare it: the geometric
    mean of its face area and its robust volume. A box seen from one side measures its
    depth worst (a wall-mounted TV mapped with its bracket is no bigger than a wider
    screen), yet a floor pouf is bigger than a flat cushion of the same face."""
    sides = [float(v) for v in extent]
    return math.sqrt(face_area(sides) * robust_volume(sides))


def linear_size(node: ObjectNode) -> float:
    """Cube root of the robust volume of the node's box (metres)."""
    return robust_volume(node.bbox.size) ** (1.0 / 3.0)


def measured_in_views(node: ObjectNode) -> bool:
    """Whether the node's box was fused from at least ``MIN_VIEWS`` views."""
    return node.observation_count >= MIN_VIEWS


def kind_sizes(objects: Iterable[ObjectNode]) -> dict[str, float]:
    """Median linear size per label (lower case) over the objects measured in several
    views; labels with fewer than ``MIN_PEERS`` of them have no reference."""
    by_label: dict[str, list[float]] = {}
    for obj in objects:
        if measured_in_views(obj):
            by_label.setdefault(obj.label.lower(), []).append(linear_size(obj))
    return {
        label: ref
        for label, sizes in by_label.items()
        if len(sizes) >= MIN_PEERS and (ref := statistics.median(sizes)) > 0
    }


def size_word(ratio: float) -> str:
    """small / medium / large from a linear size relative to the kind's median."""
    if ratio < SMALL_BELOW:
        return "small"
    return "large" if ratio > LARGE_ABOVE else "medium"


_BANDS = {
    "small": (0.0, SMALL_BELOW),
    "medium": (SMALL_BELOW, LARGE_ABOVE),
    "large": (LARGE_ABOVE, math.inf),
}


def size_word_sim(ratio: float, word: str) -> float:
    """Near 1 inside the word's band of relative size (for "large" and "small" rising
    from 1 - ``IN_BAND_SPREAD`` at the band's edge to 1 at ``EXTREME_SPAN`` beyond it),
    falling linearly to 0 at ``SIZE_SOFTNESS`` outside it (words other than small /
    medium / large: 0)."""
    band = _BANDS.get(word)
    if band is None:
        return 0.0
    lo, hi = band
    gap = max(lo - ratio, ratio - hi, 0.0)
    if gap > 0.0:
        return max(0.0, 1.0 - gap / SIZE_SOFTNESS)
    # inside the band, the more extreme the surer ("the big sofa": the biggest of the big)
    if word == "large":
        return 1.0 - IN_BAND_SPREAD * (1.0 - min(1.0, (ratio - lo) / EXTREME_SPAN))
    if word == "small":
        return 1.0 - IN_BAND_SPREAD * (1.0 - min(1.0, (hi - ratio) / EXTREME_SPAN))
    return 1.0
