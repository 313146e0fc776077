"""Fields of deserialised ROS messages (from ``rosbags``) to numpy: stamps, images, depth,
camera intrinsics and poses. ROS 1 and ROS 2 spell some fields differently (``K`` / ``k``);
both are read. Nothing here parses a bag: ``rosbags`` does that.
"""

from __future__ import annotations

from typing import Any

import cv2
import numpy as np

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers.convert import matrix_from_tq
from inherit_sg.model import Intrinsics

IMAGE = "sensor_msgs/msg/Image"
COMPRESSED_IMAGE = "sensor_msgs/msg/CompressedImage"
CAMERA_INFO = "sensor_msgs/msg/CameraInfo"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
POSE_STAMPED = "geometry_msgs/msg/PoseStamped"
POSE_WITH_COVARIANCE = "geometry_msgs/msg/PoseWithCovarianceStamped"
TRANSFORM_STAMPED = "geometry_msgs/msg/TransformStamped"
ODOMETRY = "nav_msgs/msg/Odometry"
#: Message types one topic of camera poses may have.
POSE_TYPES = (POSE_STAMPED, POSE_WITH_COVARIANCE, TRANSFORM_STAMPED, ODOMETRY)

#: Colour encodings: (channels, OpenCV conversion to RGB or None when already RGB).
_COLOUR: dict[str, tuple[int, int | None]] = {
    "rgb8": (3, None),
    "bgr8": (3, cv2.COLOR_BGR2RGB),
    "8uc3": (3, cv2.COLOR_BGR2RGB),
    "rgba8": (4, cv2.COLOR_RGBA2RGB),
    "bgra8": (4, cv2.COLOR_BGRA2RGB),
    "8uc4": (4, cv2.COLOR_BGRA2RGB),
    "mono8": (1, cv2.COLOR_GRAY2RGB),
    "8uc1": (1, cv2.COLOR_GRAY2RGB),
}
_DEPTH_16 = ("16uc1", "mono16")
_DEPTH_32 = ("32fc1",)

