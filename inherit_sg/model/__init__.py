"""Typed scene-graph model: layers, ids, value types, nodes, edges, frames and the
in-memory :class:`SceneGraph` working set."""

from inherit_sg.model.frame import Frame
from inherit_sg.model.graph import ChangeSet, SceneGraph
from inherit_sg.model.ids import EdgeKind, Layer, NodeId, layer_of, make_id
from inherit_sg.model.nodes import (
    AreaNode,
    Edge,
    FloorNode,
    Keyframe,
    Node,
    ObjectNode,
    ObjectStatus,
    RoomMask,
    RoomNode,
    Session,
)
from inherit_sg.model.values import BBox3D, Intrinsics, Pose

__all__ = [
    "AreaNode",
    "BBox3D",
    "ChangeSet",
    "Edge",
    "EdgeKind",
    "FloorNode",
    "Frame",
    "Intrinsics",
    "Keyframe",
    "Layer",
    "Node",
    "NodeId",
    "ObjectNode",
    "ObjectStatus",
    "Pose",
    "RoomMask",
    "RoomNode",
    "SceneGraph",
    "Session",
    "layer_of",
    "make_id",
]
