"""Matterport3D ``.house`` files (ASCII 1.1) → ground-truth :class:`Scene`.

A real Matterport layout becomes a world the renderer can walk through: levels become
floors, regions become rooms (floor polygons from their ``S``/``V`` surface lines, type
from the region label code), and ``O`` lines become objects (oriented boxes, labelled by
their ``C`` category). Coordinates stay as in the file: MP3D houses are already z-up
metres, so positions compare directly with the source's own annotations.

Line layouts used here (first token, then fields by position):
``L`` level: index, n_regions, label, position xyz, bbox min xyz, bbox max xyz.
``R`` region: index, level, 0, 0, label code, position xyz, bbox min xyz, bbox max xyz, height.
``S`` surface: index, region, 0, label, position xyz, normal xyz, bbox min xyz, bbox max xyz.
``V`` vertex: index, surface, label, position xyz, normal xyz.
``C`` category: index, mapping index, mapping name, mpcat40 index, mpcat40 name.
``O`` object: index, region, category, centre xyz, axis0 xyz, axis1 xyz, radii xyz.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ingest.synthetic.scene import FloorGT, ObjectGT, RoomGT, Scene
from inherit_sg.errors import DatasetError

# Region label codes of the MP3D annotation format.
REGION_TYPES: dict[str, str] = {
    "a": "bathroom",
    "b": "bedroom",
    "c": "closet",
    "d": "dining room",
    "e": "entryway",
    "f": "family room",
    "g": "garage",
    "h": "hallway",
    "i": "library",
    "j": "laundry room",
    "k": "kitchen",
    "l": "living room",
    "m": "meeting room",
    "n": "lounge",
    "o": "office",
    "p": "porch",
    "r": "game room",
    "s": "stairs",
    "t": "toilet",
    "u": "utility room",
    "v": "tv room",
    "w": "gym",
    "x": "outdoor",
    "y": "balcony",
    "z": "room",
    "B": "bar",
    "C": "classroom",
    "D": "dining booth",
    "S": "spa",
    "T": "transportation",
    "-": "room",
}

# Categories that are the building itself (rendered as background) or annotation debris.
STRUCTURE = {"wall", "floor", "ceiling", "remove", "delete", "unknown", "void", "misc", "objects"}
DOOR_WORDS = {"door", "doorframe", "door frame", "doorway"}


@dataclass(frozen=True)
class OrientedBox:
    """An MP3D object box: centre, two unit axes (the third is their cross) and half sizes."""

    center: np.ndarray
    axes: np.ndarray  # (3, 3) rows are unit axes
    radii: np.ndarray

    def corners(self) -> np.ndarray:
        """(8, 3) corner points."""
        signs = np.array(
            [[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float
        )
        return self.center + (signs * self.radii) @ self.axes


@dataclass
class HouseFile:
    """Parsed ``.house`` content needed to build a scene and a world."""

    scene: Scene
    boxes: dict[str, OrientedBox]  # object id -> oriented box
    region_heights: dict[str, float]  # room id -> ceiling height above its floor
    region_floor_z: dict[str, float] = field(default_factory=dict)  # room id -> floor height


def _floats(parts: list[str], start: int, n: int) -> np.ndarray:
    return np.array([float(v) for v in parts[start : start + n]], dtype=float)


def parse_house(path: str | Path) -> HouseFile:
    """Parse a ``.house`` file; DatasetError names the line that is malformed."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8", errors="strict")
    except FileNotFoundError:
        raise DatasetError(f"MP3D house file not found: {p}") from None
    except UnicodeDecodeError:
        raise DatasetError(f"{p}: not an ASCII .house file") from None
    lines = text.splitlines()
    if not lines or not lines[0].startswith("ASCII"):
        raise DatasetError(f"{p}: not an MP3D .house file (first line should be 'ASCII 1.1')")

    levels: dict[int, np.ndarray] = {}
    regions: dict[int, tuple[int, str, np.ndarray, np.ndarray, float]] = {}
    surface_region: dict[int, int] = {}
    surface_vertices: dict[int, list[np.ndarray]] = defaultdict(list)
    categories: dict[int, str] = {}
    objects: list[tuple[int, int, int, np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []
    for lineno, line in enumerate(lines[1:], 2):
        parts = line.split()
        if not parts:
            continue
        try:
            tag = parts[0]
            if tag == "L":
                levels[int(parts[1])] = _floats(parts, 7, 6)
            elif tag == "R":
                bbox = _floats(parts, 9, 6)
                regions[int(parts[1])] = (
                    int(parts[2]),
                    parts[5],
                    bbox[:3],
                    bbox[3:],
                    float(parts[15]),
                )
            elif tag == "S":
                surface_region[int(parts[1])] = int(parts[2])
            elif tag == "V":
                surface_vertices[int(parts[2])].append(_floats(parts, 4, 3))
            elif tag == "C":
                categories[int(parts[1])] = parts[3].replace("#", " ")
            elif tag == "O":
                objects.append(
                    (
                        int(parts[1]),
                        int(parts[2]),
                        int(parts[3]),
                        _floats(parts, 4, 3),
                        _floats(parts, 7, 3),
                        _floats(parts, 10, 3),
                        _floats(parts, 13, 3),
                    )
                )
        except (IndexError, ValueError):
            raise DatasetError(f"{p}:{lineno}: malformed {parts[0]!r} line") from None
    if not regions:
        raise DatasetError(f"{p}: no regions (R lines)")

    scene = Scene(name=p.stem, seed=None)
    level_order = sorted(levels, key=lambda i: levels[i][2]) or sorted(
        {r[0] for r in regions.values()}
    )
    level_index = {lvl: i for i, lvl in enumerate(level_order)}
    for lvl in level_order:
        lo_z = float(levels[lvl][2]) if lvl in levels else 0.0
        hi_z = float(levels[lvl][5]) if lvl in levels else lo_z + 2.5
        scene.floors.append(FloorGT(index=level_index[lvl], z=lo_z, height=max(hi_z - lo_z, 2.0)))

    polygons: dict[int, list[list[float]]] = {}
    for surface, region in surface_region.items():
        verts = surface_vertices.get(surface, [])
        if len(verts) >= 3:
            polygons.setdefault(region, [[float(v[0]), float(v[1])] for v in verts])
    counts: dict[str, int] = defaultdict(int)
    heights: dict[str, float] = {}
    floor_z: dict[str, float] = {}
    for index in sorted(regions):
        level, code, lo, hi, height = regions[index]
        rtype = REGION_TYPES.get(code, "room")
        counts[rtype] += 1
        polygon = polygons.get(
            index, [[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]]
        )
        room_id = f"r{index}"
        scene.rooms.append(
            RoomGT(
                id=room_id,
                type=rtype,
                floor=level_index.get(level, 0),
                polygon=[[float(x), float(y)] for x, y in polygon],
                name=rtype if counts[rtype] == 1 else f"{rtype} {counts[rtype]}",
            )
        )
        heights[room_id] = height if height > 0 else float(hi[2] - lo[2])
        floor_z[room_id] = float(lo[2])

    boxes: dict[str, OrientedBox] = {}
    for index, region, category, center, a0, a1, radii in objects:
        label = categories.get(category, "")
        if not label or label in STRUCTURE or region not in regions:
            continue
        axis0 = a0 / (np.linalg.norm(a0) or 1.0)
        axis1 = a1 / (np.linalg.norm(a1) or 1.0)
        box = OrientedBox(center, np.stack([axis0, axis1, np.cross(axis0, axis1)]), np.abs(radii))
        corners = box.corners()
        obj_id = f"o{index}"
        is_door = label in DOOR_WORDS
        scene.objects.append(
            ObjectGT(
                id=obj_id,
                instance_id=len(scene.objects) + 1,
                label="door" if is_door else label,
                room_id=f"r{region}",
                floor=level_index.get(regions[region][0], 0),
                centroid=[float(v) for v in center],
                bbox_min=[float(v) for v in corners.min(axis=0)],
                bbox_max=[float(v) for v in corners.max(axis=0)],
                attributes={"mp3d_category": label, "mp3d_index": index},
                structural=is_door,
            )
        )
        boxes[obj_id] = box
    return HouseFile(scene=scene, boxes=boxes, region_heights=heights, region_floor_z=floor_z)
