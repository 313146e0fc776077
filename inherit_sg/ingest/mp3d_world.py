"""An MP3D house as a renderable :class:`WorldMesh`, in the file's own coordinates.

* floors: each region's outline, ear-clipped, at the region's floor height; ceilings the
  same triangles at the region's ceiling; a slab under and a roof over each level so
  nothing shows through the seams between regions;
* walls: the pieces planned by :mod:`inherit_sg.ingest.mp3d_walls` (gaps at doors and open plans,
  lintels above them), as thin boxes just outside each region's outline;
* objects: the boxes :mod:`inherit_sg.ingest.mp3d_drawn` decides (8 corners, 12 triangles each)
  with the object's instance id: the file's oriented box, flattened for floor coverings,
  kept under the ceiling, extended to stand proud of a box that buries it; doors are
  rendered as frames (two jambs and a head) so their gap stays passable.

Colours are stable: one named colour per category (from the synthetic vocabulary, so the
ground truth can say "the grey couch"), varied slightly per object; walls, floors and
ceilings take the synthetic houses' paints, chosen per region.
"""

from __future__ import annotations

import zlib

import numpy as np

from inherit_sg.ingest.mp3d_drawn import Drawn, drawn_objects
from inherit_sg.ingest.mp3d_house import HouseFile
from inherit_sg.ingest.mp3d_polygons import rasterise, triangulate
from inherit_sg.ingest.mp3d_space import Level, LevelSpace
from inherit_sg.ingest.mp3d_walls import WALL_T, WallPlan, WallSpan
from inherit_sg.ingest.synthetic.geom import Rect
from inherit_sg.ingest.synthetic.grid import Grid
from inherit_sg.ingest.synthetic.paint import CEILING, FACADE, FLOOR_FINISH, WALL_PAINTS, WOODS
from inherit_sg.ingest.synthetic.render import RoomLights
from inherit_sg.ingest.synthetic.vocabulary import COLOURS, OBJECT_KINDS
from inherit_sg.ingest.synthetic.world import _CUBE_F, WorldMesh, srgb_to_linear

SLAB_T = 0.1
LIGHT_RES = 0.05
OBJECT_TEXTURE, BACKGROUND_TEXTURE = 0.06, 0.025


def _hash(text: str) -> int:
    return zlib.crc32(text.encode("utf-8"))


def colour_name(label: str) -> str:
    """The stable colour name of an object category."""
    kind = OBJECT_KINDS.get(label)
    names = kind.colours if kind is not None else tuple(COLOURS)
    return names[_hash(label) % len(names)]


def object_rgb(label: str, object_id: str) -> np.ndarray:
    """sRGB albedo of one object: its category's colour, a few percent lighter or darker."""
    shade = 0.92 + 0.16 * ((_hash(object_id) % 1000) / 999.0)
    return np.clip(np.asarray(COLOURS[colour_name(label)], float) * shade, 0, 255)


class _Mesh:
    """Accumulates triangles with per-face instance id, sRGB colour and texture amplitude."""

    def __init__(self) -> None:
        self.v: list[np.ndarray] = []
        self.f: list[np.ndarray] = []
        self.inst: list[int] = []
        self.rgb: list[np.ndarray] = []
        self.tex: list[float] = []
        self.n = 0

    def add(self, verts: np.ndarray, faces: np.ndarray, inst: int, rgb: object, tex: float) -> None:
        self.v.append(np.asarray(verts, float))
        self.f.append(faces + self.n)
        self.n += len(verts)
        self.inst += [inst] * len(faces)
        self.rgb += [np.asarray(rgb, float)] * len(faces)
        self.tex += [tex] * len(faces)

    def box(self, corners: np.ndarray, inst: int, rgb: object, tex: float) -> None:
        """A box from its 8 corners in ``OrientedBox.corners`` order."""
        self.add(corners, _CUBE_F, inst, rgb, tex)

    def build(self) -> WorldMesh:
        return WorldMesh(
            vertices=np.concatenate(self.v),
            faces=np.concatenate(self.f).astype(np.int32),
            instance=np.array(self.inst, dtype=np.uint16),
            albedo=srgb_to_linear(np.array(self.rgb)).astype(np.float32),
            texture=np.array(self.tex, dtype=np.float32),
        )


