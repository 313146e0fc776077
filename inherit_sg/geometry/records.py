"""Small records the geometric stream keeps: room node ids, stairs, counters, and the
room-entering hysteresis."""

from __future__ import annotations

from dataclasses import dataclass, field

from inherit_sg.model import Layer, NodeId, make_id


def room_node_id(room: int) -> NodeId:
    """Scene-graph id of a room number."""
    return make_id(Layer.ROOM, room)


@dataclass
class IdCounter:
    """Hands out increasing integers (picklable, unlike ``itertools.count``)."""

    next_id: int = 1

    def __call__(self) -> int:
        value = self.next_id
        self.next_id += 1
        return value


@dataclass
class StairsRecord:
    """Where a transition between two floors happened (first time seen)."""

    from_floor: str
    to_floor: str
    start: tuple[float, float, float]
    end: tuple[float, float, float]


@dataclass
class StreamStats:
    """Counters of a stream run; ``frame_floors`` is the floor id of every frame."""

    frames: int = 0
    integrated: int = 0
    keyframes: int = 0
    segmentations: int = 0
    refinements: int = 0
    dropped_keyframes: int = 0
    frame_floors: list[str] = field(default_factory=list)


@dataclass
class RoomTracker:
    """The room the camera is in, switched after ``frames_needed`` frames in another."""

    frames_needed: int = 3
    current: int = 0
    candidate: int = 0
    frames: int = 0

    def observe(self, room: int) -> int | None:
        """Feed the room under the camera (0 = none); returns the room just entered."""
        if room == 0 or room == self.current:
            self.candidate, self.frames = 0, 0
            return None
        if room == self.candidate:
            self.frames += 1
        else:
            self.candidate, self.frames = room, 1
        if self.frames < self.frames_needed:
            return None
        self.current, self.candidate, self.frames = room, 0, 0
        return room
