"""The house as one triangle mesh with a per-face instance id and albedo.

Walls are boxes with real gaps for doors and holes for windows, floor slabs have
stairwell openings, every storey has a ceiling, objects are built from the parts of
:mod:`inherit_sg.ingest.synthetic.shapes`. Walls, floors, ceilings and the ground outside are
background (instance 0) and are painted per room.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import trimesh

from inherit_sg.ingest.synthetic.geom import Rect, rect_minus
from inherit_sg.ingest.synthetic.paint import Painter
from inherit_sg.ingest.synthetic.placement import Placed
from inherit_sg.ingest.synthetic.plan import SLAB_T, WALL_T, FloorPlan, HousePlan, WallLine
from inherit_sg.ingest.synthetic.render_materials import material_code
from inherit_sg.ingest.synthetic.shapes import Part
from inherit_sg.ingest.synthetic.shapes_real import parts_for
from inherit_sg.ingest.synthetic.vocabulary import COLOURS

# Unit cube: 6 sides (-x, +x, -y, +y, -z, +z), two triangles each, outward winding.
_CUBE_V = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])
_CUBE_F = np.array(
    [
        [0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5],
        [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],
        [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3],
    ]
)  # fmt: skip
_SIDE_NORMALS = np.array(
    [[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]], float
)
_CYL = trimesh.creation.cylinder(radius=0.5, height=1.0, sections=14)
_BALL = trimesh.creation.icosphere(subdivisions=1, radius=0.5)
_CYL_V, _CYL_F = np.asarray(_CYL.vertices), np.asarray(_CYL.faces)
# Unit primitives by part kind: cylinders along z, y (a disc facing the front) and x.
_MESHES: dict[str, tuple[np.ndarray, np.ndarray]] = {
    "cyl": (_CYL_V, _CYL_F),
    "ycyl": (_CYL_V[:, [0, 2, 1]], _CYL_F),
    "xcyl": (_CYL_V[:, [2, 1, 0]], _CYL_F),
    "ball": (np.asarray(_BALL.vertices), np.asarray(_BALL.faces)),
}


def srgb_to_linear(rgb: np.ndarray) -> np.ndarray:
    """sRGB 0..255 to linear 0..1."""
    c = np.asarray(rgb, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


@dataclass
class WorldMesh:
    """Triangles with per-face attributes."""

    vertices: np.ndarray  # (V, 3) float64
    faces: np.ndarray  # (F, 3) int32
    instance: np.ndarray  # (F,) uint16, 0 = background
    albedo: np.ndarray  # (F, 3) float32 linear
    texture: np.ndarray  # (F,) float32 amplitude of the procedural texture
    material: np.ndarray | None = None  # (F,) uint8 material codes (render_materials)

    def to_trimesh(self) -> trimesh.Trimesh:
        """A trimesh with face colours (for inspection and export)."""
        colours = (np.clip(self.albedo, 0, 1) ** (1 / 2.2) * 255).astype(np.uint8)
        return trimesh.Trimesh(self.vertices, self.faces, face_colors=colours, process=False)


class _Builder:
    def __init__(self) -> None:
        self.v: list[np.ndarray] = []
        self.f: list[np.ndarray] = []
        self.inst: list[np.ndarray] = []
        self.rgb: list[np.ndarray] = []
        self.tex: list[np.ndarray] = []
        self.mat: list[np.ndarray] = []
        self.n = 0

    def add(
        self,
        verts: np.ndarray,
        faces: np.ndarray,
        inst: int,
        rgb: np.ndarray,
        tex: float,
        material: int = 0,
    ) -> None:
        self.v.append(verts)
        self.f.append(faces + self.n)
        self.n += len(verts)
        self.inst.append(np.full(len(faces), inst, dtype=np.uint16))
        self.rgb.append(np.broadcast_to(np.asarray(rgb, float), (len(faces), 3)))
        self.tex.append(np.full(len(faces), tex, dtype=np.float32))
        self.mat.append(np.full(len(faces), material, dtype=np.uint8))

    def box(
        self, lo: np.ndarray, hi: np.ndarray, inst: int, side_rgb: np.ndarray, tex: float
    ) -> None:
        verts = _CUBE_V * (hi - lo) + (hi + lo) / 2
        self.add(verts, _CUBE_F, inst, np.repeat(side_rgb, 2, axis=0), tex)

    def build(self) -> WorldMesh:
        return WorldMesh(
            vertices=np.concatenate(self.v),
            faces=np.concatenate(self.f).astype(np.int32),
            instance=np.concatenate(self.inst),
            albedo=srgb_to_linear(np.concatenate(self.rgb)).astype(np.float32),
            texture=np.concatenate(self.tex),
            material=np.concatenate(self.mat),
        )


def _rotate(points: np.ndarray, quarter: int) -> np.ndarray:
    for _ in range(quarter % 4):
        points = np.stack([-points[:, 1], points[:, 0], points[:, 2]], axis=1)
    return points


def _add_part(b: _Builder, obj: Placed, part: Part) -> None:
    own = obj.rgb if obj.rgb is not None else COLOURS[obj.colour]
    colour = np.asarray(part.rgb if part.rgb is not None else own, float)
    rgb = colour * (part.shade if part.rgb is None else 1.0)
    if part.prim == "box":
        verts, faces = _CUBE_V, _CUBE_F
    else:
        verts, faces = _MESHES[part.prim]
    local = verts * np.asarray(part.size) + np.asarray(part.center)
    world = _rotate(local, obj.quarter) + np.array([obj.x, obj.y, obj.z])
    # parts in their own colour (a lampshade, a screen) are not of the object's material
    if part.material is not None:
        code = material_code(part.material)
    else:
        code = material_code(obj.material) if part.rgb is None else 0
    b.add(world, faces, obj.instance_id, rgb, 0.06, code)


def _paint_box(b: _Builder, paint: Painter, lo: np.ndarray, hi: np.ndarray) -> None:
    """A background box whose sides take the colour of the room each faces."""
    centre, half = (lo + hi) / 2, (hi - lo) / 2
    sides = np.array([paint.colour(centre + n * half, n) for n in _SIDE_NORMALS], float)
    b.box(lo, hi, 0, sides, 0.025)


def _wall_boxes(wall: WallLine, floor: FloorPlan) -> list[tuple[np.ndarray, np.ndarray]]:
    holes = [
        o for o in floor.doors + floor.windows
        if o.axis == wall.axis and abs(o.coord - wall.coord) < 1e-6 and o.lo < wall.hi and o.hi > wall.lo
    ]  # fmt: skip
    t = WALL_T / 2
    spans: list[tuple[float, float, float, float]] = []  # along lo, hi, z0, z1 (relative)
    cuts = sorted((o.lo, o.hi) for o in holes)
    edges = [wall.lo - t] + [c for lo_hi in cuts for c in lo_hi] + [wall.hi + t]
    for a, c in zip(edges[::2], edges[1::2], strict=True):
        if c - a > 1e-6:
            spans.append((a, c, 0.0, floor.height))
    for o in holes:
        spans.append((o.lo, o.hi, o.z1, floor.height))
        if o.z0 > 0:
            spans.append((o.lo, o.hi, 0.0, o.z0))
    out = []
    for a, c, z0, z1 in spans:
        if z1 - z0 < 1e-6:
            continue
        if wall.axis == "x":
            lo, hi = [a, wall.coord - t, floor.z + z0], [c, wall.coord + t, floor.z + z1]
        else:
            lo, hi = [wall.coord - t, a, floor.z + z0], [wall.coord + t, c, floor.z + z1]
        out.append((np.array(lo), np.array(hi)))
    return out


def _slab(
    b: _Builder, paint: Painter, outline: Rect, holes: list[Rect], z0: float, z1: float
) -> None:
    pieces = [outline]
    for hole in holes:
        pieces = [p for piece in pieces for p in rect_minus(piece, hole)]
    for p in pieces:
        _paint_box(b, paint, np.array([p.x0, p.y0, z0]), np.array([p.x1, p.y1, z1]))


def build_world(plan: HousePlan, objects: list[Placed], rng: np.random.Generator) -> WorldMesh:
    """Triangulate the building and its objects."""
    b = _Builder()
    paint = Painter(plan, rng)
    outline = plan.footprint.grown(WALL_T / 2)
    for floor in plan.floors:
        for wall in floor.walls:
            for lo, hi in _wall_boxes(wall, floor):
                _paint_box(b, paint, lo, hi)
        _slab(b, paint, outline, floor.holes, floor.z - SLAB_T, floor.z)
    top = plan.floors[-1]
    roof = top.z + top.height
    _slab(b, paint, outline, [], roof, roof + SLAB_T)
    ground = plan.footprint.grown(40.0)
    _paint_box(
        b,
        paint,
        np.array([ground.x0, ground.y0, -SLAB_T - 0.05]),
        np.array([ground.x1, ground.y1, -0.02]),
    )
    for obj in objects:
        for part in parts_for(obj.label, obj.dims, obj.params):
            _add_part(b, obj, part)
    return b.build()
