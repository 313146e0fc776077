"""Over-segmented rooms: join two geometric rooms that are one room.

The geometric segmentation keeps two rooms apart at a constriction at most a door wide.
In a small room (a bathroom whose vanity and shower make a waist, an L-shaped room) such
a constriction can be the room's own narrowing, not a door. What the room holds tells
them apart: two rooms are joined when

1. they are geometric rooms (not parts of an open-plan split, which is done after the
   merge) and touch through a passage the segmentation found (no known door there: a
   CONNECTS edge whose ``source`` is not ``"semantic"``);
2. the passage is wide: at least ``min_opening_m`` and at least ``min_opening_share`` of
   the narrower room's width (the widest disc that fits in it), so the opening is about
   as wide as the room itself;
3. their inferred types agree: both rooms' best types are the same (not the catch-all
   "other room"), or one of them has no type evidence at all and takes the other's;
4. the union is still a plausible room of that type: its floor area lies inside the
   type's typical range (``area`` in ``rooms.toml``).

Pairs are tried widest opening first and groups grow (the union is checked again with
all its objects). In the scene graph (:func:`merge_over_segmented_rooms`) a group keeps
the id of its first room (by room number), so repeated updates with the same content
give the same ids; the other rooms are removed, their objects and CONNECTS edges move to
the kept room, and the kept room's mask is the union of the group's masks.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from inherit_sg.mapping.open_plan import is_part_id
from inherit_sg.mapping.room_semantics import (
    OTHER_TYPE,
    infer_room_types,
    room_shape,
    type_evidence,
)
from inherit_sg.model import Edge, EdgeKind, Layer, ObjectNode, RoomMask, RoomNode, SceneGraph
from inherit_sg.vocab import rooms as room_vocab

# CONNECTS edges from a known door carry this source; they never join rooms.
DOOR_SOURCE = "semantic"


@dataclass(frozen=True)
class MergeParams:
    """Thresholds of the room merge.

    ``min_opening_m``: the narrowest passage (m) that can be a room's own waist;
    ``min_opening_share``: the passage width over the narrower room's width at least.
    """

    min_opening_m: float = 1.0
    min_opening_share: float = 0.75


DEFAULT_MERGE = MergeParams()


def union_mask(masks: Sequence[RoomMask]) -> RoomMask:
    """The union of room masks on one grid (the first mask's resolution and phase)."""
    first = masks[0]
    res = first.resolution
    cols0 = [round((m.origin_x - first.origin_x) / res) for m in masks]
    rows0 = [round((m.origin_y - first.origin_y) / res) for m in masks]
    c_lo = min(cols0)
    r_lo = min(rows0)
    c_hi = max(c + m.cells.shape[1] for c, m in zip(cols0, masks, strict=True))
    r_hi = max(r + m.cells.shape[0] for r, m in zip(rows0, masks, strict=True))
    cells = np.zeros((r_hi - r_lo, c_hi - c_lo), dtype=bool)
    for r, c, m in zip(rows0, cols0, masks, strict=True):
        h, w = m.cells.shape
        cells[r - r_lo : r - r_lo + h, c - c_lo : c - c_lo + w] |= m.cells.astype(bool)
    return RoomMask(first.origin_x + c_lo * res, first.origin_y + r_lo * res, res, cells)


def _has_evidence(labels: Sequence[str]) -> bool:
    return any(v > 0 for v in type_evidence(labels).values())


def best_type(labels: Sequence[str], mask: RoomMask | None) -> str:
    """The best inferred type of a room holding ``labels`` with footprint ``mask``."""
    return infer_room_types(labels, shape=room_shape(mask))[0][0]


def merged_type(
    a_labels: Sequence[str],
    a_mask: RoomMask,
    b_labels: Sequence[str],
    b_mask: RoomMask,
) -> str | None:
    """The type two touching rooms are one room of, or None when they are two: the same
    best type for both (or the one with evidence, when the other has none), the union
    holding everything and of a floor area inside the type's typical range."""
    a_ev, b_ev = _has_evidence(a_labels), _has_evidence(b_labels)
    if not (a_ev or b_ev):
        return None
    ta = best_type(a_labels, a_mask) if a_ev else None
    tb = best_type(b_labels, b_mask) if b_ev else None
    if ta is not None and tb is not None and ta != tb:
        return None
    name = ta or tb
    if name is None or name == OTHER_TYPE:
        return None
    union = union_mask([a_mask, b_mask])
    if best_type([*a_labels, *b_labels], union) != name:
        return None
    typical = room_vocab.room_type_table()[name].area
    if typical is not None and not typical[0] <= union.area_m2 <= typical[1]:
        return None
    return name


def _room_order(room_id: str) -> tuple[int, float, str]:
    """Sort key of room ids: by room number, then by name."""
    num = room_id.partition(":")[2]
    try:
        return (0, float(num), room_id)
    except ValueError:
        return (1, math.inf, room_id)


def plan_merges(
    rooms: dict[str, RoomNode],
    by_room: dict[str, list[ObjectNode]],
    connects: Sequence[Edge],
    params: MergeParams | None = None,
) -> dict[str, str]:
    """Which rooms join which: absorbed room id -> kept room id (the group's first)."""
    params = params or MergeParams()
    widths: dict[str, float] = {}
    for rid, room in rooms.items():
        shape = room_shape(room.mask)
        widths[rid] = shape.width_m if shape is not None else 0.0
    candidates: list[tuple[float, str, str]] = []
    for e in connects:
        if e.src == e.dst or e.src not in rooms or e.dst not in rooms:
            continue
        if is_part_id(e.src) or is_part_id(e.dst):  # parts of an open-plan split
            continue
        if e.prop("source") == DOOR_SOURCE:
            continue
        if rooms[e.src].floor_id != rooms[e.dst].floor_id:
            continue
        width = float(e.prop("width", 0.0) or 0.0)
        narrower = min(widths[e.src], widths[e.dst])
        if width < params.min_opening_m or width < params.min_opening_share * narrower:
            continue
        first, second = sorted((e.src, e.dst), key=_room_order)
        candidates.append((width, first, second))
    candidates.sort(key=lambda t: (-t[0], _room_order(t[1]), _room_order(t[2])))
    group: dict[str, str] = {rid: rid for rid in rooms}  # room -> its group's first room
    members: dict[str, list[str]] = {rid: [rid] for rid in rooms}
    masks: dict[str, RoomMask] = {rid: r.mask for rid, r in rooms.items() if r.mask is not None}
    labels: dict[str, list[str]] = {rid: [o.label for o in by_room.get(rid, [])] for rid in rooms}
    for _, a, b in candidates:
        ga, gb = group[a], group[b]
        if ga == gb or ga not in masks or gb not in masks:
            continue
        if merged_type(labels[ga], masks[ga], labels[gb], masks[gb]) is None:
            continue
        keep, drop = sorted((ga, gb), key=_room_order)
        masks[keep] = union_mask([masks[keep], masks[drop]])
        labels[keep] = labels[keep] + labels[drop]
        members[keep] = members[keep] + members[drop]
        for rid in members[drop]:
            group[rid] = keep
        del masks[drop], labels[drop], members[drop]
    return {rid: keep for rid, keep in group.items() if rid != keep}


def merge_over_segmented_rooms(
    graph: SceneGraph,
    by_room: dict[str, list[ObjectNode]],
    params: MergeParams | None = None,
) -> dict[str, list[ObjectNode]]:
    """Join the rooms of ``graph`` that :func:`plan_merges` finds to be one room.

    ``by_room`` maps room ids to the objects located in them; an absorbed room's objects
    move to the kept room (``room_id`` set). The kept room's mask is the union of its
    group's masks and its position the union's centre; the absorbed rooms are removed and
    their CONNECTS edges (but the ones inside the group) re-attached to the kept room.
    Returns ``by_room`` with the absorbed rooms folded into the kept ones.
    """
    rooms = {r.id: r for r in graph.nodes(Layer.ROOM) if isinstance(r, RoomNode)}
    connects = list(graph.edges(EdgeKind.CONNECTS))
    into = plan_merges(rooms, by_room, connects, params)
    if not into:
        return by_room
    out: dict[str, list[ObjectNode]] = {}
    for rid, members in by_room.items():
        keep = into.get(rid, rid)
        for o in members:
            o.room_id = keep
        out.setdefault(keep, []).extend(members)
    for keep in sorted(set(into.values()), key=_room_order):
        group = [keep, *sorted((r for r, k in into.items() if k == keep), key=_room_order)]
        masks = [rooms[r].mask for r in group if rooms[r].mask is not None]
        mask = union_mask(masks)  # type: ignore[arg-type]
        room = rooms[keep]
        rows, cols = np.nonzero(mask.cells)
        room.mask = mask
        room.position = (
            mask.origin_x + (float(cols.mean()) + 0.5) * mask.resolution,
            mask.origin_y + (float(rows.mean()) + 0.5) * mask.resolution,
            room.position[2],
        )
        room.best_view = room.best_view or next(
            (rooms[r].best_view for r in group if rooms[r].best_view), None
        )
        graph.touch(keep)
    moved: list[Edge] = []
    for e in connects:
        src, dst = into.get(e.src, e.src), into.get(e.dst, e.dst)
        if (src, dst) == (e.src, e.dst):
            continue
        if src != dst:
            a, b = sorted((src, dst), key=_room_order)
            moved.append(Edge(e.kind, a, b, e.props))
    for rid in into:
        graph.remove(rid)
    for e in moved:
        if graph.edge(e.key) is None:
            graph.add_edge(e)
    return out
