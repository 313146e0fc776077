"""TUM RGB-D sequences (``rgbd_dataset_freiburg*``).

```
rgb.txt          "timestamp rgb/<timestamp>.png" lines, '#' comments
depth.txt        "timestamp depth/<timestamp>.png" lines (uint16, 5000 units per metre)
groundtruth.txt  "timestamp tx ty tz qx qy qz qw" (colour optical centre in the mocap world)
```

Each depth image is paired with the colour image nearest in time (one-to-one, within
``max_dt``, 0.02 s by default, as TUM's ``associate.py``). The frame's timestamp is the
depth image's; its pose is interpolated there between the two ground-truth samples around
it when both are within ``max_dt`` (linear translation, slerp rotation), else taken from
the nearest sample within ``max_dt``; pairs with no such pose are left out (``skipped``).

Intrinsics: the calibrated freiburg1/2/3 colour cameras from TUM's documentation, picked
from the folder name (``rgbd_dataset_freiburg1_xyz`` -> fr1), else the ROS default
(525, 525, 319.5, 239.5); ``camera=`` or ``intrinsics=`` override the choice.

World frame: TUM ground truth lives in the motion-capture frame, which is not z-up in
general. Poses are kept in that recorded frame; pass ``world_from_recorded`` (a 4×4
rigid transform, e.g. a gravity alignment you measured) to re-express them.
"""

from __future__ import annotations

import bisect
import math
import re
from pathlib import Path

import numpy as np

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers.base import IndexedReader
from inherit_sg.ingest.readers.convert import interpolate_matrix, matrix_from_tq, to_pose
from inherit_sg.ingest.readers.images import read_depth, read_rgb
from inherit_sg.model import Frame, Intrinsics, Pose

TUM_DEPTH_SCALE = 5000.0
TUM_CAMERAS: dict[str, Intrinsics] = {
    "fr1": Intrinsics(640, 480, 517.3, 516.5, 318.6, 255.3, TUM_DEPTH_SCALE),
    "fr2": Intrinsics(640, 480, 520.9, 521.0, 325.1, 249.7, TUM_DEPTH_SCALE),
    "fr3": Intrinsics(640, 480, 535.4, 539.2, 320.1, 247.6, TUM_DEPTH_SCALE),
    "default": Intrinsics(640, 480, 525.0, 525.0, 319.5, 239.5, TUM_DEPTH_SCALE),
}
_FREIBURG = re.compile(r"freiburg([123])")


def camera_from_path(path: Path) -> str:
    """``fr1``/``fr2``/``fr3`` from the first folder name along ``path`` that names one,
    else ``default``."""
    for part in (path.name, *(p.name for p in path.resolve().parents)):
        match = _FREIBURG.search(part.lower())
        if match:
            return f"fr{match.group(1)}"
    return "default"


