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
label is ``"class <n>"``.
"""

from __future__ import annotations

import json
from collections import defaultdict, deque
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.errors import DatasetError
from inherit_sg.model import (
    AreaNode,
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    RoomNode,
    SceneGraph,
    make_id,
)

_OBJECT = "ObjectNodeAttributes"
_ROOM = "RoomNodeAttributes"
_PLACE = "PlaceNodeAttributes"
_BUILDING_LAYER = 5


def _label_space_from_metadata(data: dict[str, Any]) -> dict[int, str]:
    meta = data.get("metadata") or {}
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
    box = attrs.get("bounding_box") or {}
    if box.get("type", "INVALID") != "INVALID" and "min" in box and "max" in box:
        return BBox3D(tuple(box["min"]), tuple(box["max"]))
    return BBox3D(tuple(position), tuple(position))


def spark_dsg_to_graph(path: str | Path, label_space: dict[int, str] | None = None) -> SceneGraph:
    """Parse a Spark-DSG JSON file into a :class:`SceneGraph` (change log: all new)."""
    p = Path(path)
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DatasetError(f"Spark-DSG file not found: {p}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise DatasetError(f"{p}: invalid JSON: {exc}") from None
    if not isinstance(data, dict) or not isinstance(data.get("nodes"), list):
        raise DatasetError(f"{p}: not a Spark-DSG JSON file (no 'nodes' list)")
    names = {**_label_space_from_metadata(data), **(label_space or {})}

    nodes: dict[int, dict[str, Any]] = {}
    for raw in data["nodes"]:
        try:
            nodes[int(raw["id"])] = raw
        except (KeyError, TypeError, ValueError):
            raise DatasetError(f"{p}: node without an integer id: {str(raw)[:80]}") from None
    adjacency: dict[int, set[int]] = defaultdict(set)
    for edge in data.get("edges", []):
        s, t = int(edge["source"]), int(edge["target"])
        if s in nodes and t in nodes:
            adjacency[s].add(t)
            adjacency[t].add(s)

    def kind(nid: int) -> str:
        return str(nodes[nid].get("attributes", {}).get("type", ""))

    graph = SceneGraph()
    building = [n for n in nodes.values() if n.get("layer") == _BUILDING_LAYER]
    floor = FloorNode(
        id=make_id(Layer.FLOOR, 0),
        level=0,
        label=str(building[0]["attributes"].get("name", "building")) if building else "floor 0",
    )
    graph.add_or_update(floor)

    room_ids: dict[int, str] = {}
    for nid, raw in nodes.items():
        if kind(nid) != _ROOM:
            continue
        attrs = raw["attributes"]
        room = RoomNode(
            id=make_id(Layer.ROOM, len(room_ids)),
            label=str(attrs.get("name") or f"room {len(room_ids)}"),
            floor_id=floor.id,
            position=tuple(float(v) for v in attrs.get("position", (0, 0, 0))),  # type: ignore[arg-type]
        )
        graph.add_or_update(room)
        graph.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor.id, room.id))
        room_ids[nid] = room.id

    def room_of(object_nid: int) -> str | None:
        """Nearest room over the place graph (object → place → … → room)."""
        seen = {object_nid}
        queue = deque([object_nid])
        while queue:
            cur = queue.popleft()
            for nxt in adjacency[cur]:
                if nxt in room_ids:
                    return room_ids[nxt]
                if nxt not in seen and kind(nxt) == _PLACE:
                    seen.add(nxt)
                    queue.append(nxt)
        return None

    areas: dict[str, str] = {}

    def area_for(room_id: str) -> str:
        if room_id not in areas:
            area = AreaNode(id=make_id(Layer.AREA, len(areas)), label="room area", room_id=room_id)
            graph.add_or_update(area)
            graph.add_edge(Edge.make(EdgeKind.HAS_AREA, room_id, area.id))
            areas[room_id] = area.id
        return areas[room_id]

    count = 0
    for nid, raw in nodes.items():
        if kind(nid) != _OBJECT:
            continue
        attrs = raw["attributes"]
        position = [float(v) for v in attrs.get("position", (0, 0, 0))]
        if len(position) != 3 or not np.all(np.isfinite(position)):
            raise DatasetError(f"{p}: object node {nid} has an invalid position")
        sem = int(attrs.get("semantic_label", -1))
        room_id = room_of(nid)
        if room_id is None:
            room_id = make_id(Layer.ROOM, "unassigned")
            if room_id not in graph:
                graph.add_or_update(RoomNode(id=room_id, label="unassigned", floor_id=floor.id))
                graph.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor.id, room_id))
        area_id = area_for(room_id)
        obj = ObjectNode(
            id=make_id(Layer.OBJECT, count),
            label=names.get(sem, f"class {sem}"),
            position=tuple(position),  # type: ignore[arg-type]
            bbox=_bbox(attrs, position),
            attributes={
                "source": "spark-dsg",
                "source_id": nid,
                "source_name": attrs.get("name", ""),
                "semantic_label": sem,
                "color": attrs.get("color"),
            },
            area_id=area_id,
            room_id=room_id,
            floor_id=floor.id,
        )
        graph.add_or_update(obj)
        graph.add_edge(Edge.make(EdgeKind.HAS_OBJECT, area_id, obj.id))
        count += 1
    for room_id, area_id in areas.items():
        members = [graph.get(o) for o in graph.children(area_id)]
        pts = np.array([m.position for m in members])  # type: ignore[union-attr]
        area = graph.get(area_id)
        area.position = tuple(float(v) for v in pts.mean(axis=0))  # type: ignore[union-attr]
        room_node = graph.get(room_id)
        if isinstance(room_node, RoomNode) and room_node.position == (0.0, 0.0, 0.0):
            room_node.position = area.position  # type: ignore[union-attr]
    return graph
