"""The geometric stream on real geometry: depth rendered from the Replica office0 scan
along its recorded trajectory (one room, one floor, walls not axis-aligned)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.geometry import GeometricStream
from inherit_sg.geometry.lines import dominant_angle
from inherit_sg.model import Frame, Pose

trimesh = pytest.importorskip("trimesh")
embree_scene = pytest.importorskip("embreex.rtcore_scene")
embree_mesh = pytest.importorskip("embreex.mesh_construction")

REPLICA = (
    Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "real" / "replica_office0"
)


@pytest.fixture(scope="module")
def office() -> GeometricStream:
    if not (REPLICA / "office0_mesh.ply").is_file():
        pytest.skip(f"Replica office0 not found at {REPLICA}")
    from inherit_sg.ingest.readers.replica import read_cam_params, read_trajectory

    mesh = trimesh.load(REPLICA / "office0_mesh.ply", process=False)
    scene = embree_scene.EmbreeScene()
    embree_mesh.TriangleMesh(scene, mesh.vertices[mesh.faces].astype(np.float32))
    intr = read_cam_params(REPLICA / "cam_params.json").scaled(0.2)
    u, v = np.meshgrid(np.arange(intr.width), np.arange(intr.height))
    rays = np.stack([(u - intr.cx) / intr.fx, (v - intr.cy) / intr.fy, np.ones(u.shape)], -1)
    rays = rays.reshape(-1, 3)
    stream = GeometricStream(enqueue_keyframes=False)
    for i, m in enumerate(read_trajectory(REPLICA / "traj.txt")[::30]):
        dirs = (rays @ m[:3, :3].T).astype(np.float32)
        origins = np.repeat(m[None, :3, 3], len(dirs), axis=0).astype(np.float32)
        hit = scene.run(origins, dirs, output=1)
        depth = np.where(hit["geomID"] >= 0, hit["tfar"], 0.0)  # rays have unit z
        frame = Frame(
            index=i,
            frame_id=f"{i:06d}",
            timestamp=float(i),
            rgb=np.full((intr.height, intr.width, 3), 128, dtype=np.uint8),
            depth=depth.reshape(intr.height, intr.width).astype(np.float32),
            pose=Pose.from_matrix(m),
            intrinsics=intr,
        )
        stream.process(frame)
    stream.refine()
    return stream


def test_one_floor_one_room(office: GeometricStream) -> None:
    floors = office.floors()
    assert len(floors) == 1
    assert floors[0].z_min == pytest.approx(-1.17, abs=0.1)  # the scan's floor
    rooms = office.rooms(refined=True)
    assert len(rooms) == 1
    mask = rooms[0].mask
    assert mask is not None and 12.0 < mask.area_m2 < 22.0
    x, y, _ = rooms[0].position
    assert -2.0 < x < 2.4 and -3.2 < y < 1.9


def test_walls_are_found_at_their_real_angle(office: GeometricStream) -> None:
    grid = office.maps["floor:0"].grid
    angle = math.degrees(dominant_angle(grid.occupied_mask()))
    assert 2.0 < abs(angle) < 15.0  # office0's walls are not aligned with the axes
