"""Readers on the real shared data: Replica office0 in the NICE-SLAM layout."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from inherit_sg.ingest.readers import detect_format, open_dataset
from inherit_sg.model import Frame

REPO_ROOT = Path(__file__).resolve().parents[2]
OFFICE0 = REPO_ROOT / ".." / "shared" / "data" / "real" / "replica_office0"

pytestmark = pytest.mark.skipif(
    not (OFFICE0 / "traj.txt").is_file(), reason="shared real data absent"
)


@pytest.fixture(scope="module")
def frames() -> list[Frame]:
    source = open_dataset(OFFICE0)
    assert source.format_name == "replica"
    return list(source)


def _world_points(frame: Frame, step: int = 8) -> np.ndarray:
    k = frame.intrinsics
    v, u = np.mgrid[0 : k.height : step, 0 : k.width : step]
    z = frame.depth[v, u]
    ok = z > 0
    cam = np.stack([(u[ok] - k.cx) / k.fx * z[ok], (v[ok] - k.cy) / k.fy * z[ok], z[ok]], axis=1)
    return frame.pose.transform_points(cam)


def test_office0_has_four_full_size_frames(frames: list[Frame]) -> None:
    assert detect_format(OFFICE0) == "replica"
    assert len(frames) == 4
    for f in frames:
        assert f.rgb.shape == (680, 1200, 3) and f.rgb.dtype == np.uint8
        assert f.depth.shape == (680, 1200) and f.depth.dtype == np.float32
        assert f.rgb.std() > 10  # a real image, not a blank


def test_office0_depth_is_in_metres(frames: list[Frame]) -> None:
    for f in frames:
        valid = f.depth[f.depth > 0]
        assert valid.size > 0.9 * f.depth.size
        assert valid.min() > 0.1 and valid.max() < 10.0
        assert 1.0 < float(np.median(valid)) < 4.0


def test_office0_poses_are_z_up(frames: list[Frame]) -> None:
    for f in frames:
        r = f.pose.rotation
        assert abs(r[2, 0]) < 1e-6  # camera x axis horizontal: no roll about world z
        assert r[2, 1] < -0.5  # image down points down in the world
        points = _world_points(f)
        # The floor is a horizontal slab: many points share the lowest z, unlike x or y.
        slab = [_lowest_slab_fraction(points[:, axis]) for axis in range(3)]
        assert slab[2] > 0.1 and slab[2] > 5 * max(slab[0], slab[1])
        camera_height = f.pose.translation[2] - np.percentile(points[:, 2], 1)
        assert 1.0 < camera_height < 2.5  # a hand-held camera above the floor


def _lowest_slab_fraction(values: np.ndarray, thickness: float = 0.05) -> float:
    return float(np.mean(np.abs(values - np.percentile(values, 1)) < thickness))


def test_office0_depth_agrees_with_the_mesh(frames: list[Frame]) -> None:
    trimesh = pytest.importorskip("trimesh")
    spatial = pytest.importorskip("scipy.spatial")
    mesh = trimesh.load(OFFICE0 / "office0_mesh.ply", process=False)
    tree = spatial.cKDTree(np.asarray(mesh.vertices))
    distances, _ = tree.query(_world_points(frames[0], step=16))
    assert float(np.median(distances)) < 0.05
