"""Ground-truth ``scene.json`` → scene graph: the oracle map.

An oracle map holds the simulator's true floors, rooms, areas and objects, with
descriptions written from the true attributes and relations computed by the same
geometric rules as a built map. It is the upper bound for retrieval (perfect perception)
in benchmarks and ablations, and a quick way to get a realistic map for tests. It is
never used by mapping: a built map comes from pixels only.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

import numpy as np

from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.mapping.relations import infer_relations
from inherit_sg.mapping.room_semantics import summarise_room
from inherit_sg.model import (
    AreaNode,
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    RoomMask,
    RoomNode,
    SceneGraph,
    make_id,
)

MASK_RESOLUTION = 0.1


def _mask(polygon: list[list[float]]) -> RoomMask:
    import cv2

    pts = np.asarray(polygon, dtype=float)
    lo = pts.min(axis=0)
    size = np.ceil((pts.max(axis=0) - lo) / MASK_RESOLUTION).astype(int) + 1
    cells = np.zeros((size[1], size[0]), np.uint8)
    pix = np.round((pts - lo) / MASK_RESOLUTION).astype(np.int32)
    cv2.fillPoly(cells, [pix], 1)
    return RoomMask(float(lo[0]), float(lo[1]), MASK_RESOLUTION, cells.astype(bool))


def _describe(label: str, attrs: dict[str, object], size: np.ndarray, room: str) -> str:
    words = [str(attrs[k]) for k in ("size", "colour", "material") if attrs.get(k)]
    dims = " × ".join(f"{v:.1f}" for v in size)
    return f"a {' '.join([*words, label])}, about {dims} m, in the {room}"


def scene_to_graph(scene: Scene) -> SceneGraph:
    """Build the oracle scene graph of ``scene`` (no embeddings; see node_text)."""
    graph = SceneGraph()
    floor_ids = {}
    for f in sorted(scene.floors, key=lambda f: f.index):
        node = FloorNode(
            make_id(Layer.FLOOR, f.index), f.index, f"floor {f.index}", f.z, f.z + f.height
        )
        graph.add_or_update(node)
        floor_ids[f.index] = node.id
    for lower, upper in zip(sorted(floor_ids), sorted(floor_ids)[1:], strict=False):
        graph.add_edge(Edge.make(EdgeKind.STAIRS, floor_ids[lower], floor_ids[upper]))
    room_ids = {}
    floor_z = {f.index: f.z for f in scene.floors}
    for r in scene.rooms:
        centre = np.asarray(r.polygon, dtype=float).mean(axis=0)
        room = RoomNode(
            make_id(Layer.ROOM, r.id),
            r.type,
            floor_id=floor_ids.get(r.floor),
            position=(float(centre[0]), float(centre[1]), floor_z.get(r.floor, 0.0)),
            mask=_mask(r.polygon),
        )
        graph.add_or_update(room)
        if room.floor_id:
            graph.add_edge(Edge.make(EdgeKind.HAS_ROOM, room.floor_id, room.id))
        room_ids[r.id] = room.id
    for d in scene.doors:
        if len(d.rooms) == 2 and all(r in room_ids for r in d.rooms):
            a, b = (room_ids[r] for r in d.rooms)
            for src, dst in ((a, b), (b, a)):
                graph.add_edge(Edge.make(EdgeKind.CONNECTS, src, dst, door=tuple(d.position)))
    area_of = {oid: a.id for a in scene.areas for oid in a.object_ids}
    area_ids: dict[str, str] = {}
    fallback_area: dict[str, str] = {}
    for gt_area in scene.areas:
        if gt_area.room_id in room_ids:
            area = AreaNode(
                make_id(Layer.AREA, gt_area.id), gt_area.label, room_id=room_ids[gt_area.room_id]
            )
            graph.add_or_update(area)
            graph.add_edge(Edge.make(EdgeKind.HAS_AREA, room_ids[gt_area.room_id], area.id))
            area_ids[gt_area.id] = area.id
    room_label = {room_ids[r.id]: r.type for r in scene.rooms}
    members: dict[str, list[ObjectNode]] = defaultdict(list)
    for o in scene.objects:
        room_id = room_ids.get(o.room_id or "")
        if room_id is None:
            continue
        area_id = area_ids.get(area_of.get(o.id, "")) or area_ids.get(o.area_id or "")
        if area_id is None:
            if room_id not in fallback_area:
                rest = AreaNode(
                    make_id(Layer.AREA, f"{o.room_id}-other"), "room area", room_id=room_id
                )
                graph.add_or_update(rest)
                graph.add_edge(Edge.make(EdgeKind.HAS_AREA, room_id, rest.id))
                fallback_area[room_id] = rest.id
            area_id = fallback_area[room_id]
        box = BBox3D(tuple(o.bbox_min), tuple(o.bbox_max))
        obj = ObjectNode(
            make_id(Layer.OBJECT, o.id),
            o.label,
            tuple(float(v) for v in o.centroid),  # type: ignore[arg-type]
            box,
            description=_describe(o.label, o.attributes, box.size, room_label[room_id]),
            attributes={
                k: v for k, v in o.attributes.items() if k in ("colour", "material", "size")
            },
            area_id=area_id,
            room_id=room_id,
            floor_id=floor_ids.get(o.floor),
        )
        graph.add_or_update(obj)
        graph.add_edge(Edge.make(EdgeKind.HAS_OBJECT, area_id, obj.id))
        members[area_id].append(obj)
    for area_id, objs in members.items():
        area_node = graph.get(area_id)
        assert isinstance(area_node, AreaNode)
        pts = np.array([o.position for o in objs])
        area_node.position = (
            float(pts[:, 0].mean()),
            float(pts[:, 1].mean()),
            float(pts[:, 2].mean()),
        )
        area_node.summary = (
            f"A {area_node.label} with {', '.join(sorted({o.label for o in objs}))}."
        )
    for room_id in room_ids.values():
        room_node = graph.get(room_id)
        assert isinstance(room_node, RoomNode)
        areas = [
            a for a in (graph.get(c) for c in graph.children(room_id)) if isinstance(a, AreaNode)
        ]
        contents = [graph.get(o).label for a in areas for o in graph.children(a.id)]
        floor_node = graph.get(room_node.floor_id) if room_node.floor_id else None
        room_node.summary = summarise_room(
            room_node.label,
            floor_node.level if isinstance(floor_node, FloorNode) else None,
            [a.summary for a in areas],
            contents,
        )
    objects = list(graph.objects())
    room_of = {o.id: o.room_id for o in objects}
    neighbours: dict[str, set[str]] = defaultdict(set)
    for e in graph.edges(EdgeKind.CONNECTS):
        neighbours[e.src].add(e.dst)
    for rel in infer_relations(objects, room_of, neighbours):
        graph.add_edge(rel.to_edge())
    return graph


def scene_file_to_graph(path: str | Path) -> SceneGraph:
    """:func:`scene_to_graph` of a ``scene.json`` file (or a folder holding one)."""
    return scene_to_graph(Scene.load(path))
