"""Typed results of the map's reads: listings of floors, rooms, areas and objects (with
filters and paging), an object's detail and the floors → rooms → areas → objects tree.
:class:`~inherit_sg.facade.MapService` returns them; the CLI prints them and REST sends
them as they are (their JSON schema is the routes' response schema)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field


class FloorItem(BaseModel):
    """One floor with the number of rooms and objects on it."""

    id: str
    label: str
    level: int | None
    rooms: int = Field(description="Rooms on this floor.")
    objects: int = Field(description="Objects on this floor.")


class RoomTypeItem(BaseModel):
    """One inferred type of a room with its probability."""

    type: str = Field(description="A room type of rooms.toml, e.g. 'tv room'.")
    p: float = Field(description="Probability that the room is of this type.")


class RoomItem(BaseModel):
    """One room with its summary, inferred types, parent floor and child counts."""

    id: str
    label: str
    summary: str | None
    position: list[float] | None
    floor_id: str | None
    best_view: str | None = Field(description="Keyframe id of the room's best viewpoint.")
    types: list[RoomTypeItem] = Field(
        default_factory=list,
        description="The room's inferred types with their probabilities, best first (the "
        "label is the best); empty when the map holds none (oracle and imported maps).",
    )
    areas: int = Field(description="Functional areas in this room.")
    objects: int = Field(description="Objects in this room.")


class AreaItem(BaseModel):
    """One functional area with its summary, parent room / floor and object count."""

    id: str
    label: str
    summary: str | None
    position: list[float] | None
    room_id: str | None
    floor_id: str | None
    objects: int = Field(description="Objects in this area.")


class FloorPage(BaseModel):
    """A page of floors with the total that matched the filters."""

    floors: list[FloorItem]
    total: int
    limit: int
    offset: int


class RoomPage(BaseModel):
    """A page of rooms with the total that matched the filters."""

    rooms: list[RoomItem]
    total: int
    limit: int
    offset: int


class AreaPage(BaseModel):
    """A page of areas with the total that matched the filters."""

    areas: list[AreaItem]
    total: int
    limit: int
    offset: int


class TreeNode(BaseModel):
    """One node of the hierarchy tree: id, label and its children one layer down."""

    id: str
    label: str
    layer: str = Field(description="floor, room, area or object.")
    children: list[TreeNode] = Field(default_factory=list)


class Hierarchy(BaseModel):
    """Floors → rooms → areas → objects (objects without an area hang under their room,
    rooms or objects without a parent under ``unassigned``)."""

    floors: list[TreeNode]
    unassigned: list[TreeNode]


class ObjectSummary(BaseModel):
    """One object row of the public ``Object`` table."""

    id: str
    label: str
    position: list[float] | None
    room_id: str | None
    floor_id: str | None
    description: str | None
    status: str | None


class ObjectPage(BaseModel):
    """A page of objects with the total that matched the filters."""

    objects: list[ObjectSummary]
    total: int
    limit: int
    offset: int


class RelationEdge(BaseModel):
    """A ``RELATION`` edge touching an object."""

    direction: str = Field(description="'out' when the object is the subject, else 'in'.")
    predicate: str
    confidence: float | None
    other_id: str
    other_label: str


class KeyframeRef(BaseModel):
    """A keyframe an object was detected in (a ``SEEN_IN`` edge)."""

    id: str
    session_id: str | None
    timestamp: float | None
    floor_id: str | None
    image: str | None = Field(
        None, description="Path of the keyframe's JPEG under the map (REST answers)."
    )
    detection: dict[str, Any] | None = Field(
        None, description="What the segmenter saw there: label, score, pixel bbox."
    )


class HierarchyStep(BaseModel):
    """One ancestor of an object (area, room or floor)."""

    layer: str
    id: str
    label: str


class ObjectDetail(ObjectSummary):
    """An object with its relations, its area → room → floor path and its keyframes."""

    bbox_min: list[float] | None
    bbox_max: list[float] | None
    relations: list[RelationEdge]
    hierarchy: list[HierarchyStep]
    best_keyframe: str | None = Field(None, description="Keyframe of the object's best view.")
    keyframes: list[KeyframeRef] = Field(default_factory=list, description="Oldest first.")


class SessionRecord(BaseModel):
    """One mapping session of a map."""

    model_config = ConfigDict(extra="allow")

    id: str
    name: str
    frames: int
    keyframes: int


class MapStats(BaseModel):
    """Counts per table, sessions and bytes on disk of a map, with its identity, the
    vocabulary it was mapped with and its label space."""

    model_config = ConfigDict(extra="allow")

    path: str
    schema_version: int
    created: str | None
    text_embedder: str | None
    visual_encoder: str | None
    vocabulary: dict[str, Any] = Field(description="Digest and file versions.")
    label_space: list[str]
    nodes: dict[str, int] = Field(description="Rows per node table.")
    edges: dict[str, int] = Field(description="Rows per relationship table.")
    vectors: dict[str, int] = Field(description="Rows per embedding table.")
    sessions: list[SessionRecord]
    bytes: dict[str, int] = Field(description="graph, keyframes and total bytes on disk.")


class MappingSummary(BaseModel):
    """What a mapping session did (``map build`` and a finished live session)."""

    model_config = ConfigDict(extra="allow")

    session_id: str
    frames: int
    keyframes: int
    objects: int
    rooms: int
    floors: int
    seconds: float


class LiveStatus(BaseModel):
    """Counters of a running or finished live mapping session."""

    model_config = ConfigDict(extra="allow")

    session_id: str
    name: str | None
    state: str = Field(description="mapping, finishing, finished or failed.")
    frames_received: int
    frames_processed: int
    keyframes: int
    objects: int
    error: str | None
    summary: dict[str, Any] | None = Field(description="The mapping summary once finished.")
    map: str | None = Field(None, description="The served map's name.")


class Scene3DFloor(BaseModel):
    """A floor of the 3D view with its height range (metres, z up)."""

    id: str
    label: str
    level: int | None
    z_min: float | None
    z_max: float | None


class Scene3DRoom(BaseModel):
    """A room of the 3D view: its footprint as world (x, y) polygons, largest first."""

    id: str
    label: str
    floor_id: str | None
    position: list[float] | None
    outlines: list[list[list[float]]] = Field(
        description="Closed polygons [[x, y], …] of the room's footprint (from its mask)."
    )


class Scene3DObject(BaseModel):
    """An object of the 3D view: its axis-aligned box."""

    id: str
    label: str
    floor_id: str | None
    room_id: str | None
    bbox_min: list[float]
    bbox_max: list[float]


class Scene3DRelation(BaseModel):
    """A spatial relation between two objects (``source`` predicate ``target``)."""

    source: str
    target: str
    predicate: str


class Scene3DConnection(BaseModel):
    """Two rooms that connect, with the door's position when known."""

    source: str
    target: str
    door: list[float] | None


