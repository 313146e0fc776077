"""Coordinate conversions shared by the readers.

Target conventions (DESIGN.md §4): world frame right-handed, z up, metres; poses are
``T_world_camera`` with OpenCV camera axes (x right, y down, z forward).

Source conventions handled here:

* **y-up worlds** (Habitat, many OpenGL tools): x right, y up, z towards the viewer. The
  rotation ``(x, y, z) -> (x, -z, y)`` (+90° about x) keeps x, sends y-up to z-up and
  keeps the frame right-handed.
* **OpenGL cameras** (Habitat sensors, NeRF/Blender): x right, y up, z backward. Flipping
  the camera's y and z axes (right-multiplying by ``diag(1, -1, -1, 1)``) gives OpenCV.
* **translation + quaternion** poses (TUM ``tx ty tz qx qy qz qw``, scalar last).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

from inherit_sg.errors import FrameError
from inherit_sg.model import Pose

#: World transform from a y-up frame to our z-up frame: (x, y, z) -> (x, -z, y).
Y_UP_TO_Z_UP = np.array(
    [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, -1.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
)

#: Camera-axes change between OpenGL (x right, y up, z back) and OpenCV (x right, y down,
#: z forward). It is its own inverse.
OPENGL_TO_OPENCV = np.diag([1.0, -1.0, -1.0, 1.0])

#: Largest deviation from orthonormality that :func:`to_pose` repairs (text round-off);
#: anything worse is a broken pose, not round-off.
ORTHONORMAL_TOLERANCE = 1e-2


def y_up_to_z_up(matrix: np.ndarray) -> np.ndarray:
    """Re-express a 4×4 ``T_world_x`` given in a y-up world in the z-up world."""
    return Y_UP_TO_Z_UP @ np.asarray(matrix, dtype=np.float64)


def opengl_to_opencv_camera(matrix: np.ndarray) -> np.ndarray:
    """Turn a 4×4 ``T_world_camera`` with OpenGL camera axes into OpenCV camera axes."""
    return np.asarray(matrix, dtype=np.float64) @ OPENGL_TO_OPENCV


def habitat_to_world(matrix: np.ndarray) -> np.ndarray:
    """Habitat sensor pose (y-up world, OpenGL camera) -> z-up world, OpenCV camera."""
    return opengl_to_opencv_camera(y_up_to_z_up(matrix))


def matrix_from_tq(translation: Sequence[float], quat_xyzw: Sequence[float]) -> np.ndarray:
    """4×4 transform from a translation and a scalar-last quaternion (normalised here)."""
    q = np.asarray(quat_xyzw, dtype=np.float64)
    norm = float(np.linalg.norm(q))
    if not np.isfinite(norm) or norm < 1e-9:
        raise FrameError(f"quaternion {q.tolist()} is zero or not finite")
    out = np.eye(4)
    out[:3, :3] = Rotation.from_quat(q / norm).as_matrix()
    out[:3, 3] = np.asarray(translation, dtype=np.float64)
    return out


def interpolate_matrix(m0: np.ndarray, m1: np.ndarray, alpha: float) -> np.ndarray:
    """Pose between ``m0`` (alpha 0) and ``m1`` (alpha 1): lerp translation, slerp rotation."""
    rotations = Rotation.from_matrix(np.stack([m0[:3, :3], m1[:3, :3]]))
    out = np.eye(4)
    out[:3, :3] = Slerp([0.0, 1.0], rotations)([alpha]).as_matrix()[0]
    out[:3, 3] = (1.0 - alpha) * m0[:3, 3] + alpha * m1[:3, 3]
    return out


def is_finite_matrix(matrix: np.ndarray) -> bool:
    """Whether every entry is finite (ScanNet marks lost tracking with ``-inf`` rows)."""
    return bool(np.all(np.isfinite(matrix)))


def to_pose(matrix: np.ndarray) -> Pose:
    """Build a :class:`Pose`, projecting a rotation that is off only by text round-off onto
    the nearest rotation. Raises FrameError for non-finite or clearly non-rigid input."""
    m = np.asarray(matrix, dtype=np.float64).copy()
    if m.shape != (4, 4):
        raise FrameError(f"pose must be 4x4, got shape {m.shape}")
    if not is_finite_matrix(m):
        raise FrameError("pose contains NaN or infinite values")
    r = m[:3, :3]
    if np.abs(r @ r.T - np.eye(3)).max() <= ORTHONORMAL_TOLERANCE and np.linalg.det(r) > 0:
        u, _, vt = np.linalg.svd(r)
        m[:3, :3] = u @ vt
    return Pose.from_matrix(m)
