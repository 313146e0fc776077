"""Open-plan rooms: split a geometric room that holds several functional rooms.

Walls and doors separate rooms for the geometric segmentation; a kitchen, a dining
space and a living space joined without them stay one room there. In the spirit of the
paper (room masks are refined, objects are clustered spatially into functional areas,
and rooms are built on top of them), a large room's objects are grouped by what they say
about the room type, and the room is split when at least two groups clearly disagree:

1. the room's informative objects (fixtures say nothing about a room's type) are
   clustered spatially (:func:`inherit_sg.mapping.areas.cluster_objects`, a tighter
   gap than for areas);
2. each cluster scores every room type with the evidence of ``rooms.toml``
   (:func:`inherit_sg.mapping.room_semantics.type_evidence`); clusters that agree (the
   same or a closely related best type, or types that the clusters do not clearly tell
   apart) are merged, nearest first, and merged groups are scored again;
3. groups with too little evidence seed nothing; when two or more groups are left, the
   room mask (holes under furniture filled) is divided between them by geodesic
   distance to their objects' footprints, every cell to one part and every part one
   connected piece (where the room's mask is one); a part smaller than its type's
   smallest plausible room (``area`` in ``rooms.toml``, kept between ``min_part_floor_m2``
   and ``min_part_m2``) drops its group.

In the scene graph (:func:`split_open_plan_rooms`) the parts replace their room: their
ids are derived from the room's id and a part index ordered by position
(:func:`part_room_id`), so a repeated update with the same content gives the same ids;
the room's doors move to the part holding them and CONNECTS edges join touching parts.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage

from inherit_sg.mapping.areas import cluster_objects
from inherit_sg.mapping.room_semantics import type_evidence
from inherit_sg.model import (
    Edge,
    EdgeKind,
    Layer,
    NodeId,
    ObjectNode,
    RoomMask,
    RoomNode,
    SceneGraph,
)
from inherit_sg.vocab import rooms as room_vocab

# Separator between a room's id and its part index ("room:2" -> "room:2.1").
PART_SEPARATOR = "."
# CONNECTS edges between parts of one room carry this source.
OPEN_SOURCE = "open plan"


@dataclass(frozen=True)
class SplitParams:
    """Thresholds of the open-plan split.

    ``min_room_m2``: smaller rooms are never split; ``cluster_gap``: single-linkage gap
    (m) between the footprints of informative objects; ``min_evidence``: the evidence a
    group needs for its best type to stand as a room; ``margin``: how much more each of
    two groups must say for its own type than for the other's to be told apart;
    ``related_agree``: types at least this similar (``related`` in ``rooms.toml``) agree;
    ``min_objects``: the fewest objects a group
    needs to stand as a room, unless its evidence reaches ``alone_evidence`` (a flight
    of stairs, an exterior door); ``min_part_m2``: the smallest part of a type that
    has no smaller plausible size (an entrance hall may be as small as
    ``min_part_floor_m2``); ``seed_reach``: how far (m) from the mask an
    object may stand and still seed its group.
    """

    min_room_m2: float = 25.0
    cluster_gap: float = 0.3
    min_evidence: float = 3.0
    keep_share: float = 0.5
    related_agree: float = 0.7
    min_objects: int = 2
    alone_evidence: float = 4.0
    min_part_m2: float = 5.0
    min_part_floor_m2: float = 3.0
    seed_reach: float = 1.0


DEFAULT_SPLIT = SplitParams()


@dataclass
class _Group:
    """Objects that say the same about the room type, with their evidence."""

    objects: list[ObjectNode]
    evidence: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.evidence = type_evidence([o.label for o in self.objects])

    @property
    def best(self) -> tuple[str, float]:
        """Best-supported type and its evidence (file order breaks ties)."""
        name = max(self.evidence, key=lambda t: self.evidence[t])
        return name, self.evidence[name]


@dataclass(frozen=True)
class RoomPart:
    """One functional room of a split room: its mask, objects and best type."""

    mask: RoomMask
    objects: tuple[ObjectNode, ...]
    room_type: str

    @property
    def centroid(self) -> tuple[float, float]:
        """World (x, y) centre of the part's mask."""
        r, c = np.nonzero(self.mask.cells)
        res = self.mask.resolution
        return (
            self.mask.origin_x + (float(c.mean()) + 0.5) * res,
            self.mask.origin_y + (float(r.mean()) + 0.5) * res,
        )


