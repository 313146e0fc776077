"""Response models of the listing routes the web viewer uses (floors, rooms, areas and
the whole hierarchy)."""

from __future__ import annotations

from pydantic import BaseModel, Field


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
