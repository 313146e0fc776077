"""ScanNet sequences exported by ScanNet's ``SensReader`` (``reader.py --export_*``).

```
color/<i>.jpg                    colour, usually 1296×968
depth/<i>.png                    uint16 millimetres, usually 640×480
pose/<i>.txt                     4×4 camera-to-world (4 lines of 4 numbers)
intrinsic/intrinsic_color.txt    4×4 (or 3×3) colour camera matrix
intrinsic/intrinsic_depth.txt    4×4 (or 3×3) depth camera matrix
```

Frames are yielded at the depth resolution with the depth intrinsics: each colour image is
resampled onto the depth pixel grid through both camera matrices (the two cameras share
their optical centre in the export), which is a plain resize when the fields of view
agree. Poses are already z-up world with OpenCV camera axes (ScanNet's reconstruction
frame) and are used as recorded. ScanNet marks frames where tracking failed with ``-inf``
poses: those frames, and frames missing an image or a pose, are left out and listed in
``skipped`` (a warning gives the count). A pose file that is not 16 numbers raises
DatasetError naming it.
"""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers.base import IndexedReader
from inherit_sg.ingest.readers.convert import is_finite_matrix, to_pose
from inherit_sg.ingest.readers.images import image_size, numbered_files, read_depth, read_rgb
from inherit_sg.model import Frame, Intrinsics, Pose

SCANNET_DEPTH_SCALE = 1000.0


def read_matrix_file(path: Path) -> np.ndarray:
    """A whitespace-separated 4×4 (or 3×3) matrix file; DatasetError names a bad file."""
    try:
        values = [float(v) for v in path.read_text(encoding="utf-8").split()]
    except FileNotFoundError:
        raise DatasetError(f"missing {path}") from None
    except ValueError:
        raise DatasetError(f"{path}: matrix values must be numbers") from None
    if len(values) not in (9, 16):
        raise DatasetError(f"{path}: expected a 3x3 or 4x4 matrix, got {len(values)} numbers")
    side = 3 if len(values) == 9 else 4
    return np.array(values).reshape(side, side)


def camera_matrix(path: Path, width: int, height: int, depth_scale: float) -> Intrinsics:
    """Intrinsics from a ScanNet ``intrinsic_*.txt`` file and the image size."""
    k = read_matrix_file(path)
    try:
        return Intrinsics(width, height, k[0, 0], k[1, 1], k[0, 2], k[1, 2], depth_scale)
    except FrameError as exc:
        raise DatasetError(f"{path}: {exc.message}") from None


def colour_to_depth_grid(rgb: np.ndarray, colour: Intrinsics, depth: Intrinsics) -> np.ndarray:
    """Resample a colour image onto the depth camera's pixel grid (shared optical centre)."""
    if rgb.shape[:2] == (depth.height, depth.width) and colour == depth:
        return rgb
    # Area-average down to about the target scale first, then a near-unit affine warp.
    fx, fy, cx, cy = colour.fx, colour.fy, colour.cx, colour.cy
    scale = min(1.0, depth.fx / colour.fx)
    if scale < 1.0:
        h, w = rgb.shape[:2]
        size = (max(1, round(w * scale)), max(1, round(h * scale)))
        rgb = cv2.resize(rgb, size, interpolation=cv2.INTER_AREA)
        sx, sy = size[0] / w, size[1] / h
        fx, fy, cx, cy = fx * sx, fy * sy, (cx + 0.5) * sx - 0.5, (cy + 0.5) * sy - 0.5
    # Maps a depth pixel to the colour pixel seeing the same ray.
    ax, ay = fx / depth.fx, fy / depth.fy
    warp = np.array([[ax, 0.0, cx - ax * depth.cx], [0.0, ay, cy - ay * depth.cy]])
    return cv2.warpAffine(
        rgb,
        warp,
        (depth.width, depth.height),
        flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP,
        borderMode=cv2.BORDER_CONSTANT,
        borderValue=(0, 0, 0),
    )


class ScanNetReader(IndexedReader):
    """Reads a ScanNet ``SensReader`` export (see the module docstring)."""

    format_name = "scannet"

    def __init__(self, root: str | Path, depth_scale: float = SCANNET_DEPTH_SCALE) -> None:
        super().__init__(root)
        for sub in ("color", "depth", "pose", "intrinsic"):
            if not (self.root / sub).is_dir():
                raise DatasetError(f"{self.root}: missing {sub}/ folder")
        colour = numbered_files(self.root / "color", "", (".jpg", ".jpeg", ".png"))
        depth = numbered_files(self.root / "depth", "", (".png",))
        poses = numbered_files(self.root / "pose", "", (".txt",))
        if not depth:
            raise DatasetError(f"{self.root}: no depth images in depth/")
        if not colour:
            raise DatasetError(f"{self.root}: no colour images in color/")
        intr = self.root / "intrinsic"
        self.intrinsics = camera_matrix(
            intr / "intrinsic_depth.txt", *image_size(depth[min(depth)]), depth_scale
        )
        self.colour_intrinsics = camera_matrix(
            intr / "intrinsic_color.txt", *image_size(colour[min(colour)]), depth_scale
        )
        self._paths: list[tuple[Path, Path]] = []
        self._poses: list[Pose] = []
        for number in sorted(set(colour) | set(depth) | set(poses)):
            frame_id = str(number)
            missing = [
                n
                for n, d in (("colour", colour), ("depth", depth), ("pose", poses))
                if number not in d
            ]
            if missing:
                self._skip(frame_id, f"no {' or '.join(missing)}")
                continue
            matrix = read_matrix_file(poses[number])
            if matrix.shape != (4, 4):
                raise DatasetError(f"{poses[number]}: pose must be 4x4")
            if not is_finite_matrix(matrix):
                self._skip(frame_id, "invalid pose (-inf/NaN: tracking lost)")
                continue
            try:
                pose = to_pose(matrix)
            except FrameError as exc:
                raise DatasetError(f"{poses[number]}: {exc.message}") from None
            self.frame_ids.append(frame_id)
            self._paths.append((colour[number], depth[number]))
            self._poses.append(pose)
        self._report_skipped()

    def _load(self, index: int) -> Frame:
        rgb_path, depth_path = self._paths[index]
        rgb = read_rgb(rgb_path)
        expected = (self.colour_intrinsics.height, self.colour_intrinsics.width)
        if rgb.shape[:2] != expected:
            raise FrameError(
                f"{rgb_path}: colour is {rgb.shape[1]}x{rgb.shape[0]}, "
                f"intrinsic_color.txt is for {expected[1]}x{expected[0]}"
            )
        return Frame(
            index=index,
            frame_id=self.frame_ids[index],
            timestamp=float(int(self.frame_ids[index])),
            rgb=colour_to_depth_grid(rgb, self.colour_intrinsics, self.intrinsics),
            depth=read_depth(depth_path, self.intrinsics.depth_scale),
            pose=self._poses[index],
            intrinsics=self.intrinsics,
        )
