"""Ray-casting RGB-D renderer over a :class:`WorldMesh` (Embree through ``embreex``).

One primary ray per pixel gives the hit triangle and distance: depth is the z-depth
along the camera axis (0 where nothing is hit within ``max_range``), the instance image
is the hit face's instance id. Colour is Lambertian shading of the face albedo under a
point light at the ceiling of the room the hit point is in, a weak sky light and an
ambient term, with a small procedural texture so flat-coloured objects vary across
their surface, and a material look per object part (grain, weave, speckle, specular
sheen, reflections of the room on metal, glass and glaze:
:mod:`inherit_sg.ingest.synthetic.render_materials`); optional shadow rays darken what the room
light cannot see.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh

from inherit_sg.ingest.synthetic.grid import Grid
from inherit_sg.ingest.synthetic.plan import HousePlan
from inherit_sg.ingest.synthetic.render_materials import finish, pattern, specular
from inherit_sg.ingest.synthetic.world import WorldMesh
from inherit_sg.model import Intrinsics, Pose

SKY_DIR = np.array([0.35, -0.25, 0.9]) / np.linalg.norm([0.35, -0.25, 0.9])
SKY_RGB = np.array([0.45, 0.62, 0.9], dtype=np.float32)
AMBIENT = 0.22
SKY_LIGHT = 0.18
LAMP = 1.25
LAMP_FALLOFF = 3.0  # metres at which the lamp's light has halved


@dataclass
class RenderResult:
    """One rendered view."""

    rgb: np.ndarray  # (H, W, 3) uint8
    depth: np.ndarray  # (H, W) float32 metres
    instances: np.ndarray  # (H, W) uint16


def _srgb_table() -> np.ndarray:
    lin = np.arange(4096, dtype=np.float64) / 4095.0
    enc = np.where(lin <= 0.0031308, lin * 12.92, 1.055 * lin ** (1 / 2.4) - 0.055)
    return np.round(enc * 255).astype(np.uint8)


_SRGB = _srgb_table()


def _encode_srgb(linear: np.ndarray) -> np.ndarray:
    """Linear 0..1 to sRGB uint8 through a 4096-entry table."""
    idx = np.clip(linear * np.float32(4095.0) + np.float32(0.5), 0, 4095).astype(np.int32)
    return np.asarray(_SRGB[idx])


@dataclass
class RoomLights:
    """One ceiling light per room, looked up from a room raster per storey (world frame).

    ``raster[floor, i, j]`` is the index into ``pos`` of the room covering cell (i, j) of
    ``grid`` on that storey; the last row of ``pos`` is the weak "outside" light. A point
    belongs to the highest storey whose floor height ``floor_z`` it is above.
    """

    grid: Grid
    floor_z: np.ndarray  # (floors,) storey floor heights, ascending
    raster: np.ndarray  # (floors, rows, cols) int32
    pos: np.ndarray  # (rooms + 1, 3) light positions, last = outside

    @property
    def outside(self) -> int:
        """Index of the outside light."""
        return len(self.pos) - 1

    def room_index(self, points: np.ndarray) -> np.ndarray:
        """Index into ``pos`` of the room each point lies in (``outside`` if none)."""
        g = self.grid
        floor = np.zeros(len(points), dtype=np.intp)
        for z in self.floor_z[1:]:
            floor += points[:, 2] >= z - 0.02
        rows, cols = g.shape
        i = np.floor((points[:, 1] - g.bounds.y0) / g.res + 0.5).astype(np.intp)
        j = np.floor((points[:, 0] - g.bounds.x0) / g.res + 0.5).astype(np.intp)
        inside = (i >= 0) & (i < rows) & (j >= 0) & (j < cols)
        np.clip(i, 0, rows - 1, out=i)
        np.clip(j, 0, cols - 1, out=j)
        return np.where(inside, self.raster[floor, i, j], self.outside)


def plan_lights(plan: HousePlan) -> RoomLights:
    """The lights of a generated house: one per room, 0.3 m under its storey's ceiling."""
    grid = Grid(plan.footprint, 0.1)
    rooms = plan.all_rooms
    pos = np.zeros((len(rooms) + 1, 3))
    pos[-1] = (plan.footprint.cx, plan.footprint.cy, 1e3)
    raster = np.full((len(plan.floors), *grid.shape), len(rooms), dtype=np.int32)
    for k, room in enumerate(rooms):
        floor = plan.floors[room.floor]
        pos[k] = (room.rect.cx, room.rect.cy, floor.z + floor.height - 0.3)
        cells = np.zeros(grid.shape, dtype=bool)
        grid.fill(cells, room.rect)
        raster[room.floor][cells] = k
    return RoomLights(grid, np.array([f.z for f in plan.floors]), raster, pos)


