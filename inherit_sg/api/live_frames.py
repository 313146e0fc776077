"""Decoding of the parts of a posted live frame: images, pose, intrinsics and instance
labels. Every problem raises FrameError (400) naming the form field that is wrong."""

from __future__ import annotations

import json
import re
from typing import Any

import cv2
import numpy as np

from inherit_sg.errors import FrameError
from inherit_sg.model import Intrinsics, Pose

_SEPARATORS = re.compile(r"[\s,]+")


def parse_pose(text: str) -> Pose:
    """``T_world_camera`` from 16 numbers (row-major, separated by spaces and/or commas)
    or a JSON 4x4 list of rows."""
    raw = text.strip()
    try:
        if raw.startswith("["):
            values: Any = json.loads(raw)
            matrix = np.asarray(values, dtype=np.float64)
            if matrix.shape == (16,):
                matrix = matrix.reshape(4, 4)
        else:
            matrix = np.asarray([float(v) for v in _SEPARATORS.split(raw) if v], dtype=np.float64)
            if matrix.shape != (16,):
                raise FrameError(f"pose: expected 16 numbers, got {matrix.size}")
            matrix = matrix.reshape(4, 4)
        return Pose.from_matrix(matrix)
    except FrameError as exc:
        msg = exc.message if exc.message.startswith("pose") else f"pose: {exc.message}"
        raise FrameError(msg) from None
    except (ValueError, TypeError) as exc:
        raise FrameError(f"pose: expected 16 numbers or a 4x4 JSON list ({exc})") from None


def parse_intrinsics(text: str) -> Intrinsics:
    """Intrinsics from the ``intrinsics.json`` form
    ``{"width","height","fx","fy","cx","cy","depth_scale"}``."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise FrameError(f"intrinsics: invalid JSON ({exc})") from None
    if not isinstance(data, dict):
        raise FrameError("intrinsics: expected a JSON object")
    try:
        return Intrinsics.from_dict(data)
    except FrameError as exc:
        raise FrameError(f"intrinsics: {exc.message}") from None
    except (ValueError, TypeError) as exc:
        raise FrameError(f"intrinsics: values must be numbers ({exc})") from None


def parse_instance_labels(text: str) -> dict[int, str]:
    """``{"<instance id>": "label" | {"label": ...}}`` as in ``instances.json``."""
    try:
        data = json.loads(text)
        if not isinstance(data, dict):
            raise TypeError("expected a JSON object")
        return {int(k): str(v["label"] if isinstance(v, dict) else v) for k, v in data.items()}
    except (json.JSONDecodeError, KeyError, ValueError, TypeError) as exc:
        raise FrameError(f"instance_labels: malformed ({exc})") from None


def _decode(data: bytes, field: str, flags: int) -> np.ndarray:
    if not data:
        raise FrameError(f"{field}: empty file")
    try:
        img = cv2.imdecode(np.frombuffer(data, dtype=np.uint8), flags)
    except cv2.error:
        img = None
    if img is None:
        raise FrameError(f"{field}: not a decodable PNG or JPEG image")
    return img


def decode_rgb(data: bytes) -> np.ndarray:
    """An RGB uint8 image from PNG or JPEG bytes."""
    bgr = _decode(data, "rgb", cv2.IMREAD_COLOR)
    return cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)


def decode_depth(data: bytes) -> np.ndarray:
    """Raw depth units (uint16, single channel) from PNG bytes."""
    img = _decode(data, "depth", cv2.IMREAD_UNCHANGED)
    if img.ndim != 2 or img.dtype != np.uint16:
        raise FrameError(
            f"depth: expected a single-channel uint16 PNG, got {img.dtype} with shape {img.shape}"
        )
    return img


def decode_instances(data: bytes) -> np.ndarray:
    """A per-pixel instance id image (uint8 or uint16, single channel) as uint16."""
    img = _decode(data, "instances", cv2.IMREAD_UNCHANGED)
    if img.ndim != 2 or img.dtype not in (np.uint8, np.uint16):
        raise FrameError(
            f"instances: expected a single-channel uint16 PNG, got {img.dtype} "
            f"with shape {img.shape}"
        )
    return img.astype(np.uint16, copy=False)
