"""Pictures the viewer shows: a floor's BEV (drawn from the graph, or the one ``map build``
stored) and keyframe JPEGs (by id, or the best view of an object or room)."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from inherit_sg.errors import InputError, NodeNotFoundError
from inherit_sg.model import RoomMask
from inherit_sg.reads.bev import BevObject, BevRoom, BevTransform, encode_png, render_bev

if TYPE_CHECKING:
    from inherit_sg.facade import MapService

# graph keys: letters, digits and ``_ . : -`` (e.g. ``kf:session:1:25``, ``floor:0``)
NODE_KEY = re.compile(r"^[A-Za-z0-9_.:-]{1,200}$")


def check_key(kind: str, key: str) -> str:
    """``key`` when it is a well-formed graph key; InputError (400) otherwise."""
    if not NODE_KEY.match(key) or ".." in key:
        raise InputError(f"{kind} id {key!r}: use letters, digits, '_', '.', ':', '-'")
    return key


def floor_level(service: MapService, floor_id: str) -> int:
    """The level of ``floor_id``; NodeNotFoundError (404) when the map has no such floor."""
    check_key("floor", floor_id)
    rows = service.cypher("MATCH (f:Floor) WHERE f.id = $id RETURN f.level", {"id": floor_id}).rows
    if not rows:
        raise NodeNotFoundError(f"no floor with id {floor_id!r} in map {service.store.path}")
    return int(rows[0][0] or 0)


def graph_bev(service: MapService, floor_id: str) -> tuple[bytes, BevTransform]:
    """PNG of one floor drawn from its room masks and object positions, with its transform."""
    floor_level(service, floor_id)
    rooms = [
        BevRoom(
            id=rid,
            label=label or "",
            position=position,
            mask=RoomMask.from_bytes(mask) if mask else None,
        )
        for rid, label, position, mask in service.cypher(
            "MATCH (r:Room) WHERE r.floor_id = $f RETURN r.id, r.label, r.position, r.mask "
            "ORDER BY r.id",
            {"f": floor_id},
            max_rows=None,
        ).rows
    ]
    objects = [
        BevObject(id=oid, position=position)
        for oid, position in service.cypher(
            "MATCH (o:Object) WHERE o.floor_id = $f AND o.position IS NOT NULL "
            "RETURN o.id, o.position ORDER BY o.id",
            {"f": floor_id},
            max_rows=None,
        ).rows
    ]
    img, tf = render_bev(rooms, objects)
    return encode_png(img), tf


def stored_bev(service: MapService, floor_id: str) -> bytes:
    """The BEV PNG ``map build`` wrote for this floor (its transform is not recorded)."""
    level = floor_level(service, floor_id)
    path = service.store.path / "bev" / f"floor_{level}.png"
    if not path.is_file():
        raise NodeNotFoundError(f"map {service.store.path} has no stored BEV for {floor_id!r}")
    return path.read_bytes()


def keyframe_jpeg(service: MapService, keyframe_id: str) -> bytes:
    """The JPEG bytes of one keyframe; NodeNotFoundError (404) when absent."""
    check_key("keyframe", keyframe_id)
    kf = service.store.get_keyframe(keyframe_id, with_image=True)
    if not kf.jpeg:
        raise NodeNotFoundError(f"keyframe {keyframe_id!r} has no stored image")
    return kf.jpeg


def best_view(service: MapService, node_id: str) -> str:
    """The keyframe id of an object's or room's best view; 404 when there is none."""
    check_key("node", node_id)
    for query in (
        "MATCH (o:Object) WHERE o.id = $id RETURN o.best_keyframe",
        "MATCH (r:Room) WHERE r.id = $id RETURN r.best_view",
    ):
        rows = service.cypher(query, {"id": node_id}).rows
        if rows:
            if not rows[0][0]:
                raise NodeNotFoundError(f"node {node_id!r} has no best view")
            return str(rows[0][0])
    raise NodeNotFoundError(f"no object or room with id {node_id!r} in map {service.store.path}")