def _timestamp(text: str, where: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise DatasetError(f"{where}: timestamp {text!r} is not a number") from None
    if not math.isfinite(value):
        raise DatasetError(f"{where}: timestamp {text!r} is not finite")
    return value


def read_file_list(path: Path) -> list[tuple[float, str]]:
    """Parse ``rgb.txt``/``depth.txt`` into (timestamp, relative path), sorted by time."""
    if not path.is_file():
        raise DatasetError(f"missing {path}")
    out: list[tuple[float, str]] = []
    for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        if len(parts) < 2:
            raise DatasetError(f"{path}:{lineno}: expected 'timestamp path'")
        out.append((_timestamp(parts[0], f"{path}:{lineno}"), parts[1]))
    return sorted(out)


def read_groundtruth(path: Path) -> tuple[list[float], list[np.ndarray]]:
    """Parse ``groundtruth.txt`` into sorted timestamps and 4×4 camera-to-world matrices."""
    if not path.is_file():
        raise DatasetError(f"missing {path} (TUM poses come from it)")
    rows: list[tuple[float, np.ndarray]] = []
    for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        where = f"{path}:{lineno}"
        if len(parts) != 8:
            raise DatasetError(f"{where}: expected 'timestamp tx ty tz qx qy qz qw'")
        stamp = _timestamp(parts[0], where)
        try:
            values = [float(v) for v in parts[1:]]
            rows.append((stamp, matrix_from_tq(values[:3], values[3:])))
        except ValueError:
            raise DatasetError(f"{where}: pose values must be numbers") from None
        except FrameError as exc:
            raise DatasetError(f"{where}: {exc.message}") from None
    rows.sort(key=lambda r: r[0])
    return [r[0] for r in rows], [r[1] for r in rows]


def associate(a: list[float], b: list[float], max_dt: float) -> list[tuple[int, int]]:
    """One-to-one pairs (i, j) of sorted timestamp lists with |a[i] - b[j]| < max_dt,
    closest pairs first; returned in order of ``a``."""
    candidates: list[tuple[float, int, int]] = []
    for i, t in enumerate(a):
        j = bisect.bisect_left(b, t - max_dt)
        while j < len(b) and b[j] < t + max_dt:
            candidates.append((abs(b[j] - t), i, j))
            j += 1
    used_a: set[int] = set()
    used_b: set[int] = set()
    pairs: list[tuple[int, int]] = []
    for _, i, j in sorted(candidates):
        if i not in used_a and j not in used_b:
            used_a.add(i)
            used_b.add(j)
            pairs.append((i, j))
    return sorted(pairs)


def pose_at(
    t: float, times: list[float], mats: list[np.ndarray], max_dt: float
) -> np.ndarray | None:
    """Ground-truth pose at time ``t`` (see the module docstring), or None."""
    k = bisect.bisect_left(times, t)
    before = k - 1 if k > 0 else None
    after = k if k < len(times) else None
    if after is not None and times[after] == t:
        return mats[after]
    near_before = before is not None and t - times[before] <= max_dt
    near_after = after is not None and times[after] - t <= max_dt
    if near_before and near_after and before is not None and after is not None:
        alpha = (t - times[before]) / (times[after] - times[before])
        return interpolate_matrix(mats[before], mats[after], alpha)
    if near_before and before is not None:
        return mats[before]
    if near_after and after is not None:
        return mats[after]
    return None


class TumReader(IndexedReader):
    """Reads a TUM RGB-D sequence (see the module docstring)."""

    format_name = "tum"

    def __init__(
        self,
        root: str | Path,
        camera: str | None = None,
        intrinsics: Intrinsics | None = None,
        max_dt: float = 0.02,
        world_from_recorded: np.ndarray | None = None,
    ) -> None:
        super().__init__(root)
        if camera is not None and camera not in TUM_CAMERAS:
            raise DatasetError(f"unknown TUM camera {camera!r}; known: {', '.join(TUM_CAMERAS)}")
        self.camera = camera or camera_from_path(self.root)
        self.intrinsics = intrinsics or TUM_CAMERAS[self.camera]
        world = np.eye(4) if world_from_recorded is None else np.asarray(world_from_recorded)
        if world.shape != (4, 4):
            raise DatasetError(f"world_from_recorded must be 4x4, got shape {world.shape}")
        rgb = read_file_list(self.root / "rgb.txt")
        depth = read_file_list(self.root / "depth.txt")
        times, mats = read_groundtruth(self.root / "groundtruth.txt")
        self.timestamps: list[float] = []
        self._paths: list[tuple[Path, Path]] = []
        self._poses: list[Pose] = []
        pairs = dict(associate([d[0] for d in depth], [c[0] for c in rgb], max_dt))
        for j, (stamp, depth_rel) in enumerate(depth):
            frame_id = f"{stamp:.6f}"
            i = pairs.get(j)
            if i is None:
                self._skip(frame_id, f"no colour image within {max_dt} s")
                continue
            matrix = pose_at(stamp, times, mats, max_dt)
            if matrix is None:
                self._skip(frame_id, f"no ground-truth pose within {max_dt} s")
                continue
            try:
                pose = to_pose(world @ matrix)
            except FrameError as exc:
                raise DatasetError(f"world_from_recorded: {exc.message}") from None
            self.frame_ids.append(frame_id)
            self.timestamps.append(stamp)
            self._paths.append((self.root / rgb[i][1], self.root / depth_rel))
            self._poses.append(pose)
        self._report_skipped()

    def _load(self, index: int) -> Frame:
        rgb_path, depth_path = self._paths[index]
        return Frame(
            index=index,
            frame_id=self.frame_ids[index],
            timestamp=self.timestamps[index],
            rgb=read_rgb(rgb_path),
            depth=read_depth(depth_path, self.intrinsics.depth_scale),
            pose=self._poses[index],
            intrinsics=self.intrinsics,
        )