class Renderer:
    """Renders RGB, depth and instance images of a world for camera poses.

    ``plan`` gives the room lights: a generated house's plan, or :class:`RoomLights`
    built for any other world (e.g. an MP3D house).
    """

    def __init__(
        self,
        world: WorldMesh,
        plan: HousePlan | RoomLights,
        intrinsics: Intrinsics,
        *,
        max_range: float = 10.0,
        shadows: bool = False,
    ) -> None:
        self.world = world
        self.intrinsics = intrinsics
        self.max_range = max_range
        self.shadows = shadows
        self._origin = world.vertices.min(axis=0)
        self._scene = rtcore_scene.EmbreeScene()
        verts = (world.vertices - self._origin).astype(np.float32)
        TriangleMesh(scene=self._scene, vertices=verts, indices=world.faces.astype(np.int32))
        v = world.vertices[world.faces]
        normals = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
        lengths = np.linalg.norm(normals, axis=1, keepdims=True)
        self._normals = (normals / np.maximum(lengths, 1e-12)).astype(np.float32)
        self._lights = plan if isinstance(plan, RoomLights) else plan_lights(plan)
        self._light_pos = (self._lights.pos - self._origin).astype(np.float32)
        self._sky_dir = SKY_DIR.astype(np.float32)
        self._origin32 = self._origin.astype(np.float32)
        k = intrinsics
        u, w = np.meshgrid(np.arange(k.width), np.arange(k.height))
        rays = np.stack([(u - k.cx) / k.fx, (w - k.cy) / k.fy, np.ones(u.shape)], axis=-1)
        rays = rays.reshape(-1, 3)
        self._rays = (rays / np.linalg.norm(rays, axis=1, keepdims=True)).astype(np.float32)
        self._ray_z = self._rays[:, 2].copy()

    def _cast(self, origins: np.ndarray, dirs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """First hit (face index, -1 for none) and distance of rays in shifted coordinates."""
        hits = self._scene.run(
            np.ascontiguousarray(origins, dtype=np.float32),
            np.ascontiguousarray(dirs, dtype=np.float32),
            output=1,
        )
        return np.asarray(hits["primID"]), np.asarray(hits["tfar"], dtype=np.float32)

    def render(self, pose: Pose) -> RenderResult:
        """Render the view from camera pose ``pose`` (T_world_camera)."""
        k = self.intrinsics
        n = k.width * k.height
        dirs = _rotate(self._rays, pose.rotation.astype(np.float32))
        centre = (pose.translation - self._origin).astype(np.float32)
        origins = np.empty_like(dirs)
        origins[:] = centre
        prim, dist = self._cast(origins, dirs)
        seen = np.flatnonzero(prim >= 0)
        depth = np.zeros(n, dtype=np.float32)
        z = dist[seen] * self._ray_z[seen]
        near = z <= self.max_range
        depth[seen[near]] = z[near]
        instances = np.zeros(n, dtype=np.uint16)
        faces = prim[seen]
        instances[seen[near]] = self.world.instance[faces[near]]
        colour = np.empty((n, 3), dtype=np.float32)
        colour[:] = SKY_RGB
        colour[seen] = self._shade(faces, dirs[seen], dist[seen], centre)
        rgb = _encode_srgb(colour).reshape(k.height, k.width, 3)
        return RenderResult(
            rgb, depth.reshape(k.height, k.width), instances.reshape(k.height, k.width)
        )

    def _shade(
        self, faces: np.ndarray, dirs: np.ndarray, dist: np.ndarray, centre: np.ndarray
    ) -> np.ndarray:
        """Linear radiance of hit points (coordinates shifted by the mesh origin).

        Written column by column: (N, 3) @ (3, 3) products through BLAS are slow here.
        """
        points = dirs * dist[:, None]
        points += centre
        normals = self._normals[faces]
        facing = np.where(_dot(normals, dirs) > 0, np.float32(-1.0), np.float32(1.0))
        normals *= facing[:, None]
        room = self._lights.room_index(points + (normals * np.float32(0.08) + self._origin32))
        to_light = self._light_pos[room] - points
        light_dist = np.sqrt(_dot(to_light, to_light))
        to_light /= np.maximum(light_dist, np.float32(1e-6))[:, None]
        lambert = np.maximum(_dot(normals, to_light), np.float32(0.0))
        lamp = np.float32(LAMP) * lambert / (1.0 + (light_dist / np.float32(LAMP_FALLOFF)) ** 2)
        if self.shadows:
            lit = np.flatnonzero(lambert > 0)
            _, tfar = self._cast(points[lit] + normals[lit] * np.float32(2e-3), to_light[lit])
            lamp[lit[tfar < light_dist[lit] - 0.05]] *= np.float32(0.15)
        sky = _rotate(normals, self._sky_dir[None, :])[:, 0]
        surface = _texture(points, faces, self.world.texture)
        codes = self.world.material
        if codes is not None:
            mats = codes[faces]
            surface = pattern(mats, points, surface)
            shine = lamp * specular(mats, normals, dirs, to_light)
        light = (
            lamp + np.float32(SKY_LIGHT) * np.maximum(sky, 0.0) + np.float32(AMBIENT)
        ) * surface
        albedo = self.world.albedo[faces]
        out = albedo * light[:, None]
        if codes is not None:
            out = finish(mats, out, albedo, shine, normals, dirs)
        return out


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise dot product of two (N, 3) arrays."""
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] + a[:, 2] * b[:, 2]


def _rotate(vectors: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """``vectors @ matrix.T`` for (N, 3) vectors and an (M, 3) matrix, without BLAS."""
    out = np.empty((len(vectors), len(matrix)), dtype=np.float32)
    for i, row in enumerate(matrix):
        out[:, i] = vectors[:, 0] * row[0] + vectors[:, 1] * row[1] + vectors[:, 2] * row[2]
    return out


def _texture(points: np.ndarray, faces: np.ndarray, amplitude: np.ndarray) -> np.ndarray:
    """Deterministic value noise in [1 - a, 1 + a] from hashed 3 cm cells."""
    cells = np.floor(points * np.float32(33.0)).astype(np.int32).view(np.uint32)
    h = (cells[:, 0] * np.uint32(73856093)) ^ (cells[:, 1] * np.uint32(19349663))
    h ^= cells[:, 2] * np.uint32(83492791)
    h = (h ^ (h >> np.uint32(13))) * np.uint32(1274126177)
    noise = ((h >> np.uint32(7)) & np.uint32(1023)).astype(np.float32) / np.float32(511.5) - 1.0
    return 1.0 + noise * amplitude[faces]