def smallest_part_m2(room_type: str, params: SplitParams) -> float:
    """The smallest part a group of ``room_type`` may have: the type's smallest
    plausible area, kept between ``min_part_floor_m2`` and ``min_part_m2``."""
    rtype = room_vocab.room_type_table().get(room_type)
    low = rtype.area[0] if rtype is not None and rtype.area is not None else params.min_part_m2
    return max(params.min_part_floor_m2, min(params.min_part_m2, low))


def part_room_id(room_id: NodeId, index: int) -> NodeId:
    """Id of part ``index`` (from 1) of room ``room_id``: ``room:2`` -> ``room:2.1``."""
    return f"{room_id}{PART_SEPARATOR}{index}"


def is_part_id(room_id: NodeId) -> bool:
    """Whether a room id names a part of a split room."""
    return PART_SEPARATOR in room_id.partition(":")[2]


def whole_room_id(room_id: NodeId) -> NodeId:
    """The geometric room a room id belongs to: the split room of a part, else itself."""
    return room_id.rpartition(PART_SEPARATOR)[0] if is_part_id(room_id) else room_id


def _footprint_gap(a: _Group, b: _Group) -> float:
    """Smallest horizontal gap (m) between the footprints of two groups' objects."""
    best = math.inf
    for p in a.objects:
        for q in b.objects:
            dx = max(0.0, p.bbox.min[0] - q.bbox.max[0], q.bbox.min[0] - p.bbox.max[0])
            dy = max(0.0, p.bbox.min[1] - q.bbox.max[1], q.bbox.min[1] - p.bbox.max[1])
            best = min(best, math.hypot(dx, dy))
    return best


def _agree(a: _Group, b: _Group, params: SplitParams) -> bool:
    """Whether two groups say the same about the room type: the same or closely related
    best types, or a type for both together that each group supports at least
    ``keep_share`` as much as its own best type."""
    ta, ea = a.best
    tb, eb = b.best
    if ea <= 0 or eb <= 0:  # a group that says nothing agrees with any
        return True
    if ta == tb or room_vocab.related(ta).get(tb, 0.0) >= params.related_agree:
        return True
    both, _ = _Group(a.objects + b.objects).best
    return min(a.evidence[both] / ea, b.evidence[both] / eb) >= params.keep_share


def _share_a_type(objects: Sequence[ObjectNode]) -> np.ndarray:
    """Which objects may link in a group: those that both support some room type (a
    sofa and a lamp, a stove and a sink), so that a sofa touching a kitchen run, or
    a stray detection between them, does not chain the two into one."""
    names = sorted({t for o in objects for t in type_evidence([o.label])})
    support = np.array(
        [[type_evidence([o.label]).get(t, 0.0) > 0 for t in names] for o in objects], dtype=bool
    ).reshape(len(objects), len(names))
    shared: np.ndarray = (support.astype(int) @ support.T.astype(int)) > 0
    return shared


def group_objects(objects: Sequence[ObjectNode], params: SplitParams) -> list[list[ObjectNode]]:
    """The groups of informative objects that stand as separate functional rooms (each
    with enough evidence, every two told apart); fewer than two when the room is one."""
    informative = [o for o in objects if any(v > 0 for v in type_evidence([o.label]).values())]
    groups = [
        _Group(c)
        for c in cluster_objects(
            informative, gap=params.cluster_gap, compatible=_share_a_type(informative)
        )
    ]
    # the gap between two groups when they agree, else None; by the groups' object ids
    known: dict[tuple[frozenset[str], frozenset[str]], float | None] = {}

    def agreeing_gap(a: _Group, b: _Group) -> float | None:
        key = (frozenset(o.id for o in a.objects), frozenset(o.id for o in b.objects))
        if key not in known:
            known[key] = _footprint_gap(a, b) if _agree(a, b, params) else None
        return known[key]

    while True:
        pairs = [
            (gap, i, j)
            for i in range(len(groups))
            for j in range(i + 1, len(groups))
            if (gap := agreeing_gap(groups[i], groups[j])) is not None
        ]
        if not pairs:
            break
        _, i, j = min(pairs)
        merged = _Group(groups[i].objects + groups[j].objects)
        groups = [g for k, g in enumerate(groups) if k not in (i, j)] + [merged]
    strong = [
        g
        for g in groups
        if g.best[1] >= params.min_evidence
        and (len(g.objects) >= params.min_objects or g.best[1] >= params.alone_evidence)
    ]
    strong.sort(key=lambda g: min(o.id for o in g.objects))
    return [g.objects for g in strong]


