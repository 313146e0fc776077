"""Coordinate conversions shared by the dataset readers."""

from __future__ import annotations

import math

import numpy as np
import pytest

from inherit_sg.errors import FrameError
from inherit_sg.ingest.readers.convert import (
    OPENGL_TO_OPENCV,
    Y_UP_TO_Z_UP,
    habitat_to_world,
    interpolate_matrix,
    is_finite_matrix,
    matrix_from_tq,
    opengl_to_opencv_camera,
    to_pose,
    y_up_to_z_up,
)


def test_y_up_to_z_up_is_a_proper_rotation_sending_up_to_z() -> None:
    r = Y_UP_TO_Z_UP[:3, :3]
    assert np.allclose(r @ r.T, np.eye(3))
    assert np.linalg.det(r) == pytest.approx(1.0)
    assert np.allclose(r @ [0, 1, 0], [0, 0, 1])  # y-up becomes z-up
    assert np.allclose(r @ [1, 0, 0], [1, 0, 0])  # x is kept
    assert np.allclose(r @ [0, 0, -1], [0, 1, 0])  # y-up "forward" (-z) becomes +y


def test_opengl_to_opencv_flips_camera_y_and_z_and_is_its_own_inverse() -> None:
    assert np.allclose(OPENGL_TO_OPENCV @ OPENGL_TO_OPENCV, np.eye(4))
    out = opengl_to_opencv_camera(np.eye(4))
    assert np.allclose(out[:3, 1], [0, -1, 0]) and np.allclose(out[:3, 2], [0, 0, -1])


def test_habitat_identity_pose_faces_plus_y_level_with_the_floor() -> None:
    hab = np.eye(4)
    hab[:3, 3] = [1.0, 1.5, -2.0]  # 1.5 m above the floor in Habitat's y-up world
    world = habitat_to_world(hab)
    assert np.allclose(world[:3, 3], [1.0, 2.0, 1.5])
    assert np.allclose(world[:3, 2], [0, 1, 0])  # optical axis (OpenCV z) is horizontal
    assert np.allclose(world[:3, 1], [0, 0, -1])  # image down is world down
    assert np.allclose(world[:3, 0], [1, 0, 0])
    assert np.allclose(y_up_to_z_up(hab)[:3, 3], [1.0, 2.0, 1.5])


def test_matrix_from_tq_normalises_scalar_last_quaternions() -> None:
    s = math.sqrt(0.5)
    m = matrix_from_tq([1, 2, 3], [0, 0, 2 * s, 2 * s])  # 90° about z, not unit length
    assert np.allclose(m[:3, :3] @ [1, 0, 0], [0, 1, 0])
    assert np.allclose(m[:3, 3], [1, 2, 3])
    with pytest.raises(FrameError, match="quaternion"):
        matrix_from_tq([0, 0, 0], [0, 0, 0, 0])


def test_interpolate_matrix_lerps_translation_and_slerps_rotation() -> None:
    m0 = np.eye(4)
    m1 = matrix_from_tq([2, 0, 0], [0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4)])
    mid = interpolate_matrix(m0, m1, 0.5)
    assert np.allclose(mid[:3, 3], [1, 0, 0])
    angle = math.degrees(math.atan2(mid[1, 0], mid[0, 0]))
    assert angle == pytest.approx(45.0)


def test_to_pose_repairs_round_off_but_rejects_broken_matrices() -> None:
    m = np.eye(4)
    m[:3, :3] += 1e-4 * np.array([[0, 1, 0], [0, 0, 1], [1, 0, 0]])
    pose = to_pose(m)
    assert np.allclose(pose.rotation @ pose.rotation.T, np.eye(3), atol=1e-9)
    bad = np.eye(4)
    bad[0, 3] = -np.inf
    assert not is_finite_matrix(bad)
    with pytest.raises(FrameError, match="NaN or infinite"):
        to_pose(bad)
    with pytest.raises(FrameError, match="rotation"):
        to_pose(np.diag([2.0, 2.0, 2.0, 1.0]))
