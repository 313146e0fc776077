"""Layers, edge kinds and typed node ids.

Node ids are strings with a layer prefix (``floor:0``, ``room:3``, ``area:12``,
``obj:57``, ``kf:…``, ``session:…``) so that an id alone says which Kuzu table holds it.
"""

from __future__ import annotations

from enum import IntEnum, StrEnum
from typing import TypeAlias

# A node id is a plain string whose prefix names its layer (see make_id / layer_of).
NodeId: TypeAlias = str


class Layer(IntEnum):
    """The four levels of the hierarchy (paper §III-A): L0 floor … L3 object."""

    FLOOR = 0
    ROOM = 1
    AREA = 2
    OBJECT = 3

    @property
    def table(self) -> str:
        """Kuzu node table holding nodes of this layer."""
        return _TABLES[self]

    @property
    def prefix(self) -> str:
        """Id prefix of nodes of this layer."""
        return _PREFIXES[self]


_TABLES = {Layer.FLOOR: "Floor", Layer.ROOM: "Room", Layer.AREA: "Area", Layer.OBJECT: "Object"}
_PREFIXES = {Layer.FLOOR: "floor", Layer.ROOM: "room", Layer.AREA: "area", Layer.OBJECT: "obj"}
_PREFIX_TO_LAYER = {v: k for k, v in _PREFIXES.items()}


class EdgeKind(StrEnum):
    """Edge types; the values are the public Kuzu relationship table names."""

    HAS_ROOM = "HAS_ROOM"  # Floor -> Room
    HAS_AREA = "HAS_AREA"  # Room -> Area
    HAS_OBJECT = "HAS_OBJECT"  # Area -> Object
    CONNECTS = "CONNECTS"  # Room -> Room (through a door)
    STAIRS = "STAIRS"  # Floor -> Floor
    RELATION = "RELATION"  # Object -> Object (predicate, confidence)
    SEEN_IN = "SEEN_IN"  # Object -> Keyframe

    @property
    def endpoints(self) -> tuple[str, str]:
        """(source table, destination table) of this relationship."""
        return _ENDPOINTS[self]


_ENDPOINTS = {
    EdgeKind.HAS_ROOM: ("Floor", "Room"),
    EdgeKind.HAS_AREA: ("Room", "Area"),
    EdgeKind.HAS_OBJECT: ("Area", "Object"),
    EdgeKind.CONNECTS: ("Room", "Room"),
    EdgeKind.STAIRS: ("Floor", "Floor"),
    EdgeKind.RELATION: ("Object", "Object"),
    EdgeKind.SEEN_IN: ("Object", "Keyframe"),
}


def make_id(layer: Layer, key: int | str) -> NodeId:
    """Build the id of a node of ``layer`` from a counter or a string key."""
    return f"{layer.prefix}:{key}"


def layer_of(node_id: str) -> Layer:
    """Layer of a node id; raises ValueError for ids that are not scene-graph nodes."""
    prefix, sep, _ = node_id.partition(":")
    if not sep or prefix not in _PREFIX_TO_LAYER:
        raise ValueError(f"not a scene-graph node id: {node_id!r}")
    return _PREFIX_TO_LAYER[prefix]