def _cell(mask: RoomMask, x: float, y: float) -> tuple[int, int]:
    return (
        math.floor((y - mask.origin_y) / mask.resolution),
        math.floor((x - mask.origin_x) / mask.resolution),
    )


def _seed_cells(
    mask: RoomMask, area: np.ndarray, objects: Sequence[ObjectNode], reach: float
) -> list[tuple[int, int]]:
    """Cells of ``area`` under the objects' footprints, or the nearest one within
    ``reach`` of an object whose footprint misses it."""
    h, w = area.shape
    out: list[tuple[int, int]] = []
    rows, cols = np.nonzero(area)
    for o in objects:
        r0, c0 = _cell(mask, o.bbox.min[0], o.bbox.min[1])
        r1, c1 = _cell(mask, o.bbox.max[0], o.bbox.max[1])
        r0, c0, r1, c1 = max(r0, 0), max(c0, 0), min(r1, h - 1), min(c1, w - 1)
        hit = (
            np.argwhere(area[r0 : r1 + 1, c0 : c1 + 1]) + np.array([r0, c0])
            if r0 <= r1 and c0 <= c1
            else np.empty((0, 2), dtype=int)
        )
        if len(hit):
            out.extend((int(r), int(c)) for r, c in hit)
            continue
        r, c = _cell(mask, o.position[0], o.position[1])
        d = np.hypot(rows - r, cols - c)
        k = int(np.argmin(d))
        if d[k] * mask.resolution <= reach:
            out.append((int(rows[k]), int(cols[k])))
    return out


_STEPS = [(dr, dc, math.hypot(dr, dc)) for dr in (-1, 0, 1) for dc in (-1, 0, 1) if dr or dc]


