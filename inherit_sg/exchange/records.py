"""Plain-JSON records of model objects (nodes, edges, keyframes, sessions).

Lossless: float32 vectors survive the float64 JSON round trip exactly, room masks and
JPEG bytes travel as base64. Used by the JSON export/import and the REST API.
"""

from __future__ import annotations

import base64
from typing import Any

import numpy as np

from inherit_sg.errors import InputError
from inherit_sg.model import (
    AreaNode,
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Keyframe,
    Layer,
    Node,
    NodeId,
    ObjectNode,
    ObjectStatus,
    Pose,
    RoomMask,
    RoomNode,
    Session,
)

_NODE_CLASSES: dict[Layer, type] = {
    Layer.FLOOR: FloorNode,
    Layer.ROOM: RoomNode,
    Layer.AREA: AreaNode,
    Layer.OBJECT: ObjectNode,
}


def _vec(value: np.ndarray | None) -> list[float] | None:
    return None if value is None else [float(v) for v in np.asarray(value, dtype=np.float32)]


def _unvec(value: list[float] | None) -> np.ndarray | None:
    return None if value is None else np.asarray(value, dtype=np.float32)


def _b64(data: bytes | None) -> str | None:
    return None if data is None else base64.b64encode(data).decode("ascii")


def _unb64(text: str | None) -> bytes | None:
    return None if text is None else base64.b64decode(text)


def _room_types(value: Any) -> tuple[tuple[str, float], ...]:
    """A room record's ``types`` (``[[type, p], …]``; absent in files written before
    rooms had them) as ``(type, probability)`` pairs."""
    if value is None:
        return ()
    if not isinstance(value, list) or not all(
        isinstance(v, list | tuple) and len(v) == 2 and isinstance(v[0], str) for v in value
    ):
        raise ValueError("'types' must be a list of [type, probability] pairs")
    return tuple((str(t), float(p)) for t, p in value)


def node_to_record(node: Node) -> dict[str, Any]:
    """JSON-able dict of any node; ``layer`` names its table."""
    rec: dict[str, Any] = {"layer": node.layer.name}
    for name, value in vars(node).items():
        if name == "layer":
            continue
        if isinstance(value, np.ndarray):
            rec[name] = _vec(value)
        elif isinstance(value, BBox3D):
            rec[name] = {"min": list(value.min), "max": list(value.max)}
        elif isinstance(value, RoomMask):
            rec[name] = _b64(value.to_bytes())
        elif isinstance(value, ObjectStatus):
            rec[name] = value.value
        elif name == "types" and isinstance(node, RoomNode):
            rec[name] = [[str(t), float(p)] for t, p in value]
        elif isinstance(value, tuple):
            rec[name] = list(value)
        else:
            rec[name] = value
    return rec


def node_from_record(rec: dict[str, Any]) -> Node:
    """Inverse of :func:`node_to_record`; InputError naming the record when malformed."""
    try:
        layer = Layer[rec["layer"]]
        fields = {k: v for k, v in rec.items() if k != "layer"}
        fields["id"] = NodeId(fields["id"])
        for key in ("visual_feature", "text_embedding"):
            if key in fields:
                fields[key] = _unvec(fields[key])
        if "position" in fields:
            fields["position"] = tuple(float(v) for v in fields["position"])
        if isinstance(fields.get("bbox"), dict):
            fields["bbox"] = BBox3D(tuple(fields["bbox"]["min"]), tuple(fields["bbox"]["max"]))
        if fields.get("mask") is not None:
            fields["mask"] = RoomMask.from_bytes(_unb64(fields["mask"]) or b"")
        if "status" in fields:
            fields["status"] = ObjectStatus(fields["status"])
        if layer is Layer.ROOM:
            fields["types"] = _room_types(fields.get("types"))
        node: Node = _NODE_CLASSES[layer](**fields)
        return node
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError(f"malformed node record {str(rec.get('id', rec))[:60]!r}: {exc}") from None


def edge_to_record(edge: Edge) -> dict[str, Any]:
    """JSON-able dict of an edge."""
    return {"kind": edge.kind.value, "src": edge.src, "dst": edge.dst, "props": edge.prop_dict}


def edge_from_record(rec: dict[str, Any]) -> Edge:
    """Inverse of :func:`edge_to_record`."""
    try:
        props = {
            k: (tuple(v) if isinstance(v, list) else v) for k, v in rec.get("props", {}).items()
        }
        return Edge.make(EdgeKind(rec["kind"]), rec["src"], rec["dst"], **props)
    except (KeyError, ValueError) as exc:
        raise InputError(f"malformed edge record {rec!r:.80}: {exc}") from None


def keyframe_to_record(kf: Keyframe) -> dict[str, Any]:
    """JSON-able dict of a keyframe, image bytes included when loaded."""
    return {
        "id": kf.id,
        "session_id": kf.session_id,
        "timestamp": kf.timestamp,
        "pose": kf.pose.to_list(),
        "floor_id": kf.floor_id,
        "frame_index": kf.frame_index,
        "global_feature": _vec(kf.global_feature),
        "jpeg": _b64(kf.jpeg),
        "width": kf.width,
        "height": kf.height,
    }


def keyframe_from_record(rec: dict[str, Any]) -> Keyframe:
    """Inverse of :func:`keyframe_to_record`."""
    try:
        return Keyframe(
            id=rec["id"],
            session_id=rec["session_id"],
            timestamp=float(rec["timestamp"]),
            pose=Pose(tuple(rec["pose"])),
            floor_id=rec.get("floor_id"),
            frame_index=int(rec.get("frame_index", 0)),
            global_feature=_unvec(rec.get("global_feature")),
            jpeg=_unb64(rec.get("jpeg")),
            width=int(rec.get("width", 0)),
            height=int(rec.get("height", 0)),
        )
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError(f"malformed keyframe record {str(rec.get('id'))!r}: {exc}") from None


def session_to_record(session: Session) -> dict[str, Any]:
    """JSON-able dict of a session."""
    return dict(vars(session))


def session_from_record(rec: dict[str, Any]) -> Session:
    """Inverse of :func:`session_to_record`."""
    try:
        return Session(**rec)
    except TypeError as exc:
        raise InputError(f"malformed session record: {exc}") from None
