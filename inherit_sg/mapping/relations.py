"""Object–object spatial relations, geometric mode (paper §III-C: "3D bounding box
offsets and vertical proximity heuristics").

Predicates keep their everyday English meaning, on axis-aligned boxes (z up, metres):

* ``on`` — a's bottom within 5 cm of b's top, footprints overlapping, a reaching higher;
* ``above`` — a higher than b's top (minus 5 cm) with footprints overlapping within
  10 cm, and not ``on`` (``under`` is its inverse and is answered from it);
* ``next to`` — same room, footprints at most 0.5 m apart, vertical gap ≤ 0.3 m, not
  stacked; stored in both directions;
* ``near`` — same floor, footprints at most 1.5 m apart; both directions;
* ``inside`` — a's box (shrunk by 2 cm) within b's box and a much smaller.

Pairs are limited to the same room or rooms joined by a door, as the paper limits them
to neighbouring areas. Confidence falls off with the margin to each threshold.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from inherit_sg.model import Edge, EdgeKind, ObjectNode

ON_Z_TOL = 0.05
STACK_XY_MARGIN = 0.10
NEXT_TO_GAP = 0.5
NEXT_TO_Z_GAP = 0.3
NEAR_GAP = 1.5


@dataclass(frozen=True)
class Relation:
    """One directed relation between two objects."""

    src: str
    dst: str
    predicate: str
    confidence: float

    def to_edge(self) -> Edge:
        """The RELATION edge of the graph."""
        return Edge.make(
            EdgeKind.RELATION,
            self.src,
            self.dst,
            predicate=self.predicate,
            confidence=round(self.confidence, 3),
        )


def _arrays(objects: Sequence[ObjectNode]) -> tuple[np.ndarray, np.ndarray]:
    lo = np.array([o.bbox.min for o in objects], dtype=float).reshape(-1, 3)
    hi = np.array([o.bbox.max for o in objects], dtype=float).reshape(-1, 3)
    return lo, hi


def infer_relations(
    objects: Sequence[ObjectNode],
    room_of: dict[str, str | None],
    neighbour_rooms: dict[str, set[str]] | None = None,
) -> list[Relation]:
    """All geometric relations among ``objects`` (vectorised over pairs)."""
    n = len(objects)
    if n < 2:
        return []
    lo, hi = _arrays(objects)
    ids = [o.id for o in objects]
    rooms = [room_of.get(i) for i in ids]
    floors = [o.floor_id for o in objects]
    neighbours = neighbour_rooms or {}
    # pairwise footprint gaps and overlaps
    dx = np.maximum(0, np.maximum(lo[:, None, 0] - hi[None, :, 0], lo[None, :, 0] - hi[:, None, 0]))
    dy = np.maximum(0, np.maximum(lo[:, None, 1] - hi[None, :, 1], lo[None, :, 1] - hi[:, None, 1]))
    gap = np.hypot(dx, dy)
    ox = np.minimum(hi[:, None, 0], hi[None, :, 0]) - np.maximum(lo[:, None, 0], lo[None, :, 0])
    oy = np.minimum(hi[:, None, 1], hi[None, :, 1]) - np.maximum(lo[:, None, 1], lo[None, :, 1])
    overlap_xy = (ox > 0) & (oy > 0)
    overlap_margin = (ox + 2 * STACK_XY_MARGIN > 0) & (oy + 2 * STACK_XY_MARGIN > 0)
    zgap = np.maximum(
        0, np.maximum(lo[:, None, 2] - hi[None, :, 2], lo[None, :, 2] - hi[:, None, 2])
    )
    bottom_to_top = lo[:, None, 2] - hi[None, :, 2]  # a bottom minus b top
    vol = np.prod(np.maximum(hi - lo, 1e-3), axis=1)

    out: list[Relation] = []
    for i in range(n):
        for j in range(n):
            if i == j or floors[i] != floors[j]:
                continue
            ri, rj = rooms[i], rooms[j]
            related_rooms = (
                ri is not None and rj is not None and (ri == rj or rj in neighbours.get(ri, ()))
            )
            if not related_rooms and not overlap_xy[i, j]:
                continue
            is_on = (
                abs(bottom_to_top[i, j]) <= ON_Z_TOL and overlap_xy[i, j] and hi[i, 2] > hi[j, 2]
            )
            if is_on:
                out.append(
                    Relation(ids[i], ids[j], "on", 1.0 - abs(bottom_to_top[i, j]) / (2 * ON_Z_TOL))
                )
            elif bottom_to_top[i, j] >= -ON_Z_TOL and overlap_margin[i, j]:
                out.append(Relation(ids[i], ids[j], "above", 0.8))
            elif (
                (lo[i] >= lo[j] - 0.02).all()
                and (hi[i] <= hi[j] + 0.02).all()
                and vol[i] < 0.5 * vol[j]
            ):
                out.append(Relation(ids[i], ids[j], "inside", 0.7))
            stacked = (bottom_to_top[i, j] >= -ON_Z_TOL and overlap_margin[i, j]) or (
                bottom_to_top[j, i] >= -ON_Z_TOL and overlap_margin[j, i]
            )
            if (
                ri is not None
                and ri == rj
                and gap[i, j] <= NEXT_TO_GAP
                and zgap[i, j] <= NEXT_TO_Z_GAP
                and not stacked
            ):
                out.append(Relation(ids[i], ids[j], "next to", 1.0 - 0.5 * gap[i, j] / NEXT_TO_GAP))
            if gap[i, j] <= NEAR_GAP:
                out.append(Relation(ids[i], ids[j], "near", 1.0 - 0.5 * gap[i, j] / NEAR_GAP))
    return out
