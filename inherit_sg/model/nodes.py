"""Node, edge, keyframe and session records of the scene graph (paper §III-A).

Nodes are mutable dataclasses (the working set is updated in place while mapping);
value types they hold (:class:`~inherit_sg.model.values.BBox3D`, poses) are frozen.
Vectors are float32 numpy arrays or ``None`` when not computed yet.
"""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

import numpy as np

from inherit_sg.model.ids import EdgeKind, Layer, NodeId
from inherit_sg.model.values import BBox3D, Pose, Vec3

Vector = np.ndarray


class ObjectStatus(StrEnum):
    """Life-cycle of an object node across sessions."""

    ACTIVE = "active"  # seen in the latest session that looked at its place
    MISSING = "missing"  # its place was in view in a later session but it was not seen
    REMOVED = "removed"  # retired by a user or merged away (kept for history)


@dataclass(frozen=True)
class RoomMask:
    """2D room footprint on a BEV grid.

    ``cells[r, c]`` covers world x in ``[origin_x + c*res, origin_x + (c+1)*res)`` and
    world y in ``[origin_y + r*res, origin_y + (r+1)*res)``.
    """

    origin_x: float
    origin_y: float
    resolution: float
    cells: np.ndarray  # bool (H, W)

    _HEADER = struct.Struct("<4sdddII")
    _MAGIC = b"RMK1"

    @property
    def area_m2(self) -> float:
        """Covered floor area in m²."""
        return float(self.cells.sum()) * self.resolution**2

    def contains_xy(self, x: float, y: float) -> bool:
        """Whether world point (x, y) falls on a covered cell."""
        c = int(np.floor((x - self.origin_x) / self.resolution))
        r = int(np.floor((y - self.origin_y) / self.resolution))
        h, w = self.cells.shape
        return 0 <= r < h and 0 <= c < w and bool(self.cells[r, c])

    def distance_xy(self, x: float, y: float) -> float:
        """Metres from world point (x, y) to the nearest covered cell's centre (0 on a
        covered cell; infinite for an empty mask)."""
        if self.contains_xy(x, y):
            return 0.0
        rows, cols = np.nonzero(self.cells)
        if rows.size == 0:
            return float("inf")
        cx = self.origin_x + (cols + 0.5) * self.resolution
        cy = self.origin_y + (rows + 0.5) * self.resolution
        return float(np.sqrt(np.min((cx - x) ** 2 + (cy - y) ** 2)))

    def to_bytes(self) -> bytes:
        """Compact binary form (bit-packed, zlib) for storage."""
        h, w = self.cells.shape
        packed = zlib.compress(np.packbits(self.cells.astype(bool), axis=None).tobytes(), 6)
        head = self._HEADER.pack(self._MAGIC, self.origin_x, self.origin_y, self.resolution, h, w)
        return head + packed

    @classmethod
    def from_bytes(cls, data: bytes) -> RoomMask:
        """Inverse of :meth:`to_bytes`."""
        magic, ox, oy, res, h, w = cls._HEADER.unpack_from(data)
        if magic != cls._MAGIC:
            raise ValueError("not a room mask blob")
        bits = np.frombuffer(zlib.decompress(data[cls._HEADER.size :]), dtype=np.uint8)
        cells = np.unpackbits(bits, count=h * w).reshape(h, w).astype(bool)
        return cls(ox, oy, res, cells)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RoomMask):
            return NotImplemented
        return (
            (self.origin_x, self.origin_y, self.resolution)
            == (other.origin_x, other.origin_y, other.resolution)
            and self.cells.shape == other.cells.shape
            and bool(np.array_equal(self.cells, other.cells))
        )

    __hash__ = None  # type: ignore[assignment]


@dataclass
class FloorNode:
    """L0: one storey, with the height band its rooms occupy."""

    id: NodeId
    level: int
    label: str = ""
    z_min: float = 0.0
    z_max: float = 0.0
    layer: Layer = field(default=Layer.FLOOR, init=False, repr=False)


@dataclass
class RoomNode:
    """L1: a room with its VLM/offline summary, 2D mask, best viewpoint and the
    distribution of its inferred types (``types``: ``(type, probability)`` pairs)."""

    id: NodeId
    label: str
    floor_id: str | None = None
    position: Vec3 = (0.0, 0.0, 0.0)
    summary: str = ""
    mask: RoomMask | None = None
    best_view: str | None = None  # keyframe id
    text_embedding: Vector | None = None
    # inferred room types with their probabilities, best first (the label is the best);
    # empty when not inferred (oracle and imported maps)
    types: tuple[tuple[str, float], ...] = ()
    layer: Layer = field(default=Layer.ROOM, init=False, repr=False)


@dataclass
class AreaNode:
    """L2: a functional area (object cluster inside a room) with label and summary."""

    id: NodeId
    label: str
    room_id: str | None = None
    position: Vec3 = (0.0, 0.0, 0.0)
    summary: str = ""
    text_embedding: Vector | None = None
    layer: Layer = field(default=Layer.AREA, init=False, repr=False)


@dataclass
class ObjectNode:
    """L3: an object instance fused from many observations."""

    id: NodeId
    label: str
    position: Vec3
    bbox: BBox3D
    description: str = ""
    visual_feature: Vector | None = None
    text_embedding: Vector | None = None
    keyframe_ids: list[str] = field(default_factory=list)
    best_keyframe: str | None = None
    observation_count: int = 1
    first_seen: float = 0.0
    last_seen: float = 0.0
    status: ObjectStatus = ObjectStatus.ACTIVE
    attributes: dict[str, Any] = field(default_factory=dict)  # colour, material, size …
    area_id: str | None = None
    room_id: str | None = None
    floor_id: str | None = None
    layer: Layer = field(default=Layer.OBJECT, init=False, repr=False)


Node = FloorNode | RoomNode | AreaNode | ObjectNode


@dataclass(frozen=True)
class Edge:
    """A directed edge; ``props`` holds e.g. ``predicate``/``confidence`` or a door
    position. The identity of an edge is ``(kind, src, dst, predicate)``."""

    kind: EdgeKind
    src: str
    dst: str
    props: tuple[tuple[str, Any], ...] = ()

    @classmethod
    def make(cls, kind: EdgeKind, src: str, dst: str, **props: Any) -> Edge:
        """Build an edge with keyword properties."""
        return cls(kind, src, dst, tuple(sorted(props.items())))

    @property
    def key(self) -> tuple[str, str, str, str]:
        """Identity used by the scene graph: relations differ by predicate."""
        return (self.kind.value, self.src, self.dst, str(self.prop("predicate", "")))

    def prop(self, name: str, default: Any = None) -> Any:
        """Value of one property."""
        for k, v in self.props:
            if k == name:
                return v
        return default

    @property
    def prop_dict(self) -> dict[str, Any]:
        """Properties as a dict."""
        return dict(self.props)


@dataclass
class Keyframe:
    """A keyframe selected by the gate; its JPEG bytes live in LanceDB."""

    id: str
    session_id: str
    timestamp: float
    pose: Pose
    floor_id: str | None = None
    frame_index: int = 0
    global_feature: Vector | None = None
    jpeg: bytes | None = None
    width: int = 0
    height: int = 0


@dataclass
class Session:
    """One mapping run that appended to the map."""

    id: str
    name: str
    started: float
    finished: float | None = None
    dataset: str = ""
    frames: int = 0
    keyframes: int = 0
    # "" while it runs; "finished", "failed", or "interrupted" (killed before it ended)
    state: str = ""
