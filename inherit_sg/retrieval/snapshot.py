"""An in-memory view of one map for answering requests, loaded once per map version.

Requests read the hierarchy (object → area → room → floor), labels, boxes and RELATION
edges many times each; fetching them from Kuzu per request would dominate latency. A
:class:`MapSnapshot` holds them in plain dicts and numpy arrays and is rebuilt only when
the map's files change (:func:`map_version`): the engine checks the version, a few
``stat`` calls, before every request.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from inherit_sg.model import (
    AreaNode,
    EdgeKind,
    FloorNode,
    ObjectNode,
    ObjectStatus,
    RoomNode,
    SceneGraph,
)
from inherit_sg.model.doorways import doorway_rooms, doorways_of
from inherit_sg.retrieval.labels import map_label_kinds
from inherit_sg.retrieval.sizes import kind_sizes
from inherit_sg.store import MapStore
from inherit_sg.vocab.rooms import room_type

Version = tuple[int, ...]
T = TypeVar("T")
_VERSION_FILES = ("graph.kuzu", "graph.kuzu.wal", "map.json")


def map_version(path: Path) -> Version:
    """A cheap fingerprint of a map directory's files: size and modification time of
    the graph file, its write-ahead log and ``map.json``. Every committed write changes
    at least one of them."""
    out: list[int] = []
    for name in _VERSION_FILES:
        try:
            st = (path / name).stat()
        except FileNotFoundError:
            out += [-1, -1]
        else:
            out += [st.st_size, st.st_mtime_ns]
    return tuple(out)


def canonical_labels(label: str) -> tuple[str, ...]:
    """Canonical vocabulary labels of a map label ("couch" → ``("sofa",)``)."""
    return map_label_kinds(label)


def _alternatives(room: RoomNode) -> tuple[tuple[str, float], ...]:
    """A room's inferred types named by their canonical type (a map written by another
    labeller may use aliases), the first of each type kept, best first."""
    out: dict[str, float] = {}
    for name, p in room.types:
        rtype = room_type(name) or name.strip().lower()
        out.setdefault(rtype, float(p))
    return tuple(sorted(out.items(), key=lambda kv: -kv[1]))


@dataclass
class MapSnapshot:
    """Nodes, hierarchy, relations and geometry of one map version."""

    version: Version
    graph: SceneGraph
    use_areas: bool = True
    objects: dict[str, ObjectNode] = field(default_factory=dict)
    rooms: dict[str, RoomNode] = field(default_factory=dict)
    areas: dict[str, AreaNode] = field(default_factory=dict)
    floors: dict[str, FloorNode] = field(default_factory=dict)
    room_of: dict[str, str | None] = field(default_factory=dict)
    area_of: dict[str, str | None] = field(default_factory=dict)
    floor_of: dict[str, str | None] = field(default_factory=dict)
    canon: dict[str, tuple[str, ...]] = field(default_factory=dict)
    # room id → the type its label names (None: the label names no type)
    room_types: dict[str, str | None] = field(default_factory=dict)
    # room id → its inferred types with probabilities, best first, each named by its
    # canonical type (empty when the map holds none: oracle and imported maps)
    room_alternatives: dict[str, tuple[tuple[str, float], ...]] = field(default_factory=dict)
    relations: dict[str, dict[str, set[str]]] = field(default_factory=dict)
    neighbours: dict[str, set[str]] = field(default_factory=dict)
    # object id → the other rooms of the doorway it stands in (a door mapped in the
    # hall is the kitchen's door too); objects in no doorway are absent
    doorway_rooms: dict[str, tuple[str, ...]] = field(default_factory=dict)
    adjacent: dict[str, set[str]] = field(default_factory=dict)
    seen_in: dict[tuple[str, str], dict[str, Any]] = field(default_factory=dict)
    # objects as arrays, row i = obj_ids[i]: box corners, centroid, floor level (-1: unknown)
    obj_ids: list[str] = field(default_factory=list)
    obj_index: dict[str, int] = field(default_factory=dict)
    lo: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    hi: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    centre: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    level: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    # median linear size per object label: the reference of size words ("a large mug")
    kind_sizes: dict[str, float] = field(default_factory=dict)
    # object ids per stored label, in snapshot (= graph store scan) order
    by_label: dict[str, list[str]] = field(default_factory=dict)
    # values derived from this version on first use (see :meth:`memo`)
    _memo: dict[Any, Any] = field(default_factory=dict, repr=False)

    # ------------------------------------------------------------------ lookups
    @property
    def levels(self) -> list[int]:
        """Floor levels present, lowest first."""
        return sorted({f.level for f in self.floors.values()})

    def level_of(self, node_id: str) -> int | None:
        """Floor level of any node (None when unknown)."""
        fid = self.floor_of.get(node_id)
        floor = self.floors.get(fid) if fid else None
        return floor.level if floor is not None else None

    def floor_height(self, node_id: str) -> float:
        """Height of the floor of the storey ``node_id`` is on (0 when unknown)."""
        fid = self.floor_of.get(node_id)
        floor = self.floors.get(fid) if fid else None
        return floor.z_min if floor is not None else 0.0

    def place_key(self, node_id: str, kind: str) -> str:
        """The room (``kind`` = ``room``) or area (``area``) a node is in, as a key of
        the room / area terms: its own id, then for a room the other rooms of the
        doorway it stands in, joined by ``|`` (``""``: in none)."""
        if kind != "room":
            return self.area_of.get(node_id) or ""
        own = self.room_of.get(node_id) or ""
        also = self.doorway_rooms.get(node_id)
        return "|".join((own, *also)) if also and own else own

    def node(self, node_id: str) -> ObjectNode | RoomNode | AreaNode | FloorNode | None:
        """The node with ``node_id`` among the four layers (None when absent)."""
        return (
            self.objects.get(node_id)
            or self.rooms.get(node_id)
            or self.areas.get(node_id)
            or self.floors.get(node_id)
        )

    def position(self, node_id: str) -> tuple[float, float, float] | None:
        """Centroid of an object, area or room; a floor's is its rooms' mean."""
        node = self.node(node_id)
        if node is None:
            return None
        if isinstance(node, FloorNode):
            pts = [r.position for r in self.rooms.values() if r.floor_id == node_id]
            if not pts:
                return (0.0, 0.0, node.z_min)
            mean = np.mean(np.asarray(pts, dtype=float), axis=0)
            return (float(mean[0]), float(mean[1]), float(mean[2]))
        return tuple(float(v) for v in node.position)  # type: ignore[return-value]

    def related(self, a: str, b: str) -> set[str]:
        """Stored RELATION predicates from ``a`` to ``b``."""
        return self.relations.get(a, {}).get(b, set())

    def has_edge_between(self, a: str, b: str) -> bool:
        """Whether any RELATION edge joins ``a`` and ``b`` (either direction)."""
        return bool(self.related(a, b) or self.related(b, a))

    def objects_labelled(self, labels: set[str]) -> list[str]:
        """Ids of objects whose canonical labels meet ``labels``."""
        return [i for i, c in self.canon.items() if labels.intersection(c)]

    def raw_labels(self) -> frozenset[str]:
        """Distinct object labels as stored (indexed once per snapshot)."""
        return frozenset(self.by_label)

    def objects_with_labels(self, labels: list[str]) -> list[str]:
        """Ids of the objects whose stored label is one of ``labels``, in snapshot
        order: what ``MATCH (o:Object) WHERE o.label IN $labels`` (live objects)
        returns, without scanning the table."""
        found = [oid for label in set(labels) for oid in self.by_label.get(label, ())]
        found.sort(key=self.obj_index.__getitem__)
        return found

    def memo(self, key: Any, make: Callable[[], T]) -> T:
        """A value derived from this snapshot only, made on first use and kept while
        the snapshot lives (per-room type similarities, cleaned labels, ...). ``key``
        must say everything ``make`` depends on besides the snapshot."""
        try:
            return self._memo[key]
        except KeyError:
            return self._memo.setdefault(key, make())


def _relations(graph: SceneGraph) -> dict[str, dict[str, set[str]]]:
    out: dict[str, dict[str, set[str]]] = defaultdict(lambda: defaultdict(set))
    for edge in graph.edges(EdgeKind.RELATION):
        predicate = str(edge.prop("predicate", "")).replace("_", " ").strip()
        out[edge.src][edge.dst].add(predicate)
        if predicate in ("next to", "near"):  # symmetric by meaning
            out[edge.dst][edge.src].add(predicate)
    return {k: dict(v) for k, v in out.items()}


def _seen_in(graph: SceneGraph) -> dict[tuple[str, str], dict[str, Any]]:
    """Detection records (pixel ``bbox``, ``label``, ``score``) per (object, keyframe)."""
    return {(e.src, e.dst): e.prop_dict for e in graph.edges(EdgeKind.SEEN_IN)}


def _index_objects(snap: MapSnapshot) -> None:
    objs = list(snap.objects.values())
    snap.obj_ids = [o.id for o in objs]
    snap.obj_index = {oid: i for i, oid in enumerate(snap.obj_ids)}
    snap.lo = np.array([o.bbox.min for o in objs], dtype=float).reshape(-1, 3)
    snap.hi = np.array([o.bbox.max for o in objs], dtype=float).reshape(-1, 3)
    snap.centre = np.array([o.position for o in objs], dtype=float).reshape(-1, 3)
    levels = [snap.level_of(o.id) for o in objs]
    snap.level = np.array([-1 if lv is None else lv for lv in levels], dtype=int)
    snap.kind_sizes = kind_sizes(objs)
    by_label: dict[str, list[str]] = {}
    for o in objs:
        by_label.setdefault(o.label, []).append(o.id)
    snap.by_label = by_label


def _doorway_rooms(snap: MapSnapshot, graph: SceneGraph) -> dict[str, tuple[str, ...]]:
    """Object id → the other rooms of the doorways it stands in (see
    :mod:`inherit_sg.model.doorways`)."""
    doorways = doorways_of(graph, snap.floor_of.get)
    if not doorways:
        return {}
    floors = [snap.floor_of.get(oid) for oid in snap.obj_ids]
    rooms = [snap.room_of.get(oid) for oid in snap.obj_ids]
    found = doorway_rooms(snap.lo, snap.hi, floors, rooms, doorways)
    return {snap.obj_ids[row]: others for row, others in found.items()}


def build_snapshot(
    graph: SceneGraph, version: Version = (), *, use_areas: bool = True
) -> MapSnapshot:
    """Index ``graph`` for retrieval (removed objects are left out). With ``use_areas``
    off, functional-area nodes are left out too (the "w/o functional areas" ablation):
    objects hang directly under their rooms, and no area can be a candidate, a
    constraint match or a relation landmark."""
    snap = MapSnapshot(version=version, graph=graph, use_areas=use_areas)
    area_room: dict[str, str | None] = {}
    for node in graph.nodes():
        if isinstance(node, ObjectNode):
            if node.status != ObjectStatus.REMOVED:
                snap.objects[node.id] = node
        elif isinstance(node, RoomNode):
            snap.rooms[node.id] = node
        elif isinstance(node, AreaNode):
            area_room[node.id] = node.room_id or graph.parent(node.id)
            if use_areas:
                snap.areas[node.id] = node
        elif isinstance(node, FloorNode):
            snap.floors[node.id] = node
    for rid, room in snap.rooms.items():
        snap.floor_of[rid] = room.floor_id or graph.parent(rid)
        snap.room_types[rid] = room_type(room.label.lower()) if room.label else None
        snap.room_alternatives[rid] = _alternatives(room)
        snap.room_of[rid] = rid
    for aid in snap.areas:
        parent_room = area_room.get(aid)
        snap.room_of[aid] = parent_room
        snap.area_of[aid] = aid
        snap.floor_of[aid] = snap.floor_of.get(parent_room) if parent_room else None
    for fid in snap.floors:
        snap.floor_of[fid] = fid
    for oid, obj in snap.objects.items():
        parent = obj.area_id or graph.parent(oid)
        area_id = parent if parent in snap.areas else None
        room_id = (
            obj.room_id or area_room.get(parent or "") or (parent if parent in snap.rooms else None)
        )
        snap.area_of[oid] = area_id
        snap.room_of[oid] = room_id
        snap.floor_of[oid] = obj.floor_id or (snap.floor_of.get(room_id) if room_id else None)
        snap.canon[oid] = canonical_labels(obj.label)
    _index_objects(snap)
    snap.relations = _relations(graph)
    adjacent: dict[str, set[str]] = defaultdict(set)
    for src, dsts in snap.relations.items():
        for dst in dsts:
            adjacent[src].add(dst)
            adjacent[dst].add(src)
    snap.adjacent = dict(adjacent)
    neighbours: dict[str, set[str]] = defaultdict(set)
    for edge in graph.edges(EdgeKind.CONNECTS):
        neighbours[edge.src].add(edge.dst)
        neighbours[edge.dst].add(edge.src)
    snap.neighbours = dict(neighbours)
    snap.doorway_rooms = _doorway_rooms(snap, graph)
    snap.seen_in = _seen_in(graph)
    return snap


def load_snapshot(store: MapStore, *, use_areas: bool = True) -> MapSnapshot:
    """Read the whole map once and index it (the version is taken before reading, so a
    write racing with the read only causes one extra reload later)."""
    version = map_version(store.path)
    return build_snapshot(store.load_graph(), version, use_areas=use_areas)
