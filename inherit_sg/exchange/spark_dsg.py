"""Import a Spark-DSG / Hydra scene graph saved as JSON.

Spark-DSG writes ``{"nodes": [...], "edges": [...], "layer_ids": [...]}`` where each node
has an integer ``id``, a ``layer`` and ``attributes`` whose ``type`` names the node
kind. We map:

* ``ObjectNodeAttributes`` (layer 2) → ``Object`` with position and box;
* ``RoomNodeAttributes`` (layer 4) → ``Room``;
* ``SemanticNodeAttributes`` on the building layer (5) → ``Floor`` (level 0);
* places (layer 3) and agent poses are not part of our hierarchy: they are used only to
  find which room an object belongs to (object ← place ← room edges) and then dropped.

Our hierarchy puts an ``Area`` between rooms and objects; Spark-DSG has none, so each
imported room gets one area labelled ``"room area"`` holding its objects. Objects whose
room cannot be found go to an ``"unassigned"`` room of the floor.

Labels: Spark-DSG stores integer semantic labels. A label space (``{"5": "chair"}``,
from the file's metadata when present or from ``label_space``) names them; otherwise the
label is ``"class <n>"``. Spark-DSG 1.1 keeps label spaces per layer in the metadata
(``labelspaces``: ``{"_l2p0": [[5, "chair"], ...]}``); the objects layer's is used.

Files written by :mod:`inherit_sg.exchange.spark_dsg_export` carry INHerit-SG metadata on
their nodes and edges (key ``inherit_sg``): then node ids, storeys (one building-layer
node per floor), areas, summaries and the relation / door / stairs edges come back too,
and an object the map had outside every room stays outside (no unassigned room).
Without it, room–room edges (Hydra's room adjacency) become ``CONNECTS``.
"""

from __future__ import annotations

import json
from collections import defaultdict, deque
from pathlib import Path
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from inherit_sg.errors import DatasetError
from inherit_sg.model import (
    AreaNode,
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    ObjectStatus,
    RoomNode,
    SceneGraph,
    layer_of,
    make_id,
)

_OBJECT = "ObjectNodeAttributes"
_ROOM = "RoomNodeAttributes"
_PLACE = "PlaceNodeAttributes"
_BUILDING_LAYER = 5
_OBJECT_LABELSPACES = ("_l2p0", "OBJECTS")
#: Metadata key holding INHerit-SG's own fields on nodes, edges and the graph.
META_KEY = "inherit_sg"


def _label_space_from_metadata(data: dict[str, Any]) -> dict[int, str]:
    meta = data.get("metadata") or {}
    per_layer = meta.get("labelspaces")
    if isinstance(per_layer, dict):
        for key in _OBJECT_LABELSPACES:
            if isinstance(per_layer.get(key), list):
                return {int(k): str(v) for k, v in per_layer[key]}
    names = meta.get("labelspace") or meta.get("label_names") or {}
    if isinstance(names, dict):
        return {int(k): str(v) for k, v in names.items()}
    if isinstance(names, list):
        return {int(e["label"]): str(e["name"]) for e in names if "label" in e and "name" in e}
    return {}


def load_label_space(path: str | Path) -> dict[int, str]:
    """Read ``{"<int>": "name"}`` JSON or ``id,name`` CSV lines."""
    p = Path(path)
    text = p.read_text(encoding="utf-8")
    try:
        if p.suffix == ".json":
            return {int(k): str(v) for k, v in json.loads(text).items()}
        out: dict[int, str] = {}
        for line in text.splitlines():
            if line.strip() and not line.startswith("#"):
                key, _, name = line.partition(",")
                out[int(key)] = name.strip()
        return out
    except (ValueError, AttributeError, json.JSONDecodeError) as exc:
        raise DatasetError(f"{p}: malformed label space: {exc}") from None


