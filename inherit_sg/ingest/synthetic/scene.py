"""Ground-truth scene description (``scene.json``) shared by the house generator, the
renderer, the query generator, the MP3D reader and the evaluation code.

Ground truth is for evaluation only: nothing in mapping or retrieval may read it.
All coordinates are world frame, z up, metres.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from inherit_sg.errors import DatasetError

SCENE_FILE = "scene.json"
SCENE_FORMAT_VERSION = 1

Vec3 = list[float]
Polygon = list[list[float]]  # [[x, y], ...] counter-clockwise, not closed


@dataclass
class FloorGT:
    """One storey: index 0 is the lowest; floor surface at ``z`` and ceiling at ``z + height``."""

    index: int
    z: float
    height: float


@dataclass
class RoomGT:
    """A room with its type (``kitchen``, ``bedroom``, …) and floor polygon."""

    id: str
    type: str
    floor: int
    polygon: Polygon
    name: str = ""  # e.g. "kitchen", "bedroom 2"
    # Source annotations, for readers of real layouts (added with a default so older
    # scene.json files load): e.g. an MP3D region's label code and category name
    # ({"mp3d_code": "v", "mp3d_category": "tv", "mp3d_index": 4}). Generated houses of
    # the default style give the type's "mp3d_code" and, for the rooms of an open-plan
    # space, "open_group" and "open_to" (the rooms it joins without a wall); classic ones
    # none.
    attributes: dict[str, Any] = field(default_factory=dict)


@dataclass
class AreaGT:
    """A functional area: a group of objects serving one function inside a room."""

    id: str
    label: str  # e.g. "sleeping area", "dining area"
    room_id: str
    object_ids: list[str] = field(default_factory=list)


@dataclass
class DoorGT:
    """A door opening (a real gap in a wall) between two rooms, or room and outside."""

    id: str
    floor: int
    position: Vec3  # centre of the opening at floor height
    width: float
    rooms: list[str]  # one or two room ids


@dataclass
class StairsGT:
    """A staircase from ``from_floor`` up to ``from_floor + 1``."""

    id: str
    from_floor: int
    bottom: Vec3
    top: Vec3
    footprint: Polygon


@dataclass
class ObjectGT:
    """An object instance; ``instance_id`` is its value in rendered instance images."""

    id: str
    instance_id: int
    label: str
    room_id: str | None
    floor: int
    centroid: Vec3
    bbox_min: Vec3
    bbox_max: Vec3
    area_id: str | None = None
    # colour, material, size; generated houses of the default style add "rgb" (the
    # sampled colour, "colour" being its basic term), "mp3d_category" and "mpcat40"
    attributes: dict[str, Any] = field(default_factory=dict)
    supported_by: str | None = None  # id of the object it stands on ("on")
    structural: bool = False  # door frames, windows: objects, but part of the building


@dataclass
class Scene:
    """The whole ground truth of one house."""

    name: str
    seed: int | None
    floors: list[FloorGT] = field(default_factory=list)
    rooms: list[RoomGT] = field(default_factory=list)
    areas: list[AreaGT] = field(default_factory=list)
    objects: list[ObjectGT] = field(default_factory=list)
    doors: list[DoorGT] = field(default_factory=list)
    stairs: list[StairsGT] = field(default_factory=list)
    version: int = SCENE_FORMAT_VERSION

    def object(self, object_id: str) -> ObjectGT:
        """The object with ``object_id`` (KeyError if absent)."""
        for obj in self.objects:
            if obj.id == object_id:
                return obj
        raise KeyError(object_id)

    def room(self, room_id: str) -> RoomGT:
        """The room with ``room_id`` (KeyError if absent)."""
        for room in self.rooms:
            if room.id == room_id:
                return room
        raise KeyError(room_id)

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Scene:
        """Inverse of :meth:`to_dict`."""
        try:
            return cls(
                name=data["name"],
                seed=data.get("seed"),
                floors=[FloorGT(**f) for f in data.get("floors", [])],
                rooms=[RoomGT(**r) for r in data.get("rooms", [])],
                areas=[AreaGT(**a) for a in data.get("areas", [])],
                objects=[ObjectGT(**o) for o in data.get("objects", [])],
                doors=[DoorGT(**d) for d in data.get("doors", [])],
                stairs=[StairsGT(**s) for s in data.get("stairs", [])],
                version=int(data.get("version", SCENE_FORMAT_VERSION)),
            )
        except (KeyError, TypeError) as exc:
            raise DatasetError(f"malformed scene description: {exc}") from None

    def save(self, folder: str | Path) -> Path:
        """Write ``scene.json`` into ``folder``."""
        path = Path(folder) / SCENE_FILE
        path.write_text(json.dumps(self.to_dict(), indent=1), encoding="utf-8")
        return path

    @classmethod
    def load(cls, folder_or_file: str | Path) -> Scene:
        """Read ``scene.json`` from a folder or a file path."""
        path = Path(folder_or_file)
        if path.is_dir():
            path = path / SCENE_FILE
        try:
            return cls.from_dict(json.loads(path.read_text(encoding="utf-8")))
        except FileNotFoundError:
            raise DatasetError(f"no ground truth: {path} not found") from None
        except (json.JSONDecodeError, UnicodeDecodeError) as exc:
            raise DatasetError(f"{path}: invalid JSON: {exc}") from None
