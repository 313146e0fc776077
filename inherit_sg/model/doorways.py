"""Objects that stand in a doorway belong to both rooms it joins.

A door, a curtain or a rug in an opening is mapped in one room (the one its centre falls
in, often by a few centimetres), but people call it the door of either room: "the doors
in the hall" and "the kitchen door" may be the same door. The scene graph records where
two rooms meet as the ``door`` point of their CONNECTS edge; an object whose footprint
covers that point (within a margin) stands in the doorway.

Room typing counts such an object in both rooms (a hall is a room many doors open from),
and retrieval matches it in both (see ``MapSnapshot.doorway_rooms``).
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from inherit_sg.model.graph import SceneGraph
from inherit_sg.model.ids import EdgeKind

# How far outside an object's box a doorway point may lie and the object still stand in
# the doorway (metres): the point is the middle of the opening, and a door's box may be
# mapped a little short of it.
DOORWAY_MARGIN = 0.15


@dataclass(frozen=True)
class Doorway:
    """Where two rooms of one storey meet."""

    x: float
    y: float
    rooms: tuple[str, str]
    floor: str | None


def doorways_of(graph: SceneGraph, floor_of: Callable[[str], str | None]) -> list[Doorway]:
    """The doorways of ``graph``'s CONNECTS edges that record a door point and join two
    rooms ``floor_of`` knows the storey of (None for either room: storey not checked)."""
    out = []
    for edge in graph.edges(EdgeKind.CONNECTS):
        door = edge.prop("door")
        if door is None or len(door) < 2 or edge.src == edge.dst:
            continue
        floor = floor_of(edge.src)
        out.append(Doorway(float(door[0]), float(door[1]), (edge.src, edge.dst), floor))
    return out


def doorway_rooms(
    lo: np.ndarray,
    hi: np.ndarray,
    floors: Sequence[str | None],
    rooms: Sequence[str | None],
    doorways: Sequence[Doorway],
    margin: float = DOORWAY_MARGIN,
) -> dict[int, tuple[str, ...]]:
    """Row → the rooms other than its own (``rooms[row]``) of the doorways the object of
    that row stands in (a doorway counts only when the object is mapped in one of its
    rooms, or in none). ``lo`` / ``hi``: box corners, shape (N, ≥2), x and y first;
    ``floors``: each row's storey (None: any)."""
    out: dict[int, set[str]] = defaultdict(set)
    if len(lo) == 0:
        return {}
    lo_xy = np.asarray(lo, dtype=float)[:, :2] - margin
    hi_xy = np.asarray(hi, dtype=float)[:, :2] + margin
    floor_arr = np.array([f or "" for f in floors], dtype=object)
    for door in doorways:
        covers = (
            (lo_xy[:, 0] <= door.x)
            & (door.x <= hi_xy[:, 0])
            & (lo_xy[:, 1] <= door.y)
            & (door.y <= hi_xy[:, 1])
        )
        if door.floor is not None:
            covers &= (floor_arr == door.floor) | (floor_arr == "")
        for row in np.flatnonzero(covers).tolist():
            own = rooms[row]
            if own is None or own in door.rooms:  # (mapped in a third room: not in it)
                out[row].update(r for r in door.rooms if r != own)
    return {row: tuple(sorted(found)) for row, found in out.items() if found}
