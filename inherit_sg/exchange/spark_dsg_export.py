"""Export a map as a Spark-DSG (Hydra) scene graph, built and saved by ``spark_dsg`` itself.

Needs the optional ``spark`` extra (``pip install 'inherit-sg[spark]'``, official
``spark-dsg`` 1.1.x). Layers follow Spark-DSG's ``DsgLayers``:

* ``Floor`` → a ``SemanticNodeAttributes`` node ``B(level)`` on ``BUILDINGS`` (layer 5).
  Spark-DSG has no floor layer; a one-storey map gives the one building node Hydra
  writes, a map of several storeys one building-layer node per storey. ``STAIRS``
  become building–building edges.
* ``Room`` → ``RoomNodeAttributes`` ``R(n)`` on ``ROOMS`` (layer 4), child of its storey's
  building node; ``CONNECTS`` (door adjacency) become room–room edges, as Hydra's.
* ``Object`` → ``ObjectNodeAttributes`` ``O(n)`` on ``OBJECTS`` (layer 2) with position,
  axis-aligned bounding box, ``name`` (its label), an integer ``semantic_label`` and the
  label's colour from Spark-DSG's ``distinct_150_color``.
* ``Area``: Spark-DSG has no layer between objects and rooms (layer 3 is ``PLACES``,
  free-space nodes), so objects are folded into their room (room → object edges, which
  Spark-DSG tools read as the object's parent). The areas are kept as data: each room's
  metadata lists its areas (id, label, position, summary) and each object's metadata
  names its area, so our importer rebuilds them.
* ``RELATION`` (object–object predicates) → object–object edges, ``weight`` = the best
  confidence; the edge metadata lists every predicate with its subject, since a
  Spark-DSG graph holds one undirected edge per node pair.

Label spaces: integer labels are named the way Spark-DSG does it, with
``set_labelspace`` per layer (objects and rooms), which ``save()`` writes to the graph
metadata (``labelspaces``, under the layer id key ``_l2p0`` and the layer name
``OBJECTS``, since ``get_labelspace(2)`` and ``get_labelspace("OBJECTS")`` read different
keys). Embeddings, room masks and keyframes are not exported (use
the JSON export for a lossless copy); every node's metadata keeps its INHerit-SG id.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.errors import InputError, ModelUnavailableError
from inherit_sg.exchange.spark_dsg import META_KEY
from inherit_sg.model import (
    AreaNode,
    BBox3D,
    EdgeKind,
    FloorNode,
    Layer,
    RoomNode,
    SceneGraph,
)


def _spark() -> Any:
    try:
        import spark_dsg
    except ImportError:
        raise ModelUnavailableError(
            "Spark-DSG export needs the spark-dsg package: pip install 'inherit-sg[spark]'"
        ) from None
    return spark_dsg


def _json_safe(value: Any) -> Any:
    """``value`` when JSON can hold it, else its string form."""
    try:
        json.dumps(value)
    except (TypeError, ValueError):
        return str(value)
    return value


def _box(sd: Any, bbox: BBox3D) -> Any:
    lo, hi = np.asarray(bbox.min, dtype=np.float64), np.asarray(bbox.max, dtype=np.float64)
    # spark_dsg.BoundingBox(dimensions, world_P_center) is an axis-aligned box
    return sd.BoundingBox((hi - lo).astype(np.float32), ((lo + hi) / 2.0).astype(np.float32))


def _room_box(room: RoomNode, floor: FloorNode | None) -> BBox3D | None:
    mask = room.mask
    if mask is None or not mask.cells.any():
        return None
    rows, cols = np.nonzero(mask.cells)
    z0, z1 = (floor.z_min, floor.z_max) if floor is not None else (0.0, 0.0)
    return BBox3D(
        (
            mask.origin_x + cols.min() * mask.resolution,
            mask.origin_y + rows.min() * mask.resolution,
            z0,
        ),
        (
            mask.origin_x + (cols.max() + 1) * mask.resolution,
            mask.origin_y + (rows.max() + 1) * mask.resolution,
            max(z0, z1),
        ),
    )


def label_space(labels: Iterable[str]) -> dict[int, str]:
    """Integer semantic labels for ``labels``: the sorted distinct names numbered from 0."""
    return dict(enumerate(sorted(set(labels))))


def graph_to_spark_dsg(graph: SceneGraph) -> Any:
    """Build a ``spark_dsg.DynamicSceneGraph`` from ``graph`` (see the module docstring)."""
    sd = _spark()
    dsg = sd.DynamicSceneGraph()
    layers = sd.DsgLayers
    floors = sorted(
        (n for n in graph.nodes(Layer.FLOOR) if isinstance(n, FloorNode)), key=lambda f: f.level
    )
    rooms = [n for n in graph.nodes(Layer.ROOM) if isinstance(n, RoomNode)]
    areas = [n for n in graph.nodes(Layer.AREA) if isinstance(n, AreaNode)]
    objects = list(graph.objects())
    symbols: dict[str, Any] = {}

    object_names = label_space(o.label for o in objects)
    room_names = label_space(r.label for r in rooms)
    object_labels = {name: k for k, name in object_names.items()}
    room_labels = {name: k for k, name in room_names.items()}

    for index, floor in enumerate(floors):
        attrs = sd.SemanticNodeAttributes()
        own = [r for r in rooms if r.floor_id == floor.id]
        xy = np.mean([r.position[:2] for r in own], axis=0) if own else np.zeros(2)
        attrs.position = np.array([xy[0], xy[1], floor.z_min], dtype=np.float64)
        attrs.name = floor.label or f"floor {floor.level}"
        attrs.metadata.set(
            {
                META_KEY: {
                    "id": floor.id,
                    "level": floor.level,
                    "z_min": floor.z_min,
                    "z_max": floor.z_max,
                }
            }
        )
        symbols[floor.id] = sd.NodeSymbol("B", index)
        dsg.add_node(layers.BUILDINGS, symbols[floor.id], attrs)

    floor_by_id = {f.id: f for f in floors}
    areas_of: dict[str, list[AreaNode]] = {}
    for area in areas:
        areas_of.setdefault(area.room_id or "", []).append(area)
    for index, room in enumerate(rooms):
        attrs = sd.RoomNodeAttributes()
        attrs.position = np.asarray(room.position, dtype=np.float64)
        attrs.name = room.label
        attrs.semantic_label = room_labels[room.label]
        box = _room_box(room, floor_by_id.get(room.floor_id or ""))
        if box is not None:
            attrs.bounding_box = _box(sd, box)
        attrs.metadata.set(
            {
                META_KEY: {
                    "id": room.id,
                    "summary": room.summary,
                    "types": [list(t) for t in room.types],
                    "areas": [
                        {
                            "id": a.id,
                            "label": a.label,
                            "position": list(a.position),
                            "summary": a.summary,
                        }
                        for a in areas_of.get(room.id, [])
                    ],
                }
            }
        )
        symbols[room.id] = sd.NodeSymbol("R", index)
        dsg.add_node(layers.ROOMS, symbols[room.id], attrs)
        if room.floor_id in symbols:
            dsg.insert_edge(symbols[room.floor_id], symbols[room.id])

    for index, obj in enumerate(objects):
        attrs = sd.ObjectNodeAttributes()
        attrs.position = np.asarray(obj.position, dtype=np.float64)
        attrs.bounding_box = _box(sd, obj.bbox)
        attrs.name = obj.label
        attrs.semantic_label = object_labels[obj.label]
        colour = sd.distinct_150_color(attrs.semantic_label)
        attrs.color = np.array([colour.r, colour.g, colour.b], dtype=np.uint8)
        attrs.metadata.set(
            {
                META_KEY: {
                    "id": obj.id,
                    "area_id": obj.area_id,
                    "floor_id": obj.floor_id,
                    "description": obj.description,
                    "status": obj.status.value,
                    "observation_count": obj.observation_count,
                    "attributes": _json_safe(obj.attributes),
                }
            }
        )
        symbols[obj.id] = sd.NodeSymbol("O", index)
        dsg.add_node(layers.OBJECTS, symbols[obj.id], attrs)
        if obj.room_id in symbols:
            dsg.insert_edge(symbols[obj.room_id], symbols[obj.id])

    _add_same_layer_edges(sd, dsg, graph, symbols)
    for layer, names in ((layers.OBJECTS, object_names), (layers.ROOMS, room_names)):
        key = dsg.get_layer_key(layer)
        # by layer id (metadata "_l2p0", get_labelspace(2)) and by name ("OBJECTS"):
        # spark_dsg looks the two up separately
        dsg.set_labelspace(sd.Labelspace(names), key.layer, key.partition)
        dsg.set_labelspace(sd.Labelspace(names), layer)
    dsg.metadata.add({META_KEY: {"exported_by": "inherit-sg", "areas": "folded into rooms"}})
    return dsg


def _add_same_layer_edges(sd: Any, dsg: Any, graph: SceneGraph, symbols: dict[str, Any]) -> None:
    """Object–object, room–room and storey–storey edges, one per node pair; the directed
    INHerit-SG edges on a pair go to the edge's metadata (subject = Spark-DSG node id)."""
    pairs: dict[tuple[int, int], list[dict[str, Any]]] = {}
    for kind in (EdgeKind.RELATION, EdgeKind.CONNECTS, EdgeKind.STAIRS):
        for edge in graph.edges(kind):
            if edge.src not in symbols or edge.dst not in symbols or edge.src == edge.dst:
                continue
            a, b = symbols[edge.src].value, symbols[edge.dst].value
            props = {k: _json_safe(v) for k, v in edge.props}
            pairs.setdefault((min(a, b), max(a, b)), []).append(
                {"kind": kind.value, "subject": a, **props}
            )
    for (a, b), entries in pairs.items():
        info = sd.EdgeAttributes()
        confidences = [float(e["confidence"]) for e in entries if "confidence" in e]
        if confidences:
            info.weighted = True
            info.weight = max(confidences)
        info.metadata.set({META_KEY: entries})
        dsg.insert_edge(sd.NodeSymbol(a), sd.NodeSymbol(b), info)


def export_spark_dsg(graph: SceneGraph, out: str | Path) -> dict[str, int]:
    """Write ``graph`` to ``out`` with ``DynamicSceneGraph.save`` (JSON for a ``.json``
    name); returns node and edge counts of the written graph."""
    target = Path(out)
    if target.is_dir():
        raise InputError(f"export target {target} is a directory: name a .json file")
    if not target.parent.is_dir():
        raise InputError(f"export target folder {target.parent} does not exist")
    if target.suffix.lower() != ".json":
        raise InputError(f"Spark-DSG export target {target} must be a .json file")
    dsg = graph_to_spark_dsg(graph)
    partial = target.with_name(target.name + ".partial" + target.suffix)
    try:
        dsg.save(str(partial), include_mesh=False)
        partial.replace(target)
    except (OSError, RuntimeError) as exc:
        partial.unlink(missing_ok=True)
        raise InputError(f"cannot write the Spark-DSG export to {target}: {exc}") from None
    return {"nodes": int(dsg.num_nodes()), "edges": int(dsg.num_edges())}