def _bbox(attrs: dict[str, Any], position: list[float]) -> BBox3D:
    """The node's box (axis-aligned around a rotated one); its position when it has none.
    Spark-DSG < 1.1 writes ``min``/``max``, 1.1 ``dimensions`` and ``world_P_center``."""
    box = attrs.get("bounding_box") or {}
    if box.get("type", "INVALID") == "INVALID":
        return BBox3D(tuple(position), tuple(position))
    if "min" in box and "max" in box:
        return BBox3D(tuple(box["min"]), tuple(box["max"]))
    if "dimensions" in box and "world_P_center" in box:
        half = np.asarray(box["dimensions"], dtype=np.float64) / 2.0
        rot = box.get("world_R_center") or {}
        quat = [float(rot.get(k, 0.0)) for k in "xyzw"] if rot else [0.0, 0.0, 0.0, 1.0]
        extent = np.abs(Rotation.from_quat(quat).as_matrix()) @ half
        centre = np.asarray(box["world_P_center"], dtype=np.float64)
        return BBox3D(tuple(centre - extent), tuple(centre + extent))
    return BBox3D(tuple(position), tuple(position))


def _ours(raw: dict[str, Any]) -> dict[str, Any]:
    """INHerit-SG's metadata on a node or edge record (empty for other writers)."""
    meta = raw.get("metadata") or {}
    value = meta.get(META_KEY) if isinstance(meta, dict) else None
    return value if isinstance(value, dict) else {}


def _node_id(layer: Layer, wanted: Any, graph: SceneGraph, counter: int) -> str:
    """The id INHerit-SG metadata asks for when valid and free, else a numbered one."""
    if isinstance(wanted, str) and wanted not in graph:
        try:
            if layer_of(wanted) == layer:
                return wanted
        except ValueError:
            pass
    key = counter
    while make_id(layer, key) in graph:
        key += 1
    return make_id(layer, key)


