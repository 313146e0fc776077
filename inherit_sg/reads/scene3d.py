"""What the viewer's 3D view draws: floors, room footprints as polygons, object boxes
and the graph's edges between them, read from the public tables in one pass.

Room outlines come from the stored room masks: the outer contours of the covered cells
(OpenCV), simplified to within one cell and turned into world x, y. Relation edges are
those between objects; ``near`` is left out unless asked for, because it links most
objects of a room to each other and hides the structure.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import cv2
import numpy as np

from inherit_sg.model import EdgeKind, Layer, ObjectStatus, RoomMask, SceneGraph
from inherit_sg.reads.models import (
    Scene3D,
    Scene3DConnection,
    Scene3DFloor,
    Scene3DObject,
    Scene3DRelation,
    Scene3DRoom,
)
from inherit_sg.reads.pictures import floor_level

if TYPE_CHECKING:
    from inherit_sg.facade import MapService
    from inherit_sg.model import FloorNode, ObjectNode, RoomNode

# the polygon may deviate from the mask's cell edges by this many cells
OUTLINE_TOLERANCE_CELLS = 1.0
# predicates drawn by default (``near`` links most objects of a room: asked for only)
DRAWN_PREDICATES = ("on", "above", "inside", "next to")


def mask_outlines(mask: RoomMask) -> list[list[list[float]]]:
    """Outer contours of a room mask as world (x, y) polygons, largest first."""
    cells = np.ascontiguousarray(mask.cells, dtype=np.uint8)
    if not cells.any():
        return []
    # pad so that contours of cells on the grid's border close outside them
    padded = np.pad(cells, 1)
    contours, _ = cv2.findContours(padded, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    out: list[tuple[float, list[list[float]]]] = []
    for contour in contours:
        poly = cv2.approxPolyDP(contour, OUTLINE_TOLERANCE_CELLS, True).reshape(-1, 2)
        if len(poly) < 3:
            continue
        # contour points are the boundary cells of the padded grid: its column c is the
        # mask's column c - 1, whose centre lies at c - 0.5 cells from the origin
        cols = poly[:, 0].astype(float) - 0.5
        rows = poly[:, 1].astype(float) - 0.5
        xs = mask.origin_x + cols * mask.resolution
        ys = mask.origin_y + rows * mask.resolution
        area = float(cv2.contourArea(contour))
        out.append(
            (area, [[round(float(x), 3), round(float(y), 3)] for x, y in zip(xs, ys, strict=True)])
        )
    out.sort(key=lambda item: -item[0])
    return [poly for _, poly in out]


def drawn_predicates(near: bool) -> tuple[str, ...]:
    """The relation predicates a 3D view draws (``near`` only when asked for)."""
    return (*DRAWN_PREDICATES, "near") if near else DRAWN_PREDICATES


def _floors(service: MapService, floor_id: str | None) -> list[Scene3DFloor]:
    query = "MATCH (f:Floor) RETURN f.id, f.label, f.level, f.z_min, f.z_max ORDER BY f.level"
    floors = [
        Scene3DFloor(id=fid, label=label or "", level=level, z_min=z_min, z_max=z_max)
        for fid, label, level, z_min, z_max in service.cypher(query, max_rows=None).rows
    ]
    return [f for f in floors if floor_id is None or f.id == floor_id]


def _rooms(service: MapService, floor_id: str | None) -> list[Scene3DRoom]:
    rows = service.cypher(
        "MATCH (r:Room) WHERE $f IS NULL OR r.floor_id = $f "
        "RETURN r.id, r.label, r.floor_id, r.position, r.mask ORDER BY r.id",
        {"f": floor_id},
        max_rows=None,
    ).rows
    return [
        Scene3DRoom(
            id=rid,
            label=label or "",
            floor_id=fid,
            position=position,
            outlines=mask_outlines(RoomMask.from_bytes(mask)) if mask else [],
        )
        for rid, label, fid, position, mask in rows
    ]


def _objects(service: MapService, floor_id: str | None) -> list[Scene3DObject]:
    rows = service.cypher(
        "MATCH (o:Object) WHERE ($f IS NULL OR o.floor_id = $f) "
        "AND o.bbox_min IS NOT NULL AND o.bbox_max IS NOT NULL "
        "AND coalesce(o.status, 'active') <> 'removed' "
        "RETURN o.id, o.label, o.floor_id, o.room_id, o.bbox_min, o.bbox_max ORDER BY o.id",
        {"f": floor_id},
        max_rows=None,
    ).rows
    return [
        Scene3DObject(
            id=oid, label=label or "", floor_id=fid, room_id=rid, bbox_min=lo, bbox_max=hi
        )
        for oid, label, fid, rid, lo, hi in rows
    ]


def _relations(
    service: MapService, objects: set[str], predicates: tuple[str, ...]
) -> list[Scene3DRelation]:
    rows = service.cypher(
        "MATCH (a:Object)-[e:RELATION]->(b:Object) WHERE e.predicate IN $p "
        "RETURN a.id, b.id, e.predicate ORDER BY a.id, b.id",
        {"p": list(predicates)},
        max_rows=None,
    ).rows
    return [
        Scene3DRelation(source=a, target=b, predicate=p)
        for a, b, p in rows
        if a in objects and b in objects
    ]


def _connections(service: MapService, rooms: set[str]) -> list[Scene3DConnection]:
    rows = service.cypher(
        "MATCH (a:Room)-[c:CONNECTS]->(b:Room) RETURN a.id, b.id, c.door ORDER BY a.id, b.id",
        max_rows=None,
    ).rows
    return [
        Scene3DConnection(source=a, target=b, door=door)
        for a, b, door in rows
        if a in rooms and b in rooms
    ]


def build_scene3d(
    service: MapService, *, floor_id: str | None = None, near: bool = False
) -> Scene3D:
    """The 3D view's content for one floor (all floors when ``floor_id`` is None);
    ``near`` adds the ``near`` relations. NodeNotFoundError for an unknown floor."""
    if floor_id is not None:
        floor_level(service, floor_id)
    objects = _objects(service, floor_id)
    rooms = _rooms(service, floor_id)
    predicates = drawn_predicates(near)
    return Scene3D(
        floors=_floors(service, floor_id),
        rooms=rooms,
        objects=objects,
        relations=_relations(service, {o.id for o in objects}, predicates),
        connections=_connections(service, {r.id for r in rooms}),
    )


def scene_from_graph(graph: SceneGraph, *, near: bool = False) -> Scene3D:
    """The same content as :func:`build_scene3d`, from an in-memory graph (a map being
    built): all floors."""
    floors: list[FloorNode] = sorted(graph.nodes(Layer.FLOOR), key=lambda f: f.level)  # type: ignore[arg-type]
    rooms: list[RoomNode] = sorted(graph.nodes(Layer.ROOM), key=lambda r: r.id)  # type: ignore[arg-type]
    objects: list[ObjectNode] = sorted(
        (o for o in graph.objects() if o.status is not ObjectStatus.REMOVED), key=lambda o: o.id
    )
    predicates = drawn_predicates(near)
    kept = {o.id for o in objects}
    room_ids = {r.id for r in rooms}
    relations = [
        Scene3DRelation(source=e.src, target=e.dst, predicate=str(e.prop("predicate")))
        for e in graph.edges(EdgeKind.RELATION)
        if e.prop("predicate") in predicates and e.src in kept and e.dst in kept
    ]
    connections = [
        Scene3DConnection(source=e.src, target=e.dst, door=_door(e.prop("door")))
        for e in graph.edges(EdgeKind.CONNECTS)
        if e.src in room_ids and e.dst in room_ids
    ]
    return Scene3D(
        floors=[
            Scene3DFloor(id=f.id, label=f.label, level=f.level, z_min=f.z_min, z_max=f.z_max)
            for f in floors
        ],
        rooms=[
            Scene3DRoom(
                id=r.id,
                label=r.label,
                floor_id=r.floor_id,
                position=list(r.position),
                outlines=mask_outlines(r.mask) if r.mask is not None else [],
            )
            for r in rooms
        ],
        objects=[
            Scene3DObject(
                id=o.id,
                label=o.label,
                floor_id=o.floor_id,
                room_id=o.room_id,
                bbox_min=list(o.bbox.min),
                bbox_max=list(o.bbox.max),
            )
            for o in objects
        ],
        relations=relations,
        connections=connections,
    )


def _door(value: object) -> list[float] | None:
    if isinstance(value, list | tuple) and len(value) == 3:
        return [float(v) for v in value]
    return None
