"""The one RGB-D frame type every reader yields and every stream consumes."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from inherit_sg.errors import FrameError
from inherit_sg.model.values import Intrinsics, Pose


@dataclass
class Frame:
    """A posed RGB-D observation.

    ``rgb`` is (H, W, 3) uint8 in RGB order; ``depth`` is (H, W) float32 metres with 0 for
    no reading; ``pose`` is ``T_world_camera`` (z-up world, OpenCV camera). ``instances``
    (optional) is (H, W) uint16 with 0 = none, and ``instance_labels`` maps the ids of
    *this frame* to labels: ids mean nothing across frames.
    """

    index: int
    frame_id: str
    timestamp: float
    rgb: np.ndarray
    depth: np.ndarray
    pose: Pose
    intrinsics: Intrinsics
    instances: np.ndarray | None = None
    instance_labels: dict[int, str] = field(default_factory=dict)

    def validate(self) -> Frame:
        """Check shapes and values against the intrinsics; raise FrameError naming the
        frame and what is wrong. Returns self so readers can chain it."""
        h, w = self.intrinsics.height, self.intrinsics.width
        name = f"frame {self.frame_id!r}"
        if self.rgb.ndim != 3 or self.rgb.shape[2] != 3:
            raise FrameError(f"{name}: rgb must be HxWx3, got shape {self.rgb.shape}")
        if self.rgb.shape[:2] != (h, w):
            raise FrameError(
                f"{name}: rgb is {self.rgb.shape[1]}x{self.rgb.shape[0]}, intrinsics say {w}x{h}"
            )
        if self.rgb.dtype != np.uint8:
            raise FrameError(f"{name}: rgb must be uint8, got {self.rgb.dtype}")
        if self.depth.shape != (h, w):
            raise FrameError(f"{name}: depth is {self.depth.shape[::-1]}, intrinsics say {w}x{h}")
        if not np.issubdtype(self.depth.dtype, np.floating):
            raise FrameError(f"{name}: depth must be float metres, got {self.depth.dtype}")
        if np.isnan(self.depth).any() or (self.depth < 0).any():
            raise FrameError(f"{name}: depth has NaN or negative values")
        if self.instances is not None and self.instances.shape != (h, w):
            raise FrameError(
                f"{name}: instance image is {self.instances.shape[::-1]}, expected {w}x{h}"
            )
        return self

    @property
    def has_instances(self) -> bool:
        """Whether the frame carries a per-pixel instance image."""
        return self.instances is not None