#: Camera axes of a REP 103 body frame (x forward, y left, z up) -> OpenCV optical axes
#: (x right, y down, z forward): ``T_world_optical = T_world_body @ BODY_FROM_OPTICAL``.
BODY_FROM_OPTICAL = np.array(
    [[0.0, 0.0, 1.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
)


def stamp_ns(msg: Any) -> int:
    """A message's ``header.stamp`` in nanoseconds (0 when it has none)."""
    header = getattr(msg, "header", None)
    stamp = getattr(header, "stamp", None)
    if stamp is None:
        return 0
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def frame_name(name: str) -> str:
    """A TF frame name without the leading ``/`` ROS 1 often writes."""
    return name.lstrip("/")


def _pixels(msg: Any, dtype: np.dtype[Any], channels: int) -> np.ndarray:
    """The (H, W[, C]) array of a ``sensor_msgs/Image``, honouring ``step`` padding and
    byte order."""
    height, width, step = int(msg.height), int(msg.width), int(msg.step)
    item = dtype.itemsize * channels
    raw = np.asarray(msg.data, dtype=np.uint8)
    if height <= 0 or width <= 0 or step < width * item or raw.size < height * step:
        raise FrameError(
            f"image message of {width}x{height} ({msg.encoding}) has step {step} and "
            f"{raw.size} bytes: too few"
        )
    rows = raw[: height * step].reshape(height, step)[:, : width * item]
    stored = dtype.newbyteorder(">" if int(msg.is_bigendian) else "<")
    values = np.ascontiguousarray(rows).view(stored)
    shape = (height, width) if channels == 1 else (height, width, channels)
    return values.reshape(shape).astype(dtype.newbyteorder("="), copy=False)


def image_to_rgb(msg: Any) -> np.ndarray:
    """(H, W, 3) uint8 RGB from a ``sensor_msgs/Image`` in rgb8, bgr8, rgba8, bgra8 or
    mono8; FrameError for other encodings."""
    encoding = str(msg.encoding).lower()
    if encoding not in _COLOUR:
        raise FrameError(
            f"colour image encoding {msg.encoding!r} is not supported "
            f"(known: rgb8, bgr8, rgba8, bgra8, mono8)"
        )
    channels, conversion = _COLOUR[encoding]
    pixels = _pixels(msg, np.dtype(np.uint8), channels)
    if conversion is None:
        return np.ascontiguousarray(pixels)
    return cv2.cvtColor(pixels, conversion)


def image_to_depth(msg: Any, metres_per_unit: float) -> np.ndarray:
    """(H, W) float32 metres from a 16UC1 (times ``metres_per_unit``) or 32FC1 (metres)
    ``sensor_msgs/Image``; NaN, infinite and negative readings become 0 (no reading)."""
    encoding = str(msg.encoding).lower()
    if encoding in _DEPTH_16:
        raw = _pixels(msg, np.dtype(np.uint16), 1)
        # divide by units per metre, as the file readers do, so equal images give equal depth
        return raw.astype(np.float32) / np.float32(1.0 / metres_per_unit)
    if encoding in _DEPTH_32:
        depth = _pixels(msg, np.dtype(np.float32), 1).copy()
        depth[~np.isfinite(depth) | (depth < 0)] = 0.0
        return depth
    raise FrameError(f"depth image encoding {msg.encoding!r} is not supported (16UC1 or 32FC1)")


def compressed_to_rgb(msg: Any) -> np.ndarray:
    """(H, W, 3) uint8 RGB from a ``sensor_msgs/CompressedImage`` (JPEG or PNG)."""
    if "compresseddepth" in str(msg.format).lower():
        raise FrameError(f"{msg.format!r} is a compressed depth image, not a colour image")
    data = np.frombuffer(np.asarray(msg.data, dtype=np.uint8).tobytes(), dtype=np.uint8)
    image = cv2.imdecode(data, cv2.IMREAD_COLOR)
    if image is None:
        raise FrameError(f"cannot decode compressed image (format {msg.format!r})")
    return cv2.cvtColor(image, cv2.COLOR_BGR2RGB)


def image_size(msgtype: str, msg: Any) -> tuple[int, int]:
    """(width, height) of an image message (decodes a compressed one)."""
    if msgtype == COMPRESSED_IMAGE:
        rgb = compressed_to_rgb(msg)
        return rgb.shape[1], rgb.shape[0]
    return int(msg.width), int(msg.height)


def _field(msg: Any, name: str) -> Any:
    """``msg.k`` (ROS 2) or ``msg.K`` (ROS 1)."""
    value = getattr(msg, name, None)
    return getattr(msg, name.upper()) if value is None else value


def intrinsics_from_camera_info(msg: Any, depth_scale: float) -> Intrinsics:
    """Pinhole intrinsics from a ``sensor_msgs/CameraInfo`` (its ``K`` matrix);
    ``depth_scale`` is the depth units per metre to record."""
    k = np.asarray(_field(msg, "k"), dtype=np.float64).reshape(-1)
    if k.size != 9 or k[0] <= 0 or k[4] <= 0:
        raise DatasetError(f"camera info has no valid K matrix: {k.tolist()}")
    fx, fy, cx, cy = float(k[0]), float(k[4]), float(k[2]), float(k[5])
    return Intrinsics(int(msg.width), int(msg.height), fx, fy, cx, cy, depth_scale)


def distortion(msg: Any) -> list[float]:
    """The camera info's distortion coefficients ``D``."""
    return [float(v) for v in np.asarray(_field(msg, "d"), dtype=np.float64).reshape(-1)]


def _tq(translation: Any, rotation: Any) -> np.ndarray:
    t = [translation.x, translation.y, translation.z]
    return matrix_from_tq(t, [rotation.x, rotation.y, rotation.z, rotation.w])


def pose_message_matrix(msgtype: str, msg: Any) -> np.ndarray:
    """4×4 ``T_frame_child`` of a PoseStamped, PoseWithCovarianceStamped, Odometry or
    TransformStamped message."""
    if msgtype == TRANSFORM_STAMPED:
        return transform_matrix(msg)
    pose = msg.pose if msgtype == POSE_STAMPED else msg.pose.pose
    return _tq(pose.position, pose.orientation)


def pose_child_frame(msgtype: str, msg: Any) -> str:
    """The frame a pose message places (``child_frame_id``), '' when the type has none."""
    if msgtype in (TRANSFORM_STAMPED, ODOMETRY):
        return frame_name(str(msg.child_frame_id))
    return ""


def transform_matrix(msg: Any) -> np.ndarray:
    """4×4 ``T_parent_child`` of a ``geometry_msgs/TransformStamped``."""
    return _tq(msg.transform.translation, msg.transform.rotation)
