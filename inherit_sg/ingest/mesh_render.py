"""Render a coloured triangle mesh (a real scan such as Replica's ``office0_mesh.ply``)
along a recorded camera trajectory into an isg dataset folder.

Each pixel casts one ray through Embree (``embreex``); depth is the hit distance along the
optical axis, colour the hit triangle's vertex colours blended by the barycentric
coordinates. Nothing is annotated: the frames carry no instance masks, like a real RGB-D
recording, so mapping them exercises the classical segmenter.

Poses are camera-to-world 4×4 matrices in our convention (z-up world, OpenCV camera:
x right, y down, z forward).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.isg import IsgWriter
from inherit_sg.model import Intrinsics, Pose

Progress = Callable[[int, int], None]


@dataclass
class MeshRenderSummary:
    """What :func:`write_mesh_dataset` wrote."""

    out_dir: str
    frames: int
    width: int
    height: int
    vertices: int
    faces: int
    seconds: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return asdict(self)


class MeshRenderer:
    """Ray-casts RGB-D frames of one mesh with per-vertex colours."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray, colours: np.ndarray) -> None:
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        vertices = np.asarray(vertices, dtype=np.float64)
        faces = np.asarray(faces, dtype=np.int64)
        if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) == 0:
            raise DatasetError(f"mesh vertices must be (N, 3), got {vertices.shape}")
        if faces.ndim != 2 or faces.shape[1] != 3 or len(faces) == 0:
            raise DatasetError(f"mesh faces must be (M, 3) triangles, got {faces.shape}")
        if faces.min() < 0 or faces.max() >= len(vertices):
            raise DatasetError("mesh faces index vertices that do not exist")
        if not np.isfinite(vertices).all():
            raise DatasetError("mesh vertices must be finite numbers")
        self.vertex_count = len(vertices)
        self.face_count = len(faces)
        self._scene = rtcore_scene.EmbreeScene()
        TriangleMesh(self._scene, vertices[faces].astype(np.float32))
        self._corner_rgb = np.asarray(colours, dtype=np.float32)[:, :3][faces]  # (M, 3, 3)

    @classmethod
    def load(cls, path: Path) -> MeshRenderer:
        """A renderer of the mesh file at ``path`` (PLY, OBJ… anything trimesh reads) with
        its vertex colours; grey where the file has none."""
        import trimesh

        if not path.is_file():
            raise DatasetError(f"mesh file not found: {path}")
        try:
            mesh = trimesh.load(path, process=False, force="mesh")
        except Exception as exc:  # trimesh raises many types for unreadable files
            raise DatasetError(f"{path}: not a readable triangle mesh: {exc}") from None
        if not isinstance(mesh, trimesh.Trimesh):
            raise DatasetError(f"{path}: not a triangle mesh")
        visual = getattr(mesh, "visual", None)
        colours = getattr(visual, "vertex_colors", None) if visual is not None else None
        if colours is None or len(colours) != len(mesh.vertices):
            colours = np.full((len(mesh.vertices), 3), 128, dtype=np.uint8)
        return cls(np.asarray(mesh.vertices), np.asarray(mesh.faces), np.asarray(colours))

    def render(self, pose: Pose, intrinsics: Intrinsics) -> tuple[np.ndarray, np.ndarray]:
        """(rgb uint8 (h, w, 3), depth float32 metres (h, w), 0 where nothing is hit)."""
        h, w = intrinsics.height, intrinsics.width
        u, v = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
        rays = np.stack(
            [
                (u - intrinsics.cx) / intrinsics.fx,
                (v - intrinsics.cy) / intrinsics.fy,
                np.ones_like(u),
            ],
            axis=-1,
        ).reshape(-1, 3)
        matrix = pose.matrix
        dirs = (rays @ matrix[:3, :3].T).astype(np.float32)
        origins = np.repeat(matrix[None, :3, 3], len(dirs), axis=0).astype(np.float32)
        hit = self._scene.run(origins, dirs, output=1)
        seen = hit["geomID"] >= 0
        prim = np.where(seen, hit["primID"], 0)
        bu, bv = hit["u"][:, None], hit["v"][:, None]
        corners = self._corner_rgb[prim]
        rgb = (1.0 - bu - bv) * corners[:, 0] + bu * corners[:, 1] + bv * corners[:, 2]
        rgb[~seen] = 0.0
        depth = np.where(seen, hit["tfar"], 0.0)  # rays have unit z: tfar is the depth
        return (
            np.clip(np.round(rgb), 0, 255).astype(np.uint8).reshape(h, w, 3),
            depth.astype(np.float32).reshape(h, w),
        )


def spread(count: int, available: int) -> list[int]:
    """``count`` indices spread evenly over ``range(available)`` (all when fewer)."""
    if available <= 0:
        raise DatasetError("the trajectory has no poses")
    if count >= available:
        return list(range(available))
    return sorted({int(i) for i in np.rint(np.linspace(0, available - 1, count))})


def write_mesh_dataset(
    renderer: MeshRenderer,
    poses: Sequence[np.ndarray],
    intrinsics: Intrinsics,
    out: Path,
    *,
    frames: int = 200,
    progress: Progress | None = None,
) -> MeshRenderSummary:
    """Render ``frames`` poses spread evenly over ``poses`` into the isg folder ``out``.
    Non-finite poses are left out."""
    start = time.perf_counter()
    usable = [m for m in poses if np.isfinite(m).all()]
    chosen = spread(frames, len(usable))
    with IsgWriter(out, intrinsics) as writer:
        for n, i in enumerate(chosen):
            pose = Pose.from_matrix(usable[i])
            rgb, depth = renderer.render(pose, intrinsics)
            writer.write(f"{n:06d}", rgb, depth, pose)
            if progress is not None:
                progress(n + 1, len(chosen))
    return MeshRenderSummary(
        out_dir=str(out),
        frames=len(chosen),
        width=intrinsics.width,
        height=intrinsics.height,
        vertices=renderer.vertex_count,
        faces=renderer.face_count,
        seconds=round(time.perf_counter() - start, 2),
    )