def _axis_box(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    return np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )


def _wall_corners(w: WallSpan) -> np.ndarray:
    out = w.normal * WALL_T
    plan = [w.a, w.a + out, w.b, w.b + out]  # (along, across) in corner order
    return np.array([[*plan[2 * i + j], z] for i in (0, 1) for j in (0, 1) for z in (w.z0, w.z1)])


def _region_paint(room_id: str, room_type: str) -> tuple[np.ndarray, np.ndarray]:
    h = _hash(room_id)
    wall = np.asarray(WALL_PAINTS[h % len(WALL_PAINTS)], float)
    floor = FLOOR_FINISH.get(room_type, WOODS[(h // 7) % len(WOODS)])
    return wall, np.asarray(floor, float)


def _level(mesh: _Mesh, house: HouseFile, level: Level) -> None:
    types = {r.id: r.type for r in level.rooms}
    for room_id, outline in level.outlines.items():
        _, floor_rgb = _region_paint(room_id, types[room_id])
        tris = triangulate(outline)
        z = house.region_floor_z.get(room_id, level.z)
        for height, rgb in ((z, floor_rgb), (level.ceilings[room_id], CEILING)):
            verts = np.column_stack([outline, np.full(len(outline), height)])
            mesh.add(verts, tris, 0, rgb, BACKGROUND_TEXTURE)
    b = level.bounds(0.3)
    low = min(house.region_floor_z.get(r, level.z) for r in level.outlines) - 0.015
    top = max(level.ceilings.values()) + 0.02
    for z0, rgb in ((low - SLAB_T, FACADE), (top, CEILING)):
        lo, hi = np.array([b.x0, b.y0, z0]), np.array([b.x1, b.y1, z0 + SLAB_T])
        mesh.box(_axis_box(lo, hi), 0, rgb, BACKGROUND_TEXTURE)


def build_house_world(
    house: HouseFile, levels: list[Level], walls: WallPlan, drawn: dict[str, Drawn] | None = None
) -> WorldMesh:
    """Triangulate regions, walls and object boxes of a parsed house; ``drawn`` says how
    each object is drawn (default: :func:`inherit_sg.ingest.mp3d_drawn.drawn_objects`)."""
    if drawn is None:
        drawn = drawn_objects(house, levels, [LevelSpace(house, lv) for lv in levels], walls)
    mesh = _Mesh()
    for level in levels:
        _level(mesh, house, level)
    types = {r.id: r.type for r in house.scene.rooms}
    for wall in walls.walls:
        wall_rgb, _ = _region_paint(wall.room_id, types[wall.room_id])
        mesh.box(_wall_corners(wall), 0, wall_rgb, BACKGROUND_TEXTURE)
    for obj in house.scene.objects:
        if obj.id not in drawn:
            continue
        rgb = object_rgb(obj.label, obj.id)
        for part in drawn[obj.id].parts:
            mesh.box(part.corners(), obj.instance_id, rgb, OBJECT_TEXTURE)
    return mesh.build()


def house_lights(levels: list[Level]) -> RoomLights:
    """One ceiling light per region, 0.3 m below its ceiling above the outline's centre."""
    pts = np.concatenate([o for lv in levels for o in lv.outlines.values()])
    lo, hi = pts.min(axis=0) - 0.5, pts.max(axis=0) + 0.5
    grid = Grid(Rect(float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])), LIGHT_RES)
    rooms = [(k, room_id) for k, lv in enumerate(levels) for room_id in lv.outlines]
    pos = np.zeros((len(rooms) + 1, 3))
    pos[-1] = ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, 1e3)
    raster = np.full((len(levels), *grid.shape), len(rooms), dtype=np.int32)
    for index, (k, room_id) in enumerate(rooms):
        outline = levels[k].outlines[room_id]
        pos[index] = (*outline.mean(axis=0), levels[k].ceilings[room_id] - 0.3)
        raster[k][rasterise(grid, outline)] = index
    floor_z = np.array([lv.z for lv in levels])
    return RoomLights(grid, floor_z, raster, pos)
