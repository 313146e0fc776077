"""The isg dataset folder (DESIGN.md §4): writer and reader.

```
intrinsics.json   {"width","height","fx","fy","cx","cy","depth_scale"}
poses.txt         "<frame_id> <16 numbers row-major T_world_camera>" per line
frames/<id>.rgb.png|jpg  frames/<id>.depth.png (uint16)
frames/<id>.instances.png (optional uint16)  frames/<id>.instances.json (optional)
instances.json    (optional) {"<instance id>": {"label": str, ...}}
scene.json, queries.jsonl  (optional ground truth, never read by mapping or retrieval)
```
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.model import Frame, Intrinsics, Pose

INTRINSICS_FILE = "intrinsics.json"
POSES_FILE = "poses.txt"
FRAMES_DIR = "frames"


def is_isg_folder(path: Path) -> bool:
    """Whether ``path`` looks like an isg dataset folder."""
    return (path / INTRINSICS_FILE).is_file() and (path / POSES_FILE).is_file()


class IsgWriter:
    """Writes frames into an isg folder; call :meth:`close` (or use ``with``)."""

    def __init__(self, root: str | Path, intrinsics: Intrinsics, rgb_format: str = "png") -> None:
        if rgb_format not in ("png", "jpg"):
            raise ValueError("rgb_format must be 'png' or 'jpg'")
        self.root = Path(root)
        self.intrinsics = intrinsics
        self.rgb_format = rgb_format
        (self.root / FRAMES_DIR).mkdir(parents=True, exist_ok=True)
        (self.root / INTRINSICS_FILE).write_text(json.dumps(intrinsics.to_dict(), indent=2))
        self._poses = open(self.root / POSES_FILE, "w", encoding="utf-8")  # noqa: SIM115
        self.count = 0

    def write(
        self,
        frame_id: str,
        rgb: np.ndarray,
        depth_m: np.ndarray,
        pose: Pose,
        instances: np.ndarray | None = None,
        instance_labels: dict[int, str] | None = None,
    ) -> None:
        """Write one frame. ``depth_m`` is float metres (0 = invalid)."""
        if any(c.isspace() for c in frame_id) or "/" in frame_id:
            raise ValueError(f"frame id must not contain spaces or '/': {frame_id!r}")
        base = self.root / FRAMES_DIR / frame_id
        bgr = cv2.cvtColor(np.ascontiguousarray(rgb), cv2.COLOR_RGB2BGR)
        if not cv2.imwrite(f"{base}.rgb.{self.rgb_format}", bgr):
            raise OSError(f"could not write {base}.rgb.{self.rgb_format}")
        scaled = np.clip(np.round(depth_m * self.intrinsics.depth_scale), 0, 65535)
        cv2.imwrite(f"{base}.depth.png", scaled.astype(np.uint16))
        if instances is not None:
            cv2.imwrite(f"{base}.instances.png", instances.astype(np.uint16))
        if instance_labels is not None:
            labels = {str(k): {"label": v} for k, v in sorted(instance_labels.items())}
            Path(f"{base}.instances.json").write_text(json.dumps(labels))
        numbers = " ".join(f"{v:.9g}" for v in pose.to_list())
        self._poses.write(f"{frame_id} {numbers}\n")
        self.count += 1

    def close(self) -> None:
        """Flush the pose file."""
        self._poses.close()

    def __enter__(self) -> IsgWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def read_intrinsics(root: Path) -> Intrinsics:
    """Parse ``intrinsics.json``."""
    path = root / INTRINSICS_FILE
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DatasetError(f"{root}: missing {INTRINSICS_FILE}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise DatasetError(f"{path}: invalid JSON: {exc}") from None
    try:
        return Intrinsics.from_dict(data)
    except FrameError as exc:
        raise DatasetError(f"{path}: {exc.message}") from None


def read_poses(root: Path) -> list[tuple[str, Pose]]:
    """Parse ``poses.txt`` into (frame id, pose) pairs; errors name the line."""
    path = root / POSES_FILE
    if not path.is_file():
        raise DatasetError(f"{root}: missing {POSES_FILE}")
    out: list[tuple[str, Pose]] = []
    for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        if len(parts) != 17:
            raise DatasetError(
                f"{path}:{lineno}: expected a frame id and 16 numbers, got {len(parts)} fields"
            )
        try:
            values = [float(v) for v in parts[1:]]
        except ValueError:
            raise DatasetError(f"{path}:{lineno}: pose values must be numbers") from None
        if not all(math.isfinite(v) for v in values):
            raise DatasetError(f"{path}:{lineno}: pose of frame {parts[0]!r} has NaN or inf")
        try:
            out.append((parts[0], Pose(tuple(values))))
        except FrameError as exc:
            raise DatasetError(f"{path}:{lineno}: frame {parts[0]!r}: {exc.message}") from None
    return out


def _read_labels(path: Path) -> dict[int, str]:
    try:
        raw: dict[str, Any] = json.loads(path.read_text(encoding="utf-8"))
        return {int(k): str(v["label"] if isinstance(v, dict) else v) for k, v in raw.items()}
    except (json.JSONDecodeError, KeyError, ValueError, TypeError) as exc:
        raise DatasetError(f"{path}: malformed instance labels: {exc}") from None


class IsgReader:
    """Reads an isg folder frame by frame; len() is the number of posed frames."""

    format_name = "isg"

    def __init__(self, root: str | Path) -> None:
        self.root = Path(root)
        if not self.root.is_dir():
            raise DatasetError(f"dataset folder not found: {self.root}")
        self.intrinsics = read_intrinsics(self.root)
        self.poses = read_poses(self.root)
        global_labels = self.root / "instances.json"
        self.global_labels = _read_labels(global_labels) if global_labels.is_file() else {}

    def __len__(self) -> int:
        return len(self.poses)

    def __iter__(self) -> Iterator[Frame]:
        for index in range(len(self.poses)):
            yield self.read(index)

    def _image(self, path: Path, flags: int) -> np.ndarray:
        img = cv2.imread(str(path), flags)
        if img is None:
            raise FrameError(f"cannot read image {path}")
        return img

    def read(self, index: int) -> Frame:
        """Load frame ``index``; raises FrameError naming the file that is wrong."""
        frame_id, pose = self.poses[index]
        base = self.root / FRAMES_DIR / frame_id
        rgb_path = next(
            (p for ext in ("png", "jpg", "jpeg") if (p := Path(f"{base}.rgb.{ext}")).is_file()),
            None,
        )
        if rgb_path is None:
            raise FrameError(f"frame {frame_id!r}: missing colour image {base}.rgb.png|jpg")
        rgb = cv2.cvtColor(self._image(rgb_path, cv2.IMREAD_COLOR), cv2.COLOR_BGR2RGB)
        depth_path = Path(f"{base}.depth.png")
        if not depth_path.is_file():
            raise FrameError(f"frame {frame_id!r}: missing depth image {depth_path}")
        depth_raw = self._image(depth_path, cv2.IMREAD_UNCHANGED)
        if depth_raw.ndim != 2 or depth_raw.dtype != np.uint16:
            # an 8-bit PNG would read as depths of at most 0.26 m: refuse it
            raise FrameError(
                f"{depth_path}: depth must be a single-channel uint16 PNG, got "
                f"{depth_raw.dtype} with shape {depth_raw.shape}"
            )
        depth = depth_raw.astype(np.float32) / np.float32(self.intrinsics.depth_scale)
        instances = None
        labels: dict[int, str] = {}
        inst_path = Path(f"{base}.instances.png")
        if inst_path.is_file():
            instances = self._image(inst_path, cv2.IMREAD_UNCHANGED).astype(np.uint16)
            per_frame = Path(f"{base}.instances.json")
            labels = _read_labels(per_frame) if per_frame.is_file() else dict(self.global_labels)
        frame = Frame(
            index=index,
            frame_id=frame_id,
            timestamp=float(index),
            rgb=rgb,
            depth=depth,
            pose=pose,
            intrinsics=self.intrinsics,
            instances=instances,
            instance_labels=labels,
        )
        return frame.validate()
