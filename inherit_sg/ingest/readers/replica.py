"""Replica sequences in the NICE-SLAM layout.

```
results/frame%06d.jpg   colour (png accepted too)
results/depth%06d.png   uint16 depth, ``scale`` units per metre (6553.5 for Replica)
traj.txt                one row-major 4×4 camera-to-world matrix per line, line i = frame i
cam_params.json         {"camera": {"w","h","fx","fy","cx","cy","scale"}} (flat keys accepted)
```

Frames are matched to poses by number: frame ``i`` takes line ``i`` of ``traj.txt``. Poses
beyond the available images are ignored; images without a pose, colour without depth
(or the reverse) and non-finite poses are left out and listed in ``skipped``.

Coordinate frame: the poses are used as recorded, because they already follow our
convention (z-up world, OpenCV camera). Evidence from office0 (``office0_mesh.ply``,
same frame as the poses): the mesh spans z -1.17..1.82 m with 40% of its vertices in the
lowest 15 cm (the floor) and a second peak at the top (the ceiling), while x and y show
no such slabs; in all 2000 poses the camera x axis has zero z component (no roll about
z) and the camera y axis points downward (mean z component -0.85); cameras sit 1.4–2.4 m
above that floor. Back-projecting frame 0's depth with the OpenCV model lands a median
1 cm from the mesh, against 0.67 m with OpenGL camera axes.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers.base import IndexedReader
from inherit_sg.ingest.readers.convert import to_pose
from inherit_sg.ingest.readers.images import numbered_files, read_depth, read_rgb
from inherit_sg.model import Frame, Intrinsics, Pose

RESULTS_DIR = "results"
TRAJ_FILE = "traj.txt"
CAM_FILE = "cam_params.json"


def read_cam_params(path: Path) -> Intrinsics:
    """Parse ``cam_params.json`` into intrinsics (``scale`` = depth units per metre)."""
    try:
        data: Any = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DatasetError(f"missing {path}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise DatasetError(f"{path}: invalid JSON: {exc}") from None
    cam = data.get("camera", data) if isinstance(data, dict) else None
    if not isinstance(cam, dict):
        raise DatasetError(f"{path}: expected an object with a 'camera' section")
    missing = [k for k in ("w", "h", "fx", "fy", "cx", "cy", "scale") if k not in cam]
    if missing:
        raise DatasetError(f"{path}: camera is missing {', '.join(missing)}")
    try:
        return Intrinsics(
            width=int(cam["w"]),
            height=int(cam["h"]),
            fx=float(cam["fx"]),
            fy=float(cam["fy"]),
            cx=float(cam["cx"]),
            cy=float(cam["cy"]),
            depth_scale=float(cam["scale"]),
        )
    except (TypeError, ValueError) as exc:
        raise DatasetError(f"{path}: camera values must be numbers: {exc}") from None
    except FrameError as exc:
        raise DatasetError(f"{path}: {exc.message}") from None


def read_trajectory(path: Path) -> list[np.ndarray]:
    """Parse ``traj.txt``: one 4×4 row-major matrix per non-empty line. Non-finite
    matrices are kept (the reader skips those frames); malformed lines raise DatasetError."""
    if not path.is_file():
        raise DatasetError(f"missing {path}")
    out: list[np.ndarray] = []
    for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        parts = line.split()
        if not parts:
            continue
        if len(parts) != 16:
            raise DatasetError(f"{path}:{lineno}: expected 16 numbers, got {len(parts)}")
        try:
            out.append(np.array([float(v) for v in parts]).reshape(4, 4))
        except ValueError:
            raise DatasetError(f"{path}:{lineno}: pose values must be numbers") from None
    return out


class ReplicaReader(IndexedReader):
    """Reads a NICE-SLAM-layout Replica sequence (see the module docstring)."""

    format_name = "replica"

    def __init__(self, root: str | Path) -> None:
        super().__init__(root)
        results = self.root / RESULTS_DIR
        if not results.is_dir():
            raise DatasetError(f"{self.root}: missing {RESULTS_DIR}/ folder")
        self.intrinsics = read_cam_params(self.root / CAM_FILE)
        trajectory = read_trajectory(self.root / TRAJ_FILE)
        colour = numbered_files(results, "frame", (".jpg", ".jpeg", ".png"))
        depth = numbered_files(results, "depth", (".png",))
        self._paths: list[tuple[Path, Path]] = []
        self._poses: list[Pose] = []
        for number in sorted(set(colour) | set(depth)):
            frame_id = f"{number:06d}"
            if number not in colour or number not in depth:
                which = "colour" if number not in colour else "depth"
                self._skip(frame_id, f"no {which} image")
            elif number >= len(trajectory):
                self._skip(frame_id, f"no pose ({TRAJ_FILE} has {len(trajectory)} lines)")
            else:
                try:
                    pose = to_pose(trajectory[number])
                except FrameError as exc:
                    self._skip(frame_id, f"invalid pose: {exc.message}")
                    continue
                self.frame_ids.append(frame_id)
                self._paths.append((colour[number], depth[number]))
                self._poses.append(pose)
        self._report_skipped()

    def _load(self, index: int) -> Frame:
        rgb_path, depth_path = self._paths[index]
        return Frame(
            index=index,
            frame_id=self.frame_ids[index],
            timestamp=float(int(self.frame_ids[index])),
            rgb=read_rgb(rgb_path),
            depth=read_depth(depth_path, self.intrinsics.depth_scale),
            pose=self._poses[index],
            intrinsics=self.intrinsics,
        )
