"""Frozen value types: camera pose, pinhole intrinsics and axis-aligned 3D boxes.

Conventions (DESIGN.md §4): world frame right-handed, z up, metres; poses are
``T_world_camera`` with the OpenCV camera axes (x right, y down, z forward).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from inherit_sg.errors import FrameError

Vec3 = tuple[float, float, float]


# The farthest a camera may be from the map's origin on any axis (metres): a building,
# or a campus, fits well inside; a pose beyond it is a broken one (1e308).
MAX_POSITION_M = 10_000.0


def _vec3(values: Iterable[float], what: str) -> Vec3:
    out = tuple(float(v) for v in values)
    if len(out) != 3 or not all(math.isfinite(v) for v in out):
        raise ValueError(f"{what} must be 3 finite numbers, got {out!r}")
    return (out[0], out[1], out[2])


@dataclass(frozen=True)
class Pose:
    """Rigid transform ``T_world_camera`` stored row-major as 16 floats."""

    matrix16: tuple[float, ...]

    def __post_init__(self) -> None:
        if len(self.matrix16) != 16:
            raise FrameError(f"pose needs 16 numbers, got {len(self.matrix16)}")
        m = np.asarray(self.matrix16, dtype=np.float64).reshape(4, 4)
        if not np.all(np.isfinite(m)):
            raise FrameError("pose contains NaN or infinite values")
        if not np.allclose(m[3], [0.0, 0.0, 0.0, 1.0], atol=1e-6):
            raise FrameError(f"pose last row must be [0 0 0 1], got {m[3].tolist()}")
        r = m[:3, :3]
        if not np.allclose(r @ r.T, np.eye(3), atol=1e-3) or np.linalg.det(r) < 0:
            raise FrameError("pose rotation is not a proper rotation matrix")
        far = float(np.abs(m[:3, 3]).max())
        if far > MAX_POSITION_M:
            raise FrameError(
                f"pose translation {far:.3g} m is implausible: positions must lie within "
                f"{MAX_POSITION_M:g} m of the map's origin"
            )

    @classmethod
    def from_matrix(cls, matrix: np.ndarray | Sequence[Sequence[float]]) -> Pose:
        """Build from a 4×4 array-like."""
        m = np.asarray(matrix, dtype=np.float64)
        if m.shape != (4, 4):
            raise FrameError(f"pose must be 4x4, got shape {m.shape}")
        return cls(tuple(float(v) for v in m.reshape(-1)))

    @classmethod
    def identity(cls) -> Pose:
        """The identity transform."""
        return cls.from_matrix(np.eye(4))

    @property
    def matrix(self) -> np.ndarray:
        """4×4 float64 copy of the transform."""
        return np.asarray(self.matrix16, dtype=np.float64).reshape(4, 4)

    @property
    def translation(self) -> np.ndarray:
        """Camera centre in world coordinates."""
        return self.matrix[:3, 3]

    @property
    def rotation(self) -> np.ndarray:
        """3×3 rotation world←camera."""
        return self.matrix[:3, :3]

    def transform_points(self, points: np.ndarray) -> np.ndarray:
        """Map (N, 3) camera-frame points into the world frame."""
        m = self.matrix
        return np.asarray(points, dtype=np.float64) @ m[:3, :3].T + m[:3, 3]

    def to_list(self) -> list[float]:
        """Row-major list of 16 floats (for JSON and storage)."""
        return list(self.matrix16)


@dataclass(frozen=True)
class Intrinsics:
    """Pinhole intrinsics plus the depth image scale (units per metre)."""

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float
    depth_scale: float = 1000.0

    def __post_init__(self) -> None:
        if self.width <= 0 or self.height <= 0:
            raise FrameError(f"image size must be positive, got {self.width}x{self.height}")
        for name in ("fx", "fy", "cx", "cy", "depth_scale"):
            v = getattr(self, name)
            if not math.isfinite(v):
                raise FrameError(f"intrinsics {name} is not finite")
        if self.fx <= 0 or self.fy <= 0 or self.depth_scale <= 0:
            raise FrameError("fx, fy and depth_scale must be positive")

    @property
    def matrix(self) -> np.ndarray:
        """3×3 camera matrix K."""
        return np.array([[self.fx, 0, self.cx], [0, self.fy, self.cy], [0, 0, 1]], dtype=float)

    def scaled(self, factor: float) -> Intrinsics:
        """Intrinsics for the image resized by ``factor`` (e.g. 0.5 halves the size)."""
        return Intrinsics(
            width=max(1, round(self.width * factor)),
            height=max(1, round(self.height * factor)),
            fx=self.fx * factor,
            fy=self.fy * factor,
            cx=(self.cx + 0.5) * factor - 0.5,
            cy=(self.cy + 0.5) * factor - 0.5,
            depth_scale=self.depth_scale,
        )

    def to_dict(self) -> dict[str, float | int]:
        """The ``intrinsics.json`` form of DESIGN.md §4."""
        return {
            "width": self.width,
            "height": self.height,
            "fx": self.fx,
            "fy": self.fy,
            "cx": self.cx,
            "cy": self.cy,
            "depth_scale": self.depth_scale,
        }

    @classmethod
    def from_dict(cls, data: dict[str, float | int]) -> Intrinsics:
        """Parse the ``intrinsics.json`` form; missing keys raise FrameError."""
        try:
            return cls(
                width=int(data["width"]),
                height=int(data["height"]),
                fx=float(data["fx"]),
                fy=float(data["fy"]),
                cx=float(data["cx"]),
                cy=float(data["cy"]),
                depth_scale=float(data.get("depth_scale", 1000.0)),
            )
        except KeyError as exc:
            raise FrameError(f"intrinsics missing key {exc.args[0]!r}") from None
        except (TypeError, ValueError) as exc:  # "fx": "abc", "width": null
            raise FrameError(f"intrinsics values must be numbers ({exc})") from None


@dataclass(frozen=True)
class BBox3D:
    """Axis-aligned box in the world frame."""

    min: tuple[float, ...]
    max: tuple[float, ...]

    def __post_init__(self) -> None:
        lo = _vec3(self.min, "bbox min")
        hi = _vec3(self.max, "bbox max")
        if any(a > b for a, b in zip(lo, hi, strict=True)):
            raise ValueError(f"bbox min {lo} exceeds max {hi}")
        object.__setattr__(self, "min", lo)
        object.__setattr__(self, "max", hi)

    @classmethod
    def from_points(cls, points: np.ndarray) -> BBox3D:
        """Tight box around (N, 3) points."""
        pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        if len(pts) == 0:
            raise ValueError("cannot box an empty point set")
        return cls(tuple(pts.min(axis=0)), tuple(pts.max(axis=0)))

    @classmethod
    def from_center_size(cls, center: Sequence[float], size: Sequence[float]) -> BBox3D:
        """Box from its centre and full extent."""
        c = np.asarray(center, dtype=float)
        h = np.asarray(size, dtype=float) / 2.0
        return cls(tuple(c - h), tuple(c + h))

    @property
    def center(self) -> np.ndarray:
        """Box centre."""
        return (np.asarray(self.min) + np.asarray(self.max)) / 2.0

    @property
    def size(self) -> np.ndarray:
        """Full extent along x, y, z."""
        return np.asarray(self.max) - np.asarray(self.min)

    @property
    def volume(self) -> float:
        """Volume in m³."""
        return float(np.prod(self.size))

    def contains(self, point: Sequence[float], margin: float = 0.0) -> bool:
        """Whether ``point`` lies inside the box grown by ``margin``."""
        p = np.asarray(point, dtype=float)
        return bool(
            np.all(p >= np.asarray(self.min) - margin)
            and np.all(p <= np.asarray(self.max) + margin)
        )

    def intersection_volume(self, other: BBox3D) -> float:
        """Volume of the overlap with ``other``."""
        lo = np.maximum(self.min, other.min)
        hi = np.minimum(self.max, other.max)
        return float(np.prod(np.clip(hi - lo, 0.0, None)))

    def iou(self, other: BBox3D) -> float:
        """Volumetric intersection over union (0 for degenerate boxes)."""
        inter = self.intersection_volume(other)
        union = self.volume + other.volume - inter
        return inter / union if union > 0 else 0.0

    def union(self, other: BBox3D) -> BBox3D:
        """Smallest box containing both."""
        lo = np.minimum(self.min, other.min)
        hi = np.maximum(self.max, other.max)
        return BBox3D(tuple(lo), tuple(hi))
