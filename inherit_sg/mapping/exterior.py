"""Exterior doors: the doors of a floor that lead out of the building.

People name a house's outer doors apart from the others ("the front door", "the mirror
by the entrance"), and a room that holds one is often an entrance hall. The map knows
no outside, but it knows where its rooms are: a door leads out when, across its panel,
one side lies inside the floor's footprint and the other clearly outside it.

The footprint of a floor is the union of its room masks on one grid, closed by
``close_m`` (walls and gaps between room masks) and with its holes filled
(:func:`floor_footprint`). A door object (a kind whose canonical label is ``door``)
whose footprint is thin in one horizontal direction (the panel) is probed on both
sides along that direction, at ``probe_m`` distances and ``lateral_m`` offsets along
the panel: it is exterior when at least ``outside_share`` of one side's probes fall
outside the footprint and at most ``inside_slack`` of the other side's do
(:func:`exterior_doors`). Doors to rooms the robot never entered look the same from
the map, so the test asks for a clear outside on one side and a clear inside on the
other, and :data:`EXTERIOR_DOOR` is a kind of door: a request for "the door" still finds
it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from inherit_sg.model import ObjectNode, RoomMask
from inherit_sg.vocab import objects as object_vocab

# The label an exterior door takes in the map (a kind of door in objects.toml).
EXTERIOR_DOOR = "exterior door"
DOOR = "door"


@dataclass(frozen=True)
class ExteriorParams:
    """Thresholds of the exterior-door test (metres and shares of probes)."""

    resolution: float = 0.1
    close_m: float = 0.75
    probe_m: tuple[float, ...] = (0.4, 0.7, 1.0)
    lateral_m: tuple[float, ...] = (-0.3, 0.0, 0.3)
    min_aspect: float = 1.5
    outside_share: float = 0.85
    inside_slack: float = 0.15


DEFAULT_EXTERIOR = ExteriorParams()


@dataclass(frozen=True)
class Footprint:
    """A floor's footprint on a grid: ``cells[r, c]`` covers world x in
    ``[x0 + c*res, x0 + (c+1)*res)`` and y in ``[y0 + r*res, y0 + (r+1)*res)``."""

    x0: float
    y0: float
    resolution: float
    cells: np.ndarray

    def contains(self, x: float, y: float) -> bool:
        """Whether world (x, y) lies in the footprint (False off the grid)."""
        c = math.floor((x - self.x0) / self.resolution)
        r = math.floor((y - self.y0) / self.resolution)
        h, w = self.cells.shape
        return 0 <= r < h and 0 <= c < w and bool(self.cells[r, c])


def floor_footprint(
    masks: Iterable[RoomMask], params: ExteriorParams = DEFAULT_EXTERIOR
) -> Footprint | None:
    """The closed, hole-filled union of a floor's room masks; None without masks."""
    masks = list(masks)
    if not masks:
        return None
    res = params.resolution
    margin = params.close_m + max(params.probe_m, default=0.0) + res
    x0 = min(m.origin_x for m in masks) - margin
    y0 = min(m.origin_y for m in masks) - margin
    x1 = max(m.origin_x + m.cells.shape[1] * m.resolution for m in masks) + margin
    y1 = max(m.origin_y + m.cells.shape[0] * m.resolution for m in masks) + margin
    h, w = math.ceil((y1 - y0) / res), math.ceil((x1 - x0) / res)
    ys = y0 + (np.arange(h) + 0.5) * res
    xs = x0 + (np.arange(w) + 0.5) * res
    union = np.zeros((h, w), dtype=bool)
    for m in masks:
        rows = np.floor((ys - m.origin_y) / m.resolution).astype(int)
        cols = np.floor((xs - m.origin_x) / m.resolution).astype(int)
        r_ok = (rows >= 0) & (rows < m.cells.shape[0])
        c_ok = (cols >= 0) & (cols < m.cells.shape[1])
        if not r_ok.any() or not c_ok.any():
            continue
        sub = m.cells[np.ix_(rows[r_ok], cols[c_ok])].astype(bool)
        union[np.ix_(r_ok, c_ok)] |= sub
    k = max(1, round(params.close_m / res))
    disk = np.hypot(*np.mgrid[-k : k + 1, -k : k + 1]) <= k
    closed = ndimage.binary_closing(np.pad(union, k + 1), structure=disk)[
        k + 1 : -k - 1, k + 1 : -k - 1
    ]
    return Footprint(x0, y0, res, ndimage.binary_fill_holes(closed | union))


def is_plain_door(label: str) -> bool:
    """Whether a map label names a door (or an exterior door) in the object vocabulary."""
    return object_vocab.canonical_label(label) in (DOOR, EXTERIOR_DOOR)


def _outside_share(
    foot: Footprint, node: ObjectNode, axis: int, sign: int, params: ExteriorParams
) -> float:
    x, y = node.position[0], node.position[1]
    probes = []
    for d in params.probe_m:
        for t in params.lateral_m:
            px, py = (x + sign * d, y + t) if axis == 0 else (x + t, y + sign * d)
            probes.append(not foot.contains(px, py))
    return sum(probes) / len(probes)


def is_exterior(
    foot: Footprint, node: ObjectNode, params: ExteriorParams = DEFAULT_EXTERIOR
) -> bool:
    """Whether a door object leads out of ``foot``: thin across its panel, clearly
    outside on one side and clearly inside on the other."""
    sx, sy = float(node.bbox.size[0]), float(node.bbox.size[1])
    thin, wide = min(sx, sy), max(sx, sy)
    if wide < params.min_aspect * max(thin, 1e-6):
        return False
    axis = 0 if sx < sy else 1
    sides = sorted(_outside_share(foot, node, axis, s, params) for s in (-1, 1))
    return sides[0] <= params.inside_slack and sides[1] >= params.outside_share


def exterior_doors(
    doors: Sequence[ObjectNode],
    masks_by_floor: dict[str | None, list[RoomMask]],
    params: ExteriorParams = DEFAULT_EXTERIOR,
) -> set[str]:
    """Ids of the door objects among ``doors`` that lead out of their floor's footprint
    (see the module docstring); doors of floors without room masks are never exterior."""
    feet: dict[str | None, Footprint | None] = {}
    out: set[str] = set()
    for node in doors:
        if not is_plain_door(node.label):
            continue
        if node.floor_id not in feet:
            feet[node.floor_id] = floor_footprint(masks_by_floor.get(node.floor_id, []), params)
        foot = feet[node.floor_id]
        if foot is not None and is_exterior(foot, node, params):
            out.add(node.id)
    return out
