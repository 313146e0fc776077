"""Events the geometric stream emits while it consumes frames (frozen dataclasses).

``FloorChanged`` is the hard trigger of the event-triggered map update (paper §III-C);
``RoomEntered`` is when the soft-trigger supervisor looks at the BEV picture.
"""

from __future__ import annotations

from dataclasses import dataclass

from inherit_sg.model import Keyframe


@dataclass(frozen=True)
class GeometryEvent:
    """Base: the frame that caused the event."""

    frame_index: int
    timestamp: float


@dataclass(frozen=True)
class FloorChanged(GeometryEvent):
    """A vertical transition finished: the robot is now on ``to_floor`` (hard trigger).

    ``created`` when the floor is new; ``reordered`` when existing floor levels moved
    because the new floor lies below them. ``stairs_start``/``stairs_end`` are the camera
    positions where the transition began and ended.
    """

    from_floor: str
    to_floor: str
    created: bool
    reordered: bool
    stairs_start: tuple[float, float, float]
    stairs_end: tuple[float, float, float]
    hard: bool = True


@dataclass(frozen=True)
class KeyframeSelected(GeometryEvent):
    """The gate selected a keyframe and queued it for the semantic stream."""

    keyframe: Keyframe
    reason: str
    hard: bool
    similarity: float


@dataclass(frozen=True)
class KeyframeDropped(GeometryEvent):
    """The full queue dropped a pending keyframe (back-pressure)."""

    keyframe_id: str
    hard: bool


@dataclass(frozen=True)
class RoomsUpdated(GeometryEvent):
    """A re-segmentation of ``floor_id`` changed the set of rooms."""

    floor_id: str
    room_ids: tuple[str, ...]
    added: tuple[str, ...]
    removed: tuple[str, ...]


@dataclass(frozen=True)
class RoomEntered(GeometryEvent):
    """The camera settled in another room (the soft trigger's cue)."""

    floor_id: str
    room_id: str
    previous_room_id: str | None