def _read(p: Path) -> dict[str, Any]:
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DatasetError(f"Spark-DSG file not found: {p}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise DatasetError(f"{p}: invalid JSON: {exc}") from None
    if not isinstance(data, dict) or not isinstance(data.get("nodes"), list):
        raise DatasetError(f"{p}: not a Spark-DSG JSON file (no 'nodes' list)")
    return data


class _Builder:
    """Turns the parsed node and edge records into a :class:`SceneGraph`."""

    def __init__(self, p: Path, data: dict[str, Any], names: dict[int, str]) -> None:
        self.p = p
        self.names = names
        self.nodes: dict[int, dict[str, Any]] = {}
        for raw in data["nodes"]:
            try:
                self.nodes[int(raw["id"])] = raw
            except (KeyError, TypeError, ValueError):
                raise DatasetError(f"{p}: node without an integer id: {str(raw)[:80]}") from None
        self.edges: list[tuple[int, int, dict[str, Any]]] = []
        self.adjacency: dict[int, set[int]] = defaultdict(set)
        for edge in data.get("edges", []):
            s, t = int(edge["source"]), int(edge["target"])
            if s in self.nodes and t in self.nodes:
                self.adjacency[s].add(t)
                self.adjacency[t].add(s)
                self.edges.append((s, t, edge.get("info") or {}))
        self.graph = SceneGraph()
        self.ids: dict[int, str] = {}  # Spark-DSG node id -> our id
        self.areas: dict[str, str] = {}  # room id -> its default area

    def kind(self, nid: int) -> str:
        return str(self.nodes[nid].get("attributes", {}).get("type", ""))

    def floors(self) -> str:
        """One floor per building-layer node (a "floor 0" when there is none); returns
        the first floor's id."""
        building = sorted(
            (nid for nid, n in self.nodes.items() if n.get("layer") == _BUILDING_LAYER),
            key=lambda nid: (int(_ours(self.nodes[nid]["attributes"]).get("level", 0)), nid),
        )
        for index, nid in enumerate(building):
            attrs = self.nodes[nid]["attributes"]
            ours = _ours(attrs)
            floor = FloorNode(
                id=_node_id(Layer.FLOOR, ours.get("id"), self.graph, index),
                level=int(ours.get("level", index)),
                label=str(attrs.get("name") or "building"),
                z_min=float(ours.get("z_min", 0.0)),
                z_max=float(ours.get("z_max", 0.0)),
            )
            self.graph.add_or_update(floor)
            self.ids[nid] = floor.id
        if not building:
            self.graph.add_or_update(
                FloorNode(id=make_id(Layer.FLOOR, 0), level=0, label="floor 0")
            )
            return make_id(Layer.FLOOR, 0)
        return self.ids[building[0]]

    def rooms(self, first_floor: str) -> None:
        for nid, raw in self.nodes.items():
            if self.kind(nid) != _ROOM:
                continue
            attrs = raw["attributes"]
            ours = _ours(attrs)
            count = sum(1 for _ in self.graph.nodes(Layer.ROOM))
            floor_id = next(
                (
                    self.ids[n]
                    for n in sorted(self.adjacency[nid])
                    if self.nodes[n].get("layer") == _BUILDING_LAYER and n in self.ids
                ),
                first_floor,
            )
            room = RoomNode(
                id=_node_id(Layer.ROOM, ours.get("id"), self.graph, count),
                label=str(attrs.get("name") or f"room {count}"),
                floor_id=floor_id,
                position=tuple(float(v) for v in attrs.get("position", (0, 0, 0))),  # type: ignore[arg-type]
                summary=str(ours.get("summary", "")),
                types=tuple((str(t), float(pr)) for t, pr in ours.get("types", [])),
            )
            self.graph.add_or_update(room)
            self.graph.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor_id, room.id))
            self.ids[nid] = room.id
            for index, area in enumerate(ours.get("areas", [])):
                node = AreaNode(
                    id=_node_id(Layer.AREA, area.get("id"), self.graph, index),
                    label=str(area.get("label", "area")),
                    room_id=room.id,
                    position=tuple(float(v) for v in area.get("position", room.position)),  # type: ignore[arg-type]
                    summary=str(area.get("summary", "")),
                )
                self.graph.add_or_update(node)
                self.graph.add_edge(Edge.make(EdgeKind.HAS_AREA, room.id, node.id))

    def room_of(self, object_nid: int) -> str | None:
        """Nearest room over the place graph (object → place → … → room)."""
        seen = {object_nid}
        queue = deque([object_nid])
        while queue:
            cur = queue.popleft()
            for nxt in sorted(self.adjacency[cur]):
                if self.kind(nxt) == _ROOM:
                    return self.ids[nxt]
                if nxt not in seen and self.kind(nxt) == _PLACE:
                    seen.add(nxt)
                    queue.append(nxt)
        return None

    def area_for(self, room_id: str, wanted: Any) -> str:
        """The area INHerit-SG metadata names when it lies in ``room_id``, else the
        room's one ``"room area"``."""
        if isinstance(wanted, str) and wanted in self.graph.children(room_id):
            return wanted
        if room_id not in self.areas:
            count = sum(1 for _ in self.graph.nodes(Layer.AREA))
            area = AreaNode(
                id=_node_id(Layer.AREA, None, self.graph, count), label="room area", room_id=room_id
            )
            self.graph.add_or_update(area)
            self.graph.add_edge(Edge.make(EdgeKind.HAS_AREA, room_id, area.id))
            self.areas[room_id] = area.id
        return self.areas[room_id]

    def unassigned_room(self, floor_id: str) -> str:
        room_id = make_id(Layer.ROOM, "unassigned")
        if room_id not in self.graph:
            self.graph.add_or_update(RoomNode(id=room_id, label="unassigned", floor_id=floor_id))
            self.graph.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor_id, room_id))
        return room_id

    def objects(self, first_floor: str) -> None:
        count = 0
        for nid, raw in self.nodes.items():
            if self.kind(nid) != _OBJECT:
                continue
            attrs = raw["attributes"]
            ours = _ours(attrs)
            position = [float(v) for v in attrs.get("position", (0, 0, 0))]
            if len(position) != 3 or not np.all(np.isfinite(position)):
                raise DatasetError(f"{self.p}: object node {nid} has an invalid position")
            sem = int(attrs.get("semantic_label", -1))
            room_id = self.room_of(nid)
            floor_id = first_floor
            if room_id is None and ours and ours.get("area_id") is None:
                # our export of an object outside every room: it stays outside
                area_id = None
                if ours.get("floor_id") in self.graph:
                    floor_id = ours["floor_id"]
            else:
                room_id = room_id or self.unassigned_room(first_floor)
                area_id = self.area_for(room_id, ours.get("area_id"))
                room = self.graph.get(room_id)
                floor_id = (
                    room.floor_id if isinstance(room, RoomNode) and room.floor_id else floor_id
                )
            extra = ours.get("attributes")
            obj = ObjectNode(
                id=_node_id(Layer.OBJECT, ours.get("id"), self.graph, count),
                label=self.names.get(sem, f"class {sem}"),
                position=tuple(position),  # type: ignore[arg-type]
                bbox=_bbox(attrs, position),
                description=str(ours.get("description", "")),
                observation_count=int(ours.get("observation_count", 1)),
                attributes={
                    **(extra if isinstance(extra, dict) else {}),
                    "source": "spark-dsg",
                    "source_id": nid,
                    "source_name": attrs.get("name", ""),
                    "semantic_label": sem,
                    "color": attrs.get("color"),
                },
                area_id=area_id,
                room_id=room_id,
                floor_id=floor_id,
            )
            if ours.get("status") in {s.value for s in ObjectStatus}:
                obj.status = ObjectStatus(ours["status"])
            self.graph.add_or_update(obj)
            if area_id is not None:
                self.graph.add_edge(Edge.make(EdgeKind.HAS_OBJECT, area_id, obj.id))
            self.ids[nid] = obj.id
            count += 1

    def same_layer_edges(self) -> None:
        """Relations, doors and stairs from INHerit-SG edge metadata; Hydra's room–room
        edges (no such metadata) as ``CONNECTS``."""
        for s, t, info in self.edges:
            if s not in self.ids or t not in self.ids:
                continue
            entries = (info.get("metadata") or {}).get(META_KEY)
            if not isinstance(entries, list):
                if self.kind(s) == _ROOM and self.kind(t) == _ROOM:
                    self.graph.add_edge(Edge.make(EdgeKind.CONNECTS, self.ids[s], self.ids[t]))
                continue
            for entry in entries:
                try:
                    kind = EdgeKind(entry.get("kind"))
                    subject = int(entry.get("subject", s))
                except (ValueError, TypeError):
                    continue
                src, dst = (s, t) if subject == s else (t, s)
                props = {k: v for k, v in entry.items() if k not in ("kind", "subject")}
                edge = Edge.make(kind, self.ids[src], self.ids[dst], **props)
                src_table, dst_table = kind.endpoints
                if (
                    self.graph.get(edge.src).layer.table == src_table
                    and self.graph.get(edge.dst).layer.table == dst_table
                ):
                    self.graph.add_edge(edge)

    def finish(self) -> None:
        """Positions of areas (and rooms) that came without one: their objects' mean."""
        for area in list(self.graph.nodes(Layer.AREA)):
            members = [self.graph.get(o) for o in self.graph.children(area.id)]
            if not members or not isinstance(area, AreaNode):
                continue
            if area.id in self.areas.values():
                pts = np.array([m.position for m in members])  # type: ignore[union-attr]
                area.position = tuple(float(v) for v in pts.mean(axis=0))  # type: ignore[assignment]
            room_node = self.graph.get(area.room_id or "")
            if isinstance(room_node, RoomNode) and room_node.position == (0.0, 0.0, 0.0):
                room_node.position = area.position


def spark_dsg_to_graph(path: str | Path, label_space: dict[int, str] | None = None) -> SceneGraph:
    """Parse a Spark-DSG JSON file into a :class:`SceneGraph` (change log: all new)."""
    p = Path(path)
    data = _read(p)
    builder = _Builder(p, data, {**_label_space_from_metadata(data), **(label_space or {})})
    first_floor = builder.floors()
    builder.rooms(first_floor)
    builder.objects(first_floor)
    builder.same_layer_edges()
    builder.finish()
    return builder.graph
