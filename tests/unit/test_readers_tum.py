"""TUM RGB-D reader: association, pose interpolation, intrinsics presets, malformed input."""

from __future__ import annotations

import math
from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.readers import detect_format, open_dataset
from inherit_sg.ingest.readers.tum import (
    TUM_CAMERAS,
    TumReader,
    associate,
    camera_from_path,
    pose_at,
)
from inherit_sg.model import Intrinsics

T0 = 100.0
RGB_TIMES = [100.100, 100.210, 100.300, 100.400, 100.905]
DEPTH_TIMES = [100.105, 100.205, 100.305, 100.450, 100.900]


def _gt_line(t: float) -> str:
    """Camera moving along +x at 1 m/s while yawing about z at 1 rad/s."""
    a = t - T0
    return f"{t:.4f} {a:.6f} 0 1.2 0 0 {math.sin(a / 2):.9f} {math.cos(a / 2):.9f}"


def _write(root: Path) -> Path:
    (root / "rgb").mkdir(parents=True)
    (root / "depth").mkdir()
    rgb_lines = ["# color images", "# timestamp filename"]
    for t in RGB_TIMES:
        name = f"rgb/{t:.6f}.png"
        cv2.imwrite(str(root / name), np.full((480, 640, 3), (10, 20, 250), np.uint8))
        rgb_lines.append(f"{t:.6f} {name}")
    depth_lines = ["# depth maps"]
    for t in DEPTH_TIMES:
        name = f"depth/{t:.6f}.png"
        cv2.imwrite(str(root / name), np.full((480, 640), 10000, np.uint16))
        depth_lines.append(f"{t:.6f} {name}")
    (root / "rgb.txt").write_text("\n".join(rgb_lines) + "\n")
    (root / "depth.txt").write_text("\n".join(depth_lines) + "\n")
    gt = ["# ground truth trajectory"] + [_gt_line(T0 + k / 100) for k in range(51)]
    (root / "groundtruth.txt").write_text("\n".join(gt) + "\n")
    return root


def test_pairs_frames_interpolates_poses_and_picks_the_camera(tmp_path: Path) -> None:
    root = _write(tmp_path / "rgbd_dataset_freiburg2_desk")
    assert detect_format(root) == "tum"
    reader = open_dataset(root)
    assert isinstance(reader, TumReader) and reader.camera == "fr2"
    assert reader.intrinsics == TUM_CAMERAS["fr2"]
    assert reader.frame_ids == ["100.105000", "100.205000", "100.305000"]
    assert "no colour" in reader.skipped["100.450000"]  # nearest rgb is 0.05 s away
    assert "no ground-truth pose" in reader.skipped["100.900000"]  # gt ends at 100.50
    f = reader.read(0)
    assert f.timestamp == pytest.approx(100.105)
    assert f.depth[0, 0] == pytest.approx(2.0)  # 10000 / 5000
    assert tuple(f.rgb[0, 0]) == (250, 20, 10)
    assert np.allclose(f.pose.translation, [0.105, 0.0, 1.2], atol=1e-6)
    yaw = math.atan2(f.pose.rotation[1, 0], f.pose.rotation[0, 0])
    assert yaw == pytest.approx(0.105, abs=1e-6)


def test_camera_override_explicit_intrinsics_and_world_transform(tmp_path: Path) -> None:
    root = _write(tmp_path / "recording")
    assert camera_from_path(root) == "default"
    assert TumReader(root).intrinsics.fx == 525.0
    assert TumReader(root, camera="fr3").intrinsics == TUM_CAMERAS["fr3"]
    own = Intrinsics(640, 480, 500.0, 500.0, 320.0, 240.0, 5000.0)
    assert TumReader(root, intrinsics=own).read(0).intrinsics == own
    lift = np.eye(4)
    lift[2, 3] = 10.0
    moved = TumReader(root, world_from_recorded=lift).read(0)
    assert moved.pose.translation[2] == pytest.approx(11.2)
    with pytest.raises(DatasetError, match="unknown TUM camera 'fr9'"):
        TumReader(root, camera="fr9")


def test_associate_is_one_to_one_and_closest_first() -> None:
    pairs = associate([1.000, 1.010, 2.0], [1.008, 1.5], 0.02)
    assert pairs == [(1, 0)]  # 1.010 is closer to 1.008 than 1.000 is; 2.0 has no partner


def test_pose_at_interpolates_only_across_small_gaps() -> None:
    times = [0.0, 0.01, 0.5]
    mats = []
    for x in (0.0, 1.0, 2.0):
        m = np.eye(4)
        m[0, 3] = x
        mats.append(m)
    mid = pose_at(0.005, times, mats, 0.02)
    assert mid is not None and mid[0, 3] == pytest.approx(0.5)
    nearest = pose_at(0.015, times, mats, 0.02)
    assert nearest is not None and nearest[0, 3] == 1.0
    assert pose_at(0.25, times, mats, 0.02) is None
    edge = pose_at(-0.01, times, mats, 0.02)
    assert edge is not None and edge[0, 3] == 0.0
    assert pose_at(-0.05, times, mats, 0.02) is None


def test_malformed_files_name_file_and_line(tmp_path: Path) -> None:
    root = _write(tmp_path / "rgbd_dataset_freiburg1_xyz")
    text = (root / "depth.txt").read_text()
    (root / "depth.txt").write_text(text + "abc depth/x.png\n")
    with pytest.raises(DatasetError, match=r"depth\.txt:7: timestamp 'abc' is not a number"):
        TumReader(root)
    (root / "depth.txt").write_text(text + "nan depth/x.png\n")
    with pytest.raises(DatasetError, match="not finite"):
        TumReader(root)
    (root / "depth.txt").write_text(text)
    with (root / "groundtruth.txt").open("a") as handle:
        handle.write("101.0 1 2 3 0 0 0\n")
    with pytest.raises(DatasetError, match=r"groundtruth\.txt:53: expected 'timestamp tx ty tz"):
        TumReader(root)
    (root / "groundtruth.txt").unlink()
    with pytest.raises(DatasetError, match=r"missing .*groundtruth\.txt"):
        TumReader(root)