def _geodesic_labels(area: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """Give every cell of ``area`` the label (> 0) of the nearest labelled cell, by
    8-connected geodesic distance inside ``area``; unreachable cells keep 0."""
    out = labels.copy()
    dist = np.full(area.shape, np.inf)
    heap: list[tuple[float, int, int, int]] = []
    for r, c in np.argwhere(out > 0):
        dist[r, c] = 0.0
        heap.append((0.0, int(out[r, c]), int(r), int(c)))
    heapq.heapify(heap)
    h, w = area.shape
    while heap:
        d, lab, r, c = heapq.heappop(heap)
        if d > dist[r, c]:
            continue
        for dr, dc, step in _STEPS:
            rr, cc = r + dr, c + dc
            if 0 <= rr < h and 0 <= cc < w and area[rr, cc] and d + step < dist[rr, cc]:
                dist[rr, cc] = d + step
                out[rr, cc] = lab
                heapq.heappush(heap, (d + step, lab, rr, cc))
    return out


def _keep_connected(area: np.ndarray, labels: np.ndarray, n: int) -> np.ndarray:
    """One connected piece per label (the largest); other pieces go to their nearest
    neighbouring label."""
    kept = labels.copy()
    for lab in range(1, n + 1):
        pieces, count = ndimage.label(kept == lab)
        if count > 1:
            sizes = ndimage.sum(np.ones_like(pieces), pieces, index=range(1, count + 1))
            keep = 1 + int(np.argmax(sizes))
            kept[(pieces > 0) & (pieces != keep)] = 0
    return _geodesic_labels(area, kept)


def _partition(mask: RoomMask, groups: Sequence[Sequence[ObjectNode]], reach: float) -> np.ndarray:
    """Label grid (0 outside, 1..n the groups) over the hole-filled room mask."""
    area = ndimage.binary_fill_holes(mask.cells.astype(bool))
    seeds = np.zeros(area.shape, dtype=np.int32)
    for k, objects in enumerate(groups, start=1):
        for r, c in _seed_cells(mask, area, objects, reach):
            if seeds[r, c] == 0:
                seeds[r, c] = k
    labels = _keep_connected(area, _geodesic_labels(area, seeds), len(groups))
    stray = area & (labels == 0)  # pieces of the mask no seed reaches
    if stray.any() and (labels > 0).any():
        _, (rows, cols) = ndimage.distance_transform_edt(labels == 0, return_indices=True)
        labels[stray] = labels[rows[stray], cols[stray]]
    return labels


def _cropped(mask: RoomMask, cells: np.ndarray) -> RoomMask:
    """A mask of ``cells`` (on ``mask``'s grid) cut to their bounding box."""
    rows, cols = np.nonzero(cells)
    r0, r1, c0, c1 = rows.min(), rows.max() + 1, cols.min(), cols.max() + 1
    res = mask.resolution
    return RoomMask(
        mask.origin_x + c0 * res, mask.origin_y + r0 * res, res, cells[r0:r1, c0:c1].copy()
    )


def _part_of(mask: RoomMask, labels: np.ndarray, x: float, y: float) -> int:
    """Part label at world (x, y), else the nearest labelled cell's."""
    r, c = _cell(mask, x, y)
    h, w = labels.shape
    if 0 <= r < h and 0 <= c < w and labels[r, c] > 0:
        return int(labels[r, c])
    rows, cols = np.nonzero(labels)
    k = int(np.argmin(np.hypot(rows - r, cols - c)))
    return int(labels[rows[k], cols[k]])


@dataclass(frozen=True)
class RoomSplit:
    """A split room: its parts (ordered by position) and the label grid over its mask
    (0 outside, ``k`` for ``parts[k - 1]``)."""

    parts: tuple[RoomPart, ...]
    labels: np.ndarray

    def part_at(self, mask: RoomMask, x: float, y: float) -> int:
        """Index (from 0) of the part at or nearest to world (x, y)."""
        return _part_of(mask, self.labels, x, y) - 1

    def touching(self) -> list[tuple[int, int, tuple[float, float], float]]:
        """Pairs of parts (indices from 0) whose cells touch, with the mean (row, col)
        of the cells on their shared border and its length in cells."""
        out = []
        lab = self.labels
        for a in range(1, len(self.parts) + 1):
            for b in range(a + 1, len(self.parts) + 1):
                border = np.zeros(lab.shape, dtype=bool)
                border[:, :-1] |= (lab[:, :-1] == a) & (lab[:, 1:] == b)
                border[:, :-1] |= (lab[:, :-1] == b) & (lab[:, 1:] == a)
                border[:-1, :] |= (lab[:-1, :] == a) & (lab[1:, :] == b)
                border[:-1, :] |= (lab[:-1, :] == b) & (lab[1:, :] == a)
                cells = np.argwhere(border)
                if len(cells):
                    r, c = cells.mean(axis=0)
                    out.append((a - 1, b - 1, (float(r), float(c)), float(len(cells))))
        return out


def split_room(
    mask: RoomMask | None, objects: Sequence[ObjectNode], params: SplitParams | None = None
) -> RoomSplit | None:
    """The functional rooms of one room, or None when it stays whole (too small, one
    coherent group, or parts too small)."""
    params = params or SplitParams()
    if mask is None or mask.area_m2 < params.min_room_m2:
        return None
    groups = group_objects(objects, params)
    while len(groups) >= 2:
        labels = _partition(mask, groups, params.seed_reach)
        sizes = [
            float(((labels == k) & mask.cells).sum()) * mask.resolution**2
            for k in range(1, len(groups) + 1)
        ]
        small = [
            k
            for k, s in enumerate(sizes)
            if s < smallest_part_m2(_Group(list(groups[k])).best[0], params)
        ]
        if not small:
            break
        weakest = min(small, key=lambda k: _Group(list(groups[k])).best[1])
        groups = [g for k, g in enumerate(groups) if k != weakest]
    if len(groups) < 2:
        return None
    cells = mask.cells.astype(bool)
    members: dict[int, list[ObjectNode]] = {k: [] for k in range(1, len(groups) + 1)}
    for o in objects:
        members[_part_of(mask, labels, o.position[0], o.position[1])].append(o)
    parts = []
    for k in range(1, len(groups) + 1):
        part_mask = _cropped(mask, (labels == k) & cells)
        best = _Group(list(groups[k - 1])).best[0]
        parts.append((k, RoomPart(part_mask, tuple(members[k]), best)))
    # parts ordered by position (x, then y of the mask centre): stable ids on repeat
    parts.sort(key=lambda kp: kp[1].centroid)
    order = np.zeros(len(groups) + 1, dtype=labels.dtype)
    for new, (old, _) in enumerate(parts, start=1):
        order[old] = new
    return RoomSplit(tuple(p for _, p in parts), order[labels])


def _door_point(edge: Edge) -> tuple[float, float] | None:
    door = edge.prop("door")
    if door is None or len(door) < 2:
        return None
    return float(door[0]), float(door[1])


def split_open_plan_rooms(
    graph: SceneGraph,
    by_room: dict[str, list[ObjectNode]],
    params: SplitParams | None = None,
) -> dict[str, list[ObjectNode]]:
    """Replace every room of ``graph`` that :func:`split_room` splits by its parts, and
    remove parts of earlier updates that no longer exist.

    ``by_room`` maps room ids to the objects located in them; the objects of a split
    room move to the part they stand in (``room_id`` set). Each part takes the room's
    floor, best view and HAS_ROOM edge; the room's CONNECTS edges move to the part
    nearest their door, and touching parts are joined by CONNECTS edges at the middle
    of their shared border. Returns ``by_room`` with the parts in place of their rooms.
    """
    params = params or SplitParams()
    located: dict[str, list[ObjectNode]] = {}
    for room_id, members in by_room.items():
        if is_part_id(room_id):  # found by nearness to a part of an earlier update
            room_id = whole_room_id(room_id)
            if room_id not in graph:
                for o in members:
                    o.room_id = o.area_id = None
                continue
        located.setdefault(room_id, []).extend(members)
    out: dict[str, list[ObjectNode]] = {}
    wanted: set[str] = set()
    for room_id in sorted(located):
        members = located[room_id]
        room = graph.get(room_id) if room_id in graph else None
        split = split_room(room.mask, members, params) if isinstance(room, RoomNode) else None
        if split is None or not isinstance(room, RoomNode) or room.mask is None:
            for o in members:
                o.room_id = room_id
            out[room_id] = members
            continue
        ids = [part_room_id(room_id, k) for k in range(1, len(split.parts) + 1)]
        wanted.update(ids)
        z = room.position[2]
        for pid, part in zip(ids, split.parts, strict=True):
            x, y = part.centroid
            prev = graph.get(pid) if pid in graph else None
            if isinstance(prev, RoomNode):
                prev.mask, prev.position, prev.floor_id = part.mask, (x, y, z), room.floor_id
                prev.best_view = room.best_view or prev.best_view
                graph.touch(pid)
            else:
                graph.add_or_update(
                    RoomNode(
                        id=pid,
                        label=room.label,
                        floor_id=room.floor_id,
                        position=(x, y, z),
                        mask=part.mask,
                        best_view=room.best_view,
                    )
                )
            for o in part.objects:
                o.room_id = pid
            out[pid] = list(part.objects)
        edges: list[Edge] = []
        for e in graph.in_edges(room_id, EdgeKind.HAS_ROOM):
            edges.extend(Edge(e.kind, e.src, pid, e.props) for pid in ids)
        for e in graph.out_edges(room_id, EdgeKind.CONNECTS) + graph.in_edges(
            room_id, EdgeKind.CONNECTS
        ):
            door = _door_point(e)
            k = split.part_at(room.mask, *door) if door else 0
            src = ids[k] if e.src == room_id else e.src
            dst = ids[k] if e.dst == room_id else e.dst
            edges.append(Edge(e.kind, src, dst, e.props))
        res = room.mask.resolution
        for a, b, (r, c), length in split.touching():
            door_xy = [room.mask.origin_x + (c + 0.5) * res, room.mask.origin_y + (r + 0.5) * res]
            edges.append(
                Edge.make(
                    EdgeKind.CONNECTS,
                    ids[a],
                    ids[b],
                    door=[*door_xy, z],
                    width=round(length * res, 2),
                    source=OPEN_SOURCE,
                )
            )
        graph.remove(room_id)
        for e in edges:
            if graph.edge(e.key) != e:
                graph.add_edge(e)
    for node in list(graph.nodes(Layer.ROOM)):
        if is_part_id(node.id) and node.id not in wanted:
            graph.remove(node.id)
    return out
