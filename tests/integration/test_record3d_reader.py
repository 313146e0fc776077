"""Record3D ``.r3d`` captures written from the frames of a small generated house: the
reader gives back the same frames (poses, depth, colour, intrinsics), drops low-confidence
depth, scales intrinsics with the image, puts the floor at z = 0 with z up (and a file
with a pose-convention mistake fails the same check), and ``inherit-sg map build
capture.r3d`` makes the same map as the same frames in an isg folder.

Fair equality: an .r3d has no instance masks, so the isg side is a copy of the dataset
without masks, holding the very JPEG bytes the .r3d holds: both builds then run the
classical segmenter on identical pixels and depth, and the maps must agree exactly (object
positions to 1e-3 m, only pose round-off through the quaternion differs)."""

from __future__ import annotations

import json
import subprocess
import sys
import zipfile
from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.isg import IsgReader
from inherit_sg.ingest.readers import detect_format, open_dataset
from inherit_sg.ingest.readers.base import FrameSource
from inherit_sg.ingest.readers.convert import OPENGL_TO_OPENCV, Y_UP_TO_Z_UP
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.perception.planes import backproject
from inherit_sg.store import MapStore

pytest.importorskip("lzfse")
from tests.integration.r3d_files import write_r3d  # after the skip: needs lzfse

CLI = [sys.executable, "-m", "inherit_sg.cli.main"]


