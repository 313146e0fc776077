"""ScanNet SensReader-export reader on tiny fixture folders."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers import detect_format, open_dataset
from inherit_sg.ingest.readers.scannet import ScanNetReader

DW, DH, DF = 80, 60, 60.0  # depth camera: size and focal length, centred principal point


def _k(f: float, cx: float, cy: float) -> str:
    m = np.array([[f, 0, cx, 0], [0, f, cy, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    return "\n".join(" ".join(f"{v:g}" for v in row) for row in m)


def _ray_colour(w: int, h: int, f: float, cx: float, cy: float) -> np.ndarray:
    """RGB image whose red/green encode each pixel's ray direction (x/z, y/z)."""
    u, v = np.meshgrid(np.arange(w), np.arange(h))
    rgb = np.zeros((h, w, 3), np.uint8)
    rgb[..., 0] = np.clip(128 + 150 * (u - cx) / f, 0, 255)
    rgb[..., 1] = np.clip(128 + 150 * (v - cy) / f, 0, 255)
    return rgb


def _pose(i: int) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], dtype=float)  # looks along +y
    m[:3, 3] = [2.0, 1.0 + i, 1.4]
    return m


def _write(
    root: Path, colour: tuple[int, int, float, float, float] = (160, 120, 120.0, 79.5, 59.5)
) -> Path:
    for sub in ("color", "depth", "pose", "intrinsic"):
        (root / sub).mkdir(parents=True)
    cw, ch, cf, ccx, ccy = colour
    (root / "intrinsic" / "intrinsic_color.txt").write_text(_k(cf, ccx, ccy))
    (root / "intrinsic" / "intrinsic_depth.txt").write_text(_k(DF, (DW - 1) / 2, (DH - 1) / 2))
    rgb = _ray_colour(cw, ch, cf, ccx, ccy)
    for i in range(5):
        cv2.imwrite(str(root / "color" / f"{i}.png"), cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR))
        cv2.imwrite(str(root / "depth" / f"{i}.png"), np.full((DH, DW), 1500 + i, np.uint16))
        if i == 4:
            continue  # frame 4 has no pose file
        text = "\n".join(" ".join(f"{v:g}" for v in row) for row in _pose(i))
        if i == 2:  # tracking lost: ScanNet writes -inf rows
            text = "\n".join(["-inf -inf -inf -inf"] * 4)
        (root / "pose" / f"{i}.txt").write_text(text)
    return root


def test_reads_depth_grid_with_depth_intrinsics_and_skips_invalid_poses(tmp_path: Path) -> None:
    root = _write(tmp_path / "scene0000_00")
    assert detect_format(root) == "scannet"
    reader = open_dataset(root)
    assert isinstance(reader, ScanNetReader)
    assert reader.frame_ids == ["0", "1", "3"]
    assert "-inf" in reader.skipped["2"] and "no pose" in reader.skipped["4"]
    assert (reader.intrinsics.width, reader.intrinsics.height, reader.intrinsics.fx) == (DW, DH, DF)
    frames = list(reader)
    assert all(np.all(np.isfinite(f.pose.matrix)) for f in frames)
    f = frames[2]
    assert f.frame_id == "3" and f.rgb.shape == (DH, DW, 3)
    assert f.depth[5, 5] == pytest.approx(1.503)
    assert np.allclose(f.pose.matrix, _pose(3))
    # Optical axis horizontal along +y, image down = world down (z-up world).
    assert np.allclose(f.pose.rotation[:, 2], [0, 1, 0]) and np.allclose(
        f.pose.rotation[:, 1], [0, 0, -1]
    )


@pytest.mark.parametrize(
    "colour",
    [(160, 120, 120.0, 79.5, 59.5), (150, 110, 100.0, 70.0, 50.0)],
    ids=["same-fov", "other-fov-and-centre"],
)
def test_colour_is_resampled_onto_the_depth_rays(
    tmp_path: Path, colour: tuple[int, int, float, float, float]
) -> None:
    frame = ScanNetReader(_write(tmp_path / "s", colour)).read(0)
    expected = _ray_colour(DW, DH, DF, (DW - 1) / 2, (DH - 1) / 2)
    inner = (slice(2, -2), slice(2, -2))
    diff = np.abs(frame.rgb[inner][..., :2].astype(int) - expected[inner][..., :2].astype(int))
    assert diff.max() <= 3


def test_back_projection_lands_on_the_known_world_point(tmp_path: Path) -> None:
    frame = ScanNetReader(_write(tmp_path / "s")).read(1)
    k = frame.intrinsics
    u, v = 60, 10
    z = float(frame.depth[v, u])
    world = frame.pose.transform_points(
        np.array([[(u - k.cx) / k.fx * z, (v - k.cy) / k.fy * z, z]])
    )[0]
    # Camera at (2, 2, 1.4) looking along +y: right is +x, up the image is +z.
    assert np.allclose(world, [2 + (u - k.cx) / k.fx * z, 2 + z, 1.4 - (v - k.cy) / k.fy * z])
    assert world[2] > 1.4  # a pixel above the image centre sees higher up


def test_malformed_pose_file_names_the_file(tmp_path: Path) -> None:
    root = _write(tmp_path / "s")
    (root / "pose" / "1.txt").write_text("1 0 0 0\n0 1 0 0\n0 0 1 0")
    with pytest.raises(DatasetError, match=r"pose/1\.txt: expected a 3x3 or 4x4 matrix"):
        ScanNetReader(root)
    (root / "pose" / "1.txt").write_text("a b c d\n" * 4)
    with pytest.raises(DatasetError, match=r"pose/1\.txt: matrix values must be numbers"):
        ScanNetReader(root)


def test_missing_parts_and_wrong_colour_size(tmp_path: Path) -> None:
    root = _write(tmp_path / "s")
    cv2.imwrite(str(root / "color" / "1.png"), np.zeros((100, 100, 3), np.uint8))
    with pytest.raises(FrameError, match=r"1\.png: colour is 100x100"):
        ScanNetReader(root).read(1)
    (root / "intrinsic" / "intrinsic_depth.txt").unlink()
    with pytest.raises(DatasetError, match=r"missing .*intrinsic_depth\.txt"):
        ScanNetReader(root)
    for p in (root / "depth").iterdir():
        p.unlink()
    with pytest.raises(DatasetError, match="no depth images"):
        ScanNetReader(root)
