"""Any scene-graph node by id: its properties, ancestors, children, edges within its
layer and keyframes (an object's through :func:`~inherit_sg.reads.objects.get_object`)."""

from __future__ import annotations

import contextlib
import json
from typing import TYPE_CHECKING, Any

from inherit_sg.errors import NodeNotFoundError
from inherit_sg.model.ids import Layer, layer_of
from inherit_sg.reads.models import HierarchyStep, NodeDetail, NodeLink
from inherit_sg.reads.objects import get_object, hierarchy_step
from inherit_sg.reads.pictures import check_key
from inherit_sg.store.codec import room_types_from_json

if TYPE_CHECKING:
    from inherit_sg.facade import MapService

# layer name → graph table, in the order an id without a known prefix is looked up
TABLES = {"object": "Object", "room": "Room", "area": "Area", "floor": "Floor"}
_PREFIX_LAYER = {
    Layer.OBJECT: "object",
    Layer.ROOM: "room",
    Layer.AREA: "area",
    Layer.FLOOR: "floor",
}
# bulky or repeated columns left out of ``attributes``
_LEFT_OUT = frozenset({"id", "label", "mask", "keyframe_ids"})
# edges within a layer: layer → (relationship, its properties returned as columns)
_LINKS = {"room": ("CONNECTS", "e.door"), "floor": ("STAIRS", "NULL")}


def describe_node(service: MapService, node_id: str) -> NodeDetail:
    """The node ``node_id`` of any layer; NodeNotFoundError when the map has none."""
    check_key("node", node_id)
    for layer in _lookup_order(node_id):
        rows = service.cypher(
            f"MATCH (n:{TABLES[layer]}) WHERE n.id = $id RETURN n", {"id": node_id}
        ).rows
        if rows:
            return _detail(service, layer, rows[0][0])
    raise NodeNotFoundError(
        f"no floor, room, area or object with id {node_id!r} in map {service.store.path}"
    )


def _lookup_order(node_id: str) -> list[str]:
    """Layers to look in, the one its id prefix names first."""
    try:
        first = _PREFIX_LAYER[layer_of(node_id)]
    except ValueError:
        return list(TABLES)
    return [first, *(name for name in TABLES if name != first)]


def _attributes(row: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in row.items():
        if key.startswith("_") or key in _LEFT_OUT:
            continue
        if key == "types":
            value = [{"type": t, "p": p} for t, p in room_types_from_json(value)]
        elif key == "attributes" and isinstance(value, str):
            with contextlib.suppress(json.JSONDecodeError):
                value = json.loads(value)
        out[key] = value
    return out


def _detail(service: MapService, layer: str, row: dict[str, Any]) -> NodeDetail:
    node_id = str(row["id"])
    common = {
        "id": node_id,
        "layer": layer,
        "label": row.get("label") or "",
        "attributes": _attributes(row),
    }
    if layer == "object":
        obj = get_object(service, node_id)
        links = [
            NodeLink(
                kind="RELATION",
                direction=r.direction,
                predicate=r.predicate,
                confidence=r.confidence,
                other_id=r.other_id,
                other_label=r.other_label,
            )
            for r in obj.relations
        ]
        return NodeDetail(
            **common,
            hierarchy=obj.hierarchy,
            children=[],
            links=links,
            best_view=obj.best_keyframe,
            keyframes=obj.keyframes,
        )
    return NodeDetail(
        **common,
        hierarchy=_ancestors(service, layer, row),
        children=_children(service, layer, node_id),
        links=_links(service, layer, node_id),
        best_view=row.get("best_view") or None,
    )


def _ancestors(service: MapService, layer: str, row: dict[str, Any]) -> list[HierarchyStep]:
    """Room → floor above an area, the floor above a room (floors have none)."""
    steps: list[HierarchyStep] = []
    floor_id = row.get("floor_id")
    room_id = row.get("room_id") if layer == "area" else None
    if room_id:
        hit = service.cypher(
            "MATCH (r:Room) WHERE r.id = $id RETURN r.label, r.floor_id", {"id": room_id}
        ).rows
        if hit:
            steps.append(HierarchyStep(layer="room", id=room_id, label=hit[0][0] or ""))
            floor_id = hit[0][1]
    if layer in ("area", "room") and floor_id:
        floor = hierarchy_step(service, "floor", floor_id)
        if floor is not None:
            steps.append(floor)
    return steps


def _children(service: MapService, layer: str, node_id: str) -> list[HierarchyStep]:
    """A floor's rooms, a room's areas and loose objects, an area's objects, by id."""
    queries = {
        "floor": [("room", "MATCH (c:Room) WHERE c.floor_id = $id")],
        "room": [
            ("area", "MATCH (c:Area) WHERE c.room_id = $id"),
            (
                "object",
                "MATCH (c:Object) WHERE c.room_id = $id AND (c.area_id IS NULL OR c.area_id = '')",
            ),
        ],
        "area": [("object", "MATCH (c:Object) WHERE c.area_id = $id")],
    }[layer]
    return [
        HierarchyStep(layer=child, id=cid, label=label or "")
        for child, match in queries
        for cid, label in service.cypher(
            f"{match} RETURN c.id, c.label ORDER BY c.id", {"id": node_id}, max_rows=None
        ).rows
    ]


def _links(service: MapService, layer: str, node_id: str) -> list[NodeLink]:
    """Doors between rooms, stairs between floors (areas have no edges of their own)."""
    if layer not in _LINKS:
        return []
    rel, extra = _LINKS[layer]
    table = TABLES[layer]
    links = []
    for direction, pattern in (
        ("out", f"(n:{table})-[e:{rel}]->(x:{table})"),
        ("in", f"(x:{table})-[e:{rel}]->(n:{table})"),
    ):
        rows = service.cypher(
            f"MATCH {pattern} WHERE n.id = $id RETURN x.id, x.label, {extra} ORDER BY x.id",
            {"id": node_id},
            max_rows=None,
        ).rows
        links += [
            NodeLink(
                kind=rel,
                direction=direction,
                other_id=oid,
                other_label=olabel or "",
                door=list(door) if door is not None else None,
            )
            for oid, olabel, door in rows
        ]
    return links
