"""Replica (NICE-SLAM layout) reader on tiny fixture folders."""

from __future__ import annotations

import json
from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers import FrameSource, detect_format, open_dataset
from inherit_sg.ingest.readers.replica import ReplicaReader
from inherit_sg.model import Frame

W, H, SCALE = 40, 30, 6553.5
FX, CX, CY = 30.0, 19.5, 14.5


def _pose(i: int) -> np.ndarray:
    """Camera looking along world +x, level, image-down = world down, 1.5 m high."""
    m = np.eye(4)
    m[:3, :3] = np.array([[0, 0, 1], [-1, 0, 0], [0, -1, 0]], dtype=float)
    m[:3, 3] = [0.1 * i, 0.0, 1.5]
    return m


def _write(root: Path, frames: int = 3, poses: int = 5, depth_m: float = 2.0) -> Path:
    res = root / "results"
    res.mkdir(parents=True)
    cam = {"w": W, "h": H, "fx": FX, "fy": FX, "cx": CX, "cy": CY, "scale": SCALE}
    (root / "cam_params.json").write_text(json.dumps({"camera": cam}))
    lines = [" ".join(f"{v:.12g}" for v in _pose(i).reshape(-1)) for i in range(poses)]
    (root / "traj.txt").write_text("\n".join(lines) + "\n")
    for i in range(frames):
        bgr = np.zeros((H, W, 3), np.uint8)
        bgr[..., 2] = 200  # red in BGR order
        bgr[0, 0] = (i, i, i)
        cv2.imwrite(str(res / f"frame{i:06d}.jpg"), bgr, [cv2.IMWRITE_JPEG_QUALITY, 100])
        depth = np.full((H, W), round(depth_m * SCALE), np.uint16)
        depth[0, :5] = 0
        cv2.imwrite(str(res / f"depth{i:06d}.png"), depth)
    return root


def _backproject(frame: Frame, u: int, v: int) -> np.ndarray:
    k = frame.intrinsics
    z = float(frame.depth[v, u])
    cam = np.array([(u - k.cx) / k.fx * z, (v - k.cy) / k.fy * z, z])
    return frame.pose.transform_points(cam[None])[0]


def test_reads_frames_in_metres_rgb_order_and_matching_poses(tmp_path: Path) -> None:
    root = _write(tmp_path / "office")
    reader = open_dataset(root)
    assert isinstance(reader, ReplicaReader) and isinstance(reader, FrameSource)
    assert detect_format(root) == "replica" and reader.format_name == "replica"
    assert len(reader) == 3 and reader.skipped == {}  # poses 3 and 4 have no images: ignored
    frames = list(reader)
    assert [f.frame_id for f in frames] == ["000000", "000001", "000002"]
    f = frames[2]
    assert f.rgb.shape == (H, W, 3) and f.rgb[5, 5, 0] > 190 and f.rgb[5, 5, 2] < 10
    assert f.depth.dtype == np.float32
    assert f.depth[10, 10] == pytest.approx(2.0, abs=1e-4) and f.depth[0, 0] == 0.0
    assert np.allclose(f.pose.matrix, _pose(2))
    assert reader.intrinsics.depth_scale == SCALE


def test_back_projection_lands_on_the_known_world_point(tmp_path: Path) -> None:
    frame = open_dataset(_write(tmp_path / "s", depth_m=2.0)).read(1)
    # Camera at (0.1, 0, 1.5) looking along +x: the principal ray at 2 m ends at x = 2.1.
    center = _backproject(frame, 20, 15)
    assert np.allclose(center, [0.1 + 2.0, -(20 - CX) / FX * 2.0, 1.5 - (15 - CY) / FX * 2.0])
    # A pixel below the centre sees a point lower in the z-up world.
    assert _backproject(frame, 20, 28)[2] < center[2]
    assert frame.pose.rotation[:, 1] @ [0, 0, 1] == pytest.approx(-1.0)  # image down = world down


def test_unpaired_images_and_frames_without_pose_are_skipped(tmp_path: Path) -> None:
    root = _write(tmp_path / "s", frames=4, poses=3)
    (root / "results" / "depth000001.png").unlink()
    reader = ReplicaReader(root)
    assert reader.frame_ids == ["000000", "000002"]
    assert "no depth" in reader.skipped["000001"] and "no pose" in reader.skipped["000003"]


def test_non_finite_pose_is_skipped_and_malformed_line_names_the_line(tmp_path: Path) -> None:
    root = _write(tmp_path / "s")
    lines = (root / "traj.txt").read_text().splitlines()
    lines[1] = " ".join(["nan"] * 16)
    (root / "traj.txt").write_text("\n".join(lines))
    reader = ReplicaReader(root)
    assert reader.frame_ids == ["000000", "000002"] and "invalid pose" in reader.skipped["000001"]
    lines[2] = "1 2 3"
    (root / "traj.txt").write_text("\n".join(lines))
    with pytest.raises(DatasetError, match=r"traj\.txt:3: expected 16 numbers"):
        ReplicaReader(root)


def test_image_removed_after_opening_raises_frame_error_naming_it(tmp_path: Path) -> None:
    root = _write(tmp_path / "s")
    reader = ReplicaReader(root)
    (root / "results" / "frame000001.jpg").unlink()
    with pytest.raises(FrameError, match=r"frame000001\.jpg"):
        reader.read(1)
    with pytest.raises(IndexError):
        reader.read(3)


def test_wrong_image_size_and_8_bit_depth_raise_frame_errors(tmp_path: Path) -> None:
    root = _write(tmp_path / "s")
    cv2.imwrite(str(root / "results" / "frame000000.jpg"), np.zeros((H, W + 2, 3), np.uint8))
    cv2.imwrite(str(root / "results" / "depth000001.png"), np.ones((H, W), np.uint8))
    reader = ReplicaReader(root)
    with pytest.raises(FrameError, match="intrinsics say 40x30"):
        reader.read(0)
    with pytest.raises(FrameError, match=r"depth000001\.png.*16-bit"):
        reader.read(1)


def test_missing_or_malformed_files_raise_dataset_errors(tmp_path: Path) -> None:
    root = _write(tmp_path / "s")
    (root / "cam_params.json").write_text(json.dumps({"camera": {"w": W, "h": H, "fx": FX}}))
    with pytest.raises(
        DatasetError, match=r"cam_params\.json: camera is missing fy, cx, cy, scale"
    ):
        ReplicaReader(root)
    (root / "cam_params.json").write_text("{not json")
    with pytest.raises(DatasetError, match="invalid JSON"):
        ReplicaReader(root)
    good = {"w": W, "h": H, "fx": FX, "fy": FX, "cx": CX, "cy": CY, "scale": SCALE}
    (root / "cam_params.json").write_text(json.dumps(good))  # flat keys are accepted too
    (root / "traj.txt").unlink()
    with pytest.raises(DatasetError, match=r"missing .*traj\.txt"):
        ReplicaReader(root)
    with pytest.raises(DatasetError, match="not found"):
        ReplicaReader(tmp_path / "nowhere")