class Scene3D(BaseModel):
    """Everything the viewer's 3D view draws: floors, room footprints, object boxes,
    object relations and room connections."""

    floors: list[Scene3DFloor]
    rooms: list[Scene3DRoom]
    objects: list[Scene3DObject]
    relations: list[Scene3DRelation]
    connections: list[Scene3DConnection]


class NodeLink(BaseModel):
    """An edge between a node and another node of its layer: a spatial ``RELATION``
    between objects, a door (``CONNECTS``) between rooms, ``STAIRS`` between floors."""

    kind: str = Field(description="RELATION, CONNECTS or STAIRS.")
    direction: str = Field(description="'out' when the node is the edge's source, else 'in'.")
    predicate: str | None = Field(None, description="The spatial predicate (RELATION).")
    confidence: float | None = None
    other_id: str
    other_label: str
    door: list[float] | None = Field(None, description="The door's position (CONNECTS).")


class NodeDetail(BaseModel):
    """Any scene-graph node (floor, room, area or object): its properties, its ancestors
    and direct children, its edges within its layer and the keyframes that show it."""

    id: str
    layer: str = Field(description="floor, room, area or object.")
    label: str
    attributes: dict[str, Any] = Field(
        description="The node's properties in its graph table (room masks and keyframe "
        "id lists left out; JSON text columns decoded)."
    )
    hierarchy: list[HierarchyStep] = Field(
        description="Ancestors, nearest first (area → room → floor)."
    )
    children: list[HierarchyStep] = Field(
        description="Direct children: a floor's rooms, a room's areas (and its objects "
        "outside any area), an area's objects."
    )
    links: list[NodeLink]
    best_view: str | None = Field(None, description="Keyframe id of the best view, if any.")
    keyframes: list[KeyframeRef] = Field(
        default_factory=list, description="Keyframes an object was detected in, oldest first."
    )


class PropertySchema(BaseModel):
    """One property (column) of a graph table."""

    name: str
    type: str = Field(description="Kuzu type, e.g. STRING, INT64, DOUBLE[3].")
    primary_key: bool = False


class TableSchema(BaseModel):
    """One public graph table, read from the map's own catalogue."""

    name: str
    kind: str = Field(description="'node' or 'relationship'.")
    description: str
    source: str | None = Field(None, description="Source node table (relationships).")
    target: str | None = Field(None, description="Target node table (relationships).")
    properties: list[PropertySchema]


class CypherExample(BaseModel):
    """A read-only Cypher statement that runs on any map, with what it answers."""

    question: str
    cypher: str


class GraphSchema(BaseModel):
    """The public graph tables of a map with their properties, example statements and
    the rules a statement must follow."""

    nodes: list[TableSchema]
    relationships: list[TableSchema]
    examples: list[CypherExample]
    notes: list[str]
