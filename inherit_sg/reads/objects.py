"""Object listing and detail, read through Cypher on the public graph tables."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from inherit_sg.errors import NodeNotFoundError
from inherit_sg.reads.listing import label_filter, page_of
from inherit_sg.reads.models import (
    HierarchyStep,
    KeyframeRef,
    ObjectDetail,
    ObjectPage,
    ObjectSummary,
    RelationEdge,
)

if TYPE_CHECKING:
    from inherit_sg.facade import MapService

_FIELDS = "o.id, o.label, o.position, o.room_id, o.floor_id, o.description, o.status"


def _summary(row: list[Any]) -> dict[str, Any]:
    keys = ("id", "label", "position", "room_id", "floor_id", "description", "status")
    return dict(zip(keys, row, strict=True))


def list_objects(
    service: MapService,
    *,
    floor: str | None,
    room: str | None,
    label: str | None,
    limit: int,
    offset: int,
) -> ObjectPage:
    """A page of objects ordered by id, filtered by floor id, room id and label."""
    filters = [
        ("floor", "o.floor_id", floor),
        ("room", "o.room_id", room),
        ("label", "lower(o.label)", label_filter(label)),
    ]
    total, rows = page_of(service, "Object", "o", _FIELDS, filters, limit, offset)
    objects = [ObjectSummary(**_summary(row)) for row in rows]
    return ObjectPage(objects=objects, total=int(total), limit=limit, offset=offset)


def get_object(service: MapService, object_id: str) -> ObjectDetail:
    """One object with its RELATION edges, its area → room → floor path and the keyframes
    it was seen in; NodeNotFoundError when the map has no such object."""
    found = service.cypher(
        f"MATCH (o:Object) WHERE o.id = $id "
        f"RETURN {_FIELDS}, o.bbox_min, o.bbox_max, o.area_id, o.best_keyframe",
        {"id": object_id},
    )
    if not found.rows:
        raise NodeNotFoundError(f"no object with id {object_id!r} in map {service.store.path}")
    row = found.rows[0]
    base = _summary(row[:7])
    bbox_min, bbox_max, area_id, best_keyframe = row[7:]
    relations = [
        RelationEdge(
            direction=direction, predicate=p, confidence=c, other_id=oid, other_label=olabel
        )
        for direction, pattern in (
            ("out", "(o:Object)-[e:RELATION]->(x:Object)"),
            ("in", "(x:Object)-[e:RELATION]->(o:Object)"),
        )
        for p, c, oid, olabel in service.cypher(
            f"MATCH {pattern} WHERE o.id = $id "
            "RETURN e.predicate, e.confidence, x.id, x.label ORDER BY e.predicate, x.id",
            {"id": object_id},
            max_rows=None,
        ).rows
    ]
    hierarchy = [
        step
        for layer, node_id in (
            ("area", area_id),
            ("room", base["room_id"]),
            ("floor", base["floor_id"]),
        )
        if node_id and (step := hierarchy_step(service, layer, node_id)) is not None
    ]
    return ObjectDetail(
        **base,
        bbox_min=bbox_min,
        bbox_max=bbox_max,
        relations=relations,
        hierarchy=hierarchy,
        best_keyframe=best_keyframe or None,
        keyframes=_keyframes(service, object_id),
    )


_LAYER_TABLES = {"area": "Area", "room": "Room", "floor": "Floor"}


def hierarchy_step(service: MapService, layer: str, node_id: str) -> HierarchyStep | None:
    """The area, room or floor ``node_id`` as a step of a hierarchy path (with its
    label); None when the map has no such node."""
    hit = service.cypher(
        f"MATCH (n:{_LAYER_TABLES[layer]}) WHERE n.id = $id RETURN n.label", {"id": node_id}
    ).rows
    return HierarchyStep(layer=layer, id=node_id, label=hit[0][0] or "") if hit else None


def _keyframes(service: MapService, object_id: str) -> list[KeyframeRef]:
    rows = service.cypher(
        "MATCH (o:Object)-[e:SEEN_IN]->(k:Keyframe) WHERE o.id = $id "
        "RETURN k.id, k.session_id, k.timestamp, k.floor_id, e.props "
        "ORDER BY k.timestamp, k.id",
        {"id": object_id},
        max_rows=None,
    ).rows
    return [
        KeyframeRef(id=kid, session_id=sid, timestamp=ts, floor_id=fid, detection=_props(props))
        for kid, sid, ts, fid, props in rows
    ]


def _props(text: str | None) -> dict[str, Any] | None:
    try:
        value = json.loads(text) if text else None
    except json.JSONDecodeError:
        return None
    return value if isinstance(value, dict) else None
