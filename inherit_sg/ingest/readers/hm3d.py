"""HM3D-Semantics walks in the layout HOV-SG renders with Habitat.

Layout, as written by ``save_obs`` in HOV-SG's ``hovsg/data/hm3dsem/habitat_utils.py`` and
read by ``hovsg/dataloader/hm3dsem.py`` (github.com/hovsg/HOV-SG):

```
rgb/<scene>_%06d.png       colour
depth/<scene>_%06d.png     uint16 millimetres (Habitat depth × 1000)
pose/<scene>_%06d.txt      Habitat sensor pose T_world_sensor: 16 numbers of a row-major 4×4
                           (older exports: 7 numbers "x y z qx qy qz qw")
semantic/<scene>_%06d.npy  optional per-pixel HM3D object ids (0 = none)
<scene>.semantic.txt       optional HM3D annotation file: 'id,HEX,"category",region' lines
```

Frames are matched across folders by file stem. Intrinsics follow Habitat's pinhole
sensor: horizontal field of view ``hfov_deg`` (90° by default), square pixels, principal
point at the image centre, image size from the first colour image.

Coordinates: Habitat's world is y-up and its sensors use OpenGL axes (x right, y up,
z backward). Poses are converted with :func:`inherit_sg.ingest.readers.convert.habitat_to_world`:
world (x, y, z) -> (x, -z, y) so Habitat's up becomes z, and the camera's y and z axes
are flipped into OpenCV's. A frame whose pose is not finite, or that misses its colour,
depth or pose file, is left out and listed in ``skipped``.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers.base import IndexedReader
from inherit_sg.ingest.readers.convert import (
    habitat_to_world,
    is_finite_matrix,
    matrix_from_tq,
    to_pose,
)
from inherit_sg.ingest.readers.images import image_size, read_depth, read_rgb, trailing_number
from inherit_sg.model import Frame, Intrinsics, Pose

HM3D_DEPTH_SCALE = 1000.0


def habitat_intrinsics(width: int, height: int, hfov_deg: float = 90.0) -> Intrinsics:
    """Pinhole intrinsics of a Habitat camera with horizontal field of view ``hfov_deg``."""
    if not 0.0 < hfov_deg < 180.0:
        raise DatasetError(f"hfov_deg must be in (0, 180), got {hfov_deg}")
    f = width / (2.0 * math.tan(math.radians(hfov_deg) / 2.0))
    return Intrinsics(width, height, f, f, (width - 1) / 2.0, (height - 1) / 2.0, HM3D_DEPTH_SCALE)


def read_habitat_pose(path: Path) -> np.ndarray:
    """A HOV-SG pose file as a 4×4 Habitat ``T_world_sensor`` (may hold non-finite values)."""
    try:
        values = [float(v) for v in path.read_text(encoding="utf-8").split()]
    except ValueError:
        raise DatasetError(f"{path}: pose values must be numbers") from None
    if len(values) == 16:
        return np.array(values).reshape(4, 4)
    if len(values) == 7:
        if not all(math.isfinite(v) for v in values):
            return np.full((4, 4), np.nan)
        try:
            return matrix_from_tq(values[:3], values[3:])
        except FrameError as exc:
            raise DatasetError(f"{path}: {exc.message}") from None
    raise DatasetError(
        f"{path}: expected 16 (4x4) or 7 (x y z qx qy qz qw) numbers, got {len(values)}"
    )


def read_semantic_labels(path: Path) -> dict[int, str]:
    """Parse an HM3D ``*.semantic.txt`` file into object id -> category."""
    labels: dict[int, str] = {}
    with path.open(encoding="utf-8", newline="") as handle:
        for lineno, row in enumerate(csv.reader(handle), 1):
            if len(row) < 3 or not row[0].strip().isdigit():
                if lineno == 1:  # the "HM3D Semantic Annotations" header
                    continue
                raise DatasetError(f"{path}:{lineno}: expected 'id,HEX,\"category\",region'")
            labels[int(row[0])] = row[2].strip()
    return labels


def _frame_order(stem: str) -> tuple[int, str]:
    number = trailing_number(stem)
    return (-1 if number is None else number, stem)


class Hm3dReader(IndexedReader):
    """Reads an HM3D walk in the HOV-SG layout (see the module docstring)."""

    format_name = "hm3d"

    def __init__(self, root: str | Path, hfov_deg: float = 90.0) -> None:
        super().__init__(root)
        for sub in ("rgb", "depth", "pose"):
            if not (self.root / sub).is_dir():
                raise DatasetError(f"{self.root}: missing {sub}/ folder")
        colour = {
            p.stem: p for p in (self.root / "rgb").iterdir() if p.suffix.lower() in (".png", ".jpg")
        }
        depth = {p.stem: p for p in (self.root / "depth").glob("*.png")}
        poses = {p.stem: p for p in (self.root / "pose").glob("*.txt")}
        if not colour:
            raise DatasetError(f"{self.root}: no colour images in rgb/")
        stems = sorted(set(colour) | set(depth) | set(poses), key=_frame_order)
        self.intrinsics = habitat_intrinsics(
            *image_size(colour[min(colour, key=_frame_order)]), hfov_deg
        )
        label_files = sorted(self.root.glob("*semantic.txt"))
        self.labels = read_semantic_labels(label_files[0]) if label_files else {}
        self._paths: list[tuple[Path, Path]] = []
        self._poses: list[Pose] = []
        for stem in stems:
            missing = [
                n
                for n, d in (("colour", colour), ("depth", depth), ("pose", poses))
                if stem not in d
            ]
            if missing:
                self._skip(stem, f"no {' or '.join(missing)}")
                continue
            matrix = read_habitat_pose(poses[stem])
            if not is_finite_matrix(matrix):
                self._skip(stem, "invalid pose (NaN/inf)")
                continue
            try:
                pose = to_pose(habitat_to_world(matrix))
            except FrameError as exc:
                raise DatasetError(f"{poses[stem]}: {exc.message}") from None
            self.frame_ids.append(stem)
            self._paths.append((colour[stem], depth[stem]))
            self._poses.append(pose)
        self._report_skipped()

    def _instances(self, stem: str) -> tuple[np.ndarray | None, dict[int, str]]:
        path = self.root / "semantic" / f"{stem}.npy"
        if not path.is_file():
            return None, {}
        try:
            ids = np.load(path, allow_pickle=False)
        except (OSError, ValueError) as exc:
            raise FrameError(f"cannot read semantic image {path}: {exc}") from None
        if ids.ndim != 2 or not np.issubdtype(ids.dtype, np.integer):
            raise FrameError(
                f"{path}: semantic ids must be a 2-D integer array, got {ids.dtype} {ids.shape}"
            )
        if ids.size and (ids.min() < 0 or ids.max() > np.iinfo(np.uint16).max):
            raise FrameError(f"{path}: semantic ids must lie in 0..65535")
        present = {int(v) for v in np.unique(ids)} - {0}
        labels = {i: self.labels[i] for i in sorted(present) if i in self.labels}
        return ids.astype(np.uint16), labels

    def _load(self, index: int) -> Frame:
        rgb_path, depth_path = self._paths[index]
        stem = self.frame_ids[index]
        instances, labels = self._instances(stem)
        number = trailing_number(stem)
        return Frame(
            index=index,
            frame_id=stem,
            timestamp=float(index if number is None else number),
            rgb=read_rgb(rgb_path),
            depth=read_depth(depth_path, self.intrinsics.depth_scale),
            pose=self._poses[index],
            intrinsics=self.intrinsics,
            instances=instances,
            instance_labels=labels,
        )