@pytest.fixture(scope="module")
def house(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("house") / "h"
    write_dataset(generate_house(3, 1, 4), out, width=160, height=120, workers=1, max_frames=40)
    return out


@pytest.fixture(scope="module")
def capture(house: Path) -> tuple[Path, Path]:
    """(.r3d file, isg copy with the same JPEG colour images and no masks)."""
    return write_r3d(house, house.parent / "capture.r3d", jpeg_copy=house.parent / "jpeg"), (
        house.parent / "jpeg"
    )


def test_frames_equal_the_isg_frames(capture: tuple[Path, Path]) -> None:
    r3d, jpeg = capture
    assert detect_format(r3d) == "record3d"
    reader, isg = open_dataset(r3d), IsgReader(jpeg)
    assert isinstance(reader, FrameSource)
    assert reader.intrinsics == isg.intrinsics and len(reader) == len(isg) == 40
    for ours, truth in zip(reader, isg, strict=True):
        assert np.array_equal(ours.rgb, truth.rgb)
        assert np.array_equal(ours.depth, truth.depth)
        assert np.abs(ours.pose.matrix - truth.pose.matrix).max() < 1e-9
        assert ours.timestamp == truth.timestamp


def _blocks(w: int, h: int) -> np.ndarray:
    """High confidence but for a low (0) block top left and a medium (1) one top right."""
    conf = np.full((h, w), 2, np.uint8)
    conf[: h // 3, : w // 3] = 0
    conf[: h // 3, -w // 3 :] = 1
    return conf


def _nearest(image: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    return cv2.resize(image, size, interpolation=cv2.INTER_NEAREST_EXACT)


def test_small_depth_and_confidence(house: Path, tmp_path: Path) -> None:
    r3d = write_r3d(house, tmp_path / "c.r3d", depth_size=(80, 60), confidence=_blocks)
    isg = IsgReader(house)
    truth = isg.read(5)
    expected = _nearest(_nearest(truth.depth, (80, 60)), (160, 120))
    conf = _nearest(_blocks(80, 60), (160, 120))
    frame = open_dataset(r3d).read(5)  # default: high confidence only
    assert frame.depth.shape == (120, 160)
    assert np.array_equal(frame.depth, np.where(conf == 2, expected, 0))
    medium = open_dataset(r3d, min_confidence=1).read(5)
    assert np.array_equal(medium.depth, np.where(conf >= 1, expected, 0))
    # a working size below the colour size: intrinsics scale with the image
    half = open_dataset(r3d, max_width=80)
    assert half.intrinsics == isg.intrinsics.scaled(0.5)
    small = half.read(5)
    assert small.rgb.shape == (60, 80, 3)
    assert np.array_equal(
        small.depth, np.where(_blocks(80, 60) == 2, _nearest(truth.depth, (80, 60)), 0)
    )


def _axis_problems(source: FrameSource) -> list[str]:
    """What is wrong with a stream's world frame, for a house whose floor is z = 0."""
    problems = []
    points, heights, downs = [], [], []
    for frame in source:
        m = frame.pose.matrix
        if m[2, 1] >= 0:
            problems.append(f"frame {frame.frame_id}: camera y (image down) points up")
        downs.append(m[2, 1])
        heights.append(m[2, 3])
        cam = backproject(frame.depth, frame.intrinsics).reshape(-1, 3)
        cam = cam[cam[:, 2] > 0]
        points.append(cam @ m[:3, :3].T + m[:3, 3])
    z = np.concatenate(points)[:, 2]
    floor = float(np.percentile(z, 2))
    if abs(floor) > 0.05:
        problems.append(f"floor at z = {floor:.2f}, not 0")
    if float(np.median(downs)) > -0.9:
        problems.append("cameras are not held upright (image down is not world down)")
    if not 0.5 < float(np.median(heights)) < 2.0:
        problems.append(f"cameras at z = {np.median(heights):.2f}, not at eye height")
    return problems


def test_world_is_z_up_with_the_floor_at_zero(capture: tuple[Path, Path], tmp_path: Path) -> None:
    assert _axis_problems(open_dataset(capture[0])) == []
    # the checks catch pose-convention mistakes: a capture whose camera axes were never
    # flipped from OpenGL, and one whose world stayed y-up
    no_flip = write_r3d(
        capture[1], tmp_path / "a.r3d", convention=lambda m: np.linalg.inv(Y_UP_TO_Z_UP) @ m
    )
    y_up = write_r3d(capture[1], tmp_path / "b.r3d", convention=lambda m: m @ OPENGL_TO_OPENCV)
    assert _axis_problems(open_dataset(no_flip))
    assert _axis_problems(open_dataset(y_up))


def _objects(map_dir: Path) -> list[tuple[str, tuple[float, ...]]]:
    with MapStore.open(map_dir) as store:
        return sorted(
            (o.label, tuple(np.round(o.position, 3))) for o in store.load_graph().objects()
        )


def test_map_build_matches_the_isg_build(capture: tuple[Path, Path], tmp_path: Path) -> None:
    r3d, jpeg = capture
    summaries = []
    for source, name in ((r3d, "from_r3d"), (jpeg, "from_isg")):
        proc = subprocess.run(
            [*CLI, "map", "build", str(source), "--map", str(tmp_path / name), "--json"],
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert proc.returncode == 0, proc.stderr
        summaries.append(json.loads(proc.stdout))
    keys = ("frames", "keyframes", "floors", "rooms", "areas", "objects", "relations")
    assert {k: summaries[0][k] for k in keys} == {k: summaries[1][k] for k in keys}
    assert summaries[0]["objects"] >= 10 and summaries[0]["floors"] == 1
    from_r3d, from_isg = _objects(tmp_path / "from_r3d"), _objects(tmp_path / "from_isg")
    assert len(from_r3d) == len(from_isg)
    for (label_a, pos_a), (label_b, pos_b) in zip(from_r3d, from_isg, strict=True):
        assert label_a == label_b and np.allclose(pos_a, pos_b, atol=1e-3)


def test_bad_files(tmp_path: Path) -> None:
    not_zip = tmp_path / "a.r3d"
    not_zip.write_text("hello")
    with pytest.raises(DatasetError, match="not a zip"):
        open_dataset(not_zip)
    no_meta = tmp_path / "b.r3d"
    with zipfile.ZipFile(no_meta, "w") as archive:
        archive.writestr("rgbd/0.jpg", b"")
    with pytest.raises(DatasetError, match="no 'metadata'"):
        open_dataset(no_meta)
    with pytest.raises(DatasetError, match=r"expected one \.r3d"):
        open_dataset(tmp_path, format="record3d")
