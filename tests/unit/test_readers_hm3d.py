"""HM3D walks (HOV-SG layout) reader: Habitat y-up/OpenGL poses to z-up/OpenCV."""

from __future__ import annotations

import math
from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers import detect_format, open_dataset
from inherit_sg.ingest.readers.hm3d import Hm3dReader, habitat_intrinsics
from inherit_sg.model import Frame

W, H = 64, 48
SCENE = "Dd4bFSTQ8gi"
DEPTH_M = 2.5


def _yaw_pitch(
    yaw_deg: float, pitch_deg: float, position: tuple[float, float, float]
) -> np.ndarray:
    """Habitat sensor pose: yaw about Habitat's up (y), then pitch about the sensor's x."""
    y, p = math.radians(yaw_deg), math.radians(pitch_deg)
    ry = np.array([[math.cos(y), 0, math.sin(y)], [0, 1, 0], [-math.sin(y), 0, math.cos(y)]])
    rx = np.array([[1, 0, 0], [0, math.cos(p), -math.sin(p)], [0, math.sin(p), math.cos(p)]])
    m = np.eye(4)
    m[:3, :3] = ry @ rx
    m[:3, 3] = position
    return m


HAB_POSES = {
    0: _yaw_pitch(0, 0, (1.0, 1.5, -2.0)),
    1: _yaw_pitch(90, 0, (0.0, 1.5, 0.0)),
    2: _yaw_pitch(0, -30, (0.0, 1.5, 0.0)),  # looking 30° down
}


def _write(root: Path) -> Path:
    for sub in ("rgb", "depth", "pose", "semantic"):
        (root / sub).mkdir(parents=True)
    for i in range(6):
        stem = f"{SCENE}_{i:06d}"
        cv2.imwrite(str(root / "rgb" / f"{stem}.png"), np.full((H, W, 3), (0, 255, 0), np.uint8))
        if i != 4:  # frame 4 has no depth
            cv2.imwrite(
                str(root / "depth" / f"{stem}.png"),
                np.full((H, W), round(DEPTH_M * 1000), np.uint16),
            )
        if i in HAB_POSES:
            text = "\t".join(repr(float(v)) for v in HAB_POSES[i].reshape(-1)) + "\n"
        elif i == 3:
            text = "\t".join(["nan"] * 16)
        else:  # older exports: "x y z qx qy qz qw", one value per line
            text = "\n".join(["3.0", "1.2", "4.0", "0", "0", "0", "1"])
        (root / "pose" / f"{stem}.txt").write_text(text)
    ids = np.zeros((H, W), np.int32)
    ids[10:20, 10:20] = 5
    ids[30:, :] = 7
    np.save(root / "semantic" / f"{SCENE}_000000.npy", ids)
    labels = 'HM3D Semantic Annotations\n3,9E9E9E,"wall",0\n5,AABBCC,"chair",1\n'
    (root / f"{SCENE}.semantic.txt").write_text(labels)
    return root


def _backproject(frame: Frame, u: int, v: int) -> np.ndarray:
    k = frame.intrinsics
    z = float(frame.depth[v, u])
    return frame.pose.transform_points(
        np.array([[(u - k.cx) / k.fx * z, (v - k.cy) / k.fy * z, z]])
    )[0]


def test_layout_is_detected_and_frames_are_matched_by_stem(tmp_path: Path) -> None:
    root = _write(tmp_path / f"00824-{SCENE}")
    assert detect_format(root) == "hm3d"
    reader = open_dataset(root)
    assert isinstance(reader, Hm3dReader)
    assert reader.frame_ids == [f"{SCENE}_{i:06d}" for i in (0, 1, 2, 5)]
    assert "invalid pose" in reader.skipped[f"{SCENE}_000003"]
    assert "no depth" in reader.skipped[f"{SCENE}_000004"]
    assert reader.intrinsics.fx == pytest.approx(W / 2) and reader.intrinsics.depth_scale == 1000
    f = reader.read(0)
    assert f.depth[0, 0] == pytest.approx(DEPTH_M) and tuple(f.rgb[0, 0]) == (0, 255, 0)


def test_poses_become_z_up_with_opencv_camera_axes(tmp_path: Path) -> None:
    reader = Hm3dReader(_write(tmp_path / "walk"))
    level, turned, down, old = (reader.read(i).pose for i in range(4))
    # Habitat (1, 1.5, -2), facing -z: z-up world (1, 2, 1.5), facing +y, image down = -z.
    assert np.allclose(level.translation, [1.0, 2.0, 1.5])
    assert np.allclose(level.rotation[:, 2], [0, 1, 0]) and np.allclose(
        level.rotation[:, 1], [0, 0, -1]
    )
    # A left turn (+90° about up) faces -x, counter-clockwise seen from above.
    assert np.allclose(turned.rotation[:, 2], [-1, 0, 0]) and turned.translation[
        2
    ] == pytest.approx(1.5)
    # Pitching down tilts the optical axis below the horizon.
    assert down.rotation[2, 2] == pytest.approx(-math.sin(math.radians(30)))
    # The 7-number pose format: identity rotation at Habitat (3, 1.2, 4).
    assert np.allclose(old.translation, [3.0, -4.0, 1.2])


@pytest.mark.parametrize("index", [0, 1, 2])
def test_known_habitat_point_back_projects_to_the_same_world_point(
    tmp_path: Path, index: int
) -> None:
    frame = Hm3dReader(_write(tmp_path / "walk")).read(index)
    u, v = 10, 40
    k = habitat_intrinsics(W, H)
    # The point Habitat's OpenGL camera sees at pixel (u, v), 2.5 m in front (-z forward, y up).
    p_gl = np.array([(u - k.cx) / k.fx * DEPTH_M, -(v - k.cy) / k.fy * DEPTH_M, -DEPTH_M, 1.0])
    x, y, z = (HAB_POSES[index] @ p_gl)[:3]
    assert np.allclose(_backproject(frame, u, v), [x, -z, y])


def test_semantic_ids_become_instances_with_labels_of_this_frame(tmp_path: Path) -> None:
    reader = Hm3dReader(_write(tmp_path / "walk"))
    f = reader.read(0)
    assert f.instances is not None and f.instances.dtype == np.uint16
    assert f.instances[15, 15] == 5 and f.instances[40, 0] == 7
    assert f.instance_labels == {5: "chair"}  # wall (3) is not in view, 7 has no label
    assert reader.read(1).instances is None


def test_malformed_inputs(tmp_path: Path) -> None:
    root = _write(tmp_path / "walk")
    np.save(root / "semantic" / f"{SCENE}_000001.npy", np.full((H, W), 70000, np.int64))
    with pytest.raises(FrameError, match=r"0\.\.65535"):
        Hm3dReader(root).read(1)
    (root / "pose" / f"{SCENE}_000002.txt").write_text("1 2 3 4 5")
    with pytest.raises(DatasetError, match=rf"{SCENE}_000002\.txt: expected 16"):
        Hm3dReader(root)
    with pytest.raises(DatasetError, match="hfov_deg"):
        habitat_intrinsics(W, H, 180.0)
    (root / f"{SCENE}.semantic.txt").write_text("HM3D Semantic Annotations\nbroken line\n")
    with pytest.raises(DatasetError, match=r"semantic\.txt:2"):
        Hm3dReader(root)
