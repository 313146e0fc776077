"""Matterport3D ``.house`` files (ASCII 1.1) → ground-truth :class:`Scene`.

A real Matterport layout becomes a world the renderer can walk through: levels become
floors, every region becomes a room (floor polygon from its ``S``/``V`` surface lines,
readable type from its label code, the code and the MP3D category name kept in the
room's ``attributes``), and ``O`` lines become objects (oriented boxes labelled by their
raw ``C`` category; ``attributes`` keep the raw name, the mpcat40 class and the line's
index). Walls, floors, ceilings, junk segments and unnamed leftovers are not objects:
they are listed in :attr:`HouseFile.skipped` with the reason. Coordinates stay as in the
file: MP3D houses are already z-up metres, so positions compare directly with the
source's own annotations.

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

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.synthetic.scene import FloorGT, ObjectGT, RoomGT, Scene

# Region label codes of the MP3D annotation format: code -> (readable type, the
# category as the Matterport3D documentation names it). Every region becomes a room of
# the ground truth with its readable type; the code and the category are kept in the
# room's attributes.
REGIONS: dict[str, tuple[str, str]] = {
    "a": ("bathroom", "bathroom"),
    "b": ("bedroom", "bedroom"),
    "c": ("closet", "closet"),
    "d": ("dining room", "dining room"),
    "e": ("entryway", "entryway/foyer/lobby"),
    "f": ("family room", "familyroom"),
    "g": ("garage", "garage"),
    "h": ("hallway", "hallway"),
    "i": ("library", "library"),
    "j": ("laundry room", "laundryroom/mudroom"),
    "k": ("kitchen", "kitchen"),
    "l": ("living room", "living room"),
    "m": ("meeting room", "meetingroom/conferenceroom"),
    "n": ("lounge", "lounge"),
    "o": ("office", "office"),
    "p": ("porch", "porch/terrace/deck/driveway"),
    "r": ("game room", "rec/game"),
    "s": ("stairs", "stairs"),
    "t": ("toilet", "toilet"),
    "u": ("utility room", "utilityroom/toolroom"),
    "v": ("tv room", "tv"),
    "w": ("gym", "workout/gym/exercise"),
    "x": ("outdoor", "outdoor"),
    "y": ("balcony", "balcony"),
    "z": ("room", "other room"),
    "B": ("bar", "bar"),
    "C": ("classroom", "classroom"),
    "D": ("dining booth", "dining booth"),
    "S": ("spa", "spa/sauna"),
    "T": ("transportation", "transportation"),
    "Z": ("junk", "junk"),
    "-": ("room", "no label"),
}
REGION_TYPES: dict[str, str] = {code: rtype for code, (rtype, _) in REGIONS.items()}

# Raw categories (the ``C`` lines' mapping names) that are not objects of the ground truth:
# the building itself (walls, floors and ceilings are drawn from the region outlines),
# segments the annotators marked as junk ("remove", "delete": mpcat40 ``void``) and
# unnamed leftovers ("unknown": mostly one room-sized box per region). ``O`` lines with
# no category (index -1) are skipped too. See :attr:`HouseFile.skipped`.
STRUCTURE = {"wall", "floor", "ceiling"}
JUNK = {"remove", "delete", "void"}
UNNAMED = {"unknown", ""}
DOOR_WORDS = {"door", "doorframe", "door frame", "doorway"}


@dataclass(frozen=True)
class Category:
    """One ``C`` line: the raw annotator name (``#`` read as a space) and its mpcat40 class."""

    raw: str
    mpcat40: str
    mpcat40_index: int


@dataclass(frozen=True)
class SkippedObject:
    """An ``O`` line that is not an object of the ground truth, and why (``structure``,
    ``junk``, ``unnamed``, ``no category`` or ``no region``)."""

    index: int
    region: int
    raw: str
    mpcat40: str
    reason: str


def skip_reason(raw: str, has_category: bool = True) -> str | None:
    """Why an object of raw category ``raw`` is not kept (None when it is kept)."""
    if not has_category:
        return "no category"
    if raw in STRUCTURE:
        return "structure"
    if raw in JUNK:
        return "junk"
    if raw in UNNAMED:
        return "unnamed"
    return None


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
    skipped: list[SkippedObject] = field(default_factory=list)  # O lines left out, with why


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
    categories: dict[int, Category] = {}
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
                categories[int(parts[1])] = Category(
                    parts[3].replace("#", " "), parts[5].replace("#", " "), int(parts[4])
                )
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
        rtype, region_category = REGIONS.get(code, ("room", f"unknown code {code}"))
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
                attributes={
                    "mp3d_code": code,
                    "mp3d_category": region_category,
                    "mp3d_index": index,
                },
            )
        )
        heights[room_id] = height if height > 0 else float(hi[2] - lo[2])
        floor_z[room_id] = float(lo[2])

    boxes: dict[str, OrientedBox] = {}
    skipped: list[SkippedObject] = []
    for index, region, category, center, a0, a1, radii in objects:
        cat = categories.get(category)
        raw = cat.raw if cat is not None else ""
        mpcat40 = cat.mpcat40 if cat is not None else ""
        reason = skip_reason(raw, cat is not None)
        if reason is None and region not in regions:
            reason = "no region"
        if reason is not None:
            skipped.append(SkippedObject(index, region, raw, mpcat40, reason))
            continue
        assert cat is not None
        axis0 = a0 / (np.linalg.norm(a0) or 1.0)
        axis1 = a1 / (np.linalg.norm(a1) or 1.0)
        box = OrientedBox(center, np.stack([axis0, axis1, np.cross(axis0, axis1)]), np.abs(radii))
        corners = box.corners()
        obj_id = f"o{index}"
        is_door = raw in DOOR_WORDS
        scene.objects.append(
            ObjectGT(
                id=obj_id,
                instance_id=len(scene.objects) + 1,
                label="door" if is_door else raw,
                room_id=f"r{region}",
                floor=level_index.get(regions[region][0], 0),
                centroid=[float(v) for v in center],
                bbox_min=[float(v) for v in corners.min(axis=0)],
                bbox_max=[float(v) for v in corners.max(axis=0)],
                attributes={
                    "mp3d_category": raw,
                    "mp3d_index": index,
                    "mpcat40": cat.mpcat40,
                    "mpcat40_index": cat.mpcat40_index,
                },
                structural=is_door,
            )
        )
        boxes[obj_id] = box
    return HouseFile(
        scene=scene,
        boxes=boxes,
        region_heights=heights,
        region_floor_z=floor_z,
        skipped=skipped,
    )
