"""Record3D ``.r3d`` captures (the iPhone / iPad LiDAR app's export, as ConceptGraphs and
DualMap users bring them). Needs the optional ``record3d`` extra (the ``lzfse`` package).

An ``.r3d`` file is a zip archive:

```
metadata          JSON: w, h (RGB size), dw, dh (depth size, e.g. 192×256), fps,
                  K (RGB intrinsics, 9 numbers column-major: fx 0 0 0 fy 0 cx cy 1),
                  poses ([qx, qy, qz, qw, px, py, pz] per frame), frameTimestamps (optional)
rgbd/<i>.jpg      colour image of frame i
rgbd/<i>.depth    LZFSE-compressed float32 metres, dh×dw, NaN where no reading
rgbd/<i>.conf     (optional) LZFSE-compressed uint8 confidence, dh×dw: 0 low, 1 medium, 2 high
```

Poses are ``T_world_camera`` in ARKit's gravity-aligned y-up world with OpenGL camera axes
(x right, y up, z backward); they are turned into the z-up world with OpenCV camera axes
(:func:`~inherit_sg.ingest.readers.convert.habitat_to_world`, the same two axis changes).
ARKit puts the world origin where the capture started, so the floor lies about a device
height below z = 0; mapping measures heights from the floor it sees, not from z = 0.

Resolution: frames come at the colour image's size, shrunk (area averaging) to at most
``max_width`` pixels wide (default 640; None keeps the full size), with the intrinsics
scaled to match (pixel-centre convention). Depth and confidence are resized to that size
by exact nearest neighbour (``cv2.INTER_NEAREST_EXACT``, centre-aligned), so every depth
pixel is a LiDAR reading, never a blend across an edge. The colour images carry the
detail segmentation needs; the 192×256 depth is too small to segment on.

Confidence: where ``.conf`` exists, depth with confidence below ``min_confidence``
(default 2: only ARKit's high confidence is kept) becomes 0 (no reading).
"""

from __future__ import annotations

import json
import re
import threading
import zipfile
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from inherit_sg.errors import DatasetError, FrameError, ModelUnavailableError
from inherit_sg.ingest.readers.base import IndexedReader
from inherit_sg.ingest.readers.convert import habitat_to_world, matrix_from_tq, to_pose
from inherit_sg.model import Frame, Intrinsics, Pose

_FRAME_FILE = re.compile(r"^rgbd/(\d+)\.(jpg|depth|conf)$")


def find_r3d_file(path: str | Path) -> Path:
    """The ``.r3d`` file at ``path`` (a file, or a folder with exactly one)."""
    p = Path(path)
    if p.is_file():
        return p
    if not p.is_dir():
        raise DatasetError(f"Record3D file not found: {p}")
    found = sorted(p.glob("*.r3d"))
    if len(found) != 1:
        raise DatasetError(f"{p}: expected one .r3d file, found {len(found)}")
    return found[0]


def _decompress(data: bytes, where: str) -> bytes:
    try:
        import lzfse
    except ImportError:
        raise ModelUnavailableError(
            "Record3D depth is LZFSE-compressed: pip install 'inherit-sg[record3d]'"
        ) from None
    try:
        return bytes(lzfse.decompress(data))
    except lzfse.error:
        raise FrameError(f"{where}: not LZFSE data") from None


def _metadata(archive: zipfile.ZipFile, path: Path) -> dict[str, Any]:
    try:
        meta = json.loads(archive.read("metadata"))
    except KeyError:
        raise DatasetError(f"{path}: no 'metadata' entry (not a Record3D .r3d file)") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise DatasetError(f"{path}: metadata is not JSON: {exc}") from None
    missing = [k for k in ("w", "h", "K", "poses") if k not in meta]
    if not isinstance(meta, dict) or missing:
        raise DatasetError(f"{path}: metadata lacks {', '.join(missing) or 'fields'}")
    if len(meta["K"]) != 9:
        raise DatasetError(f"{path}: metadata K must hold 9 numbers, got {len(meta['K'])}")
    return meta


def _scaled(meta: dict[str, Any], width: int, height: int) -> Intrinsics:
    """The RGB intrinsics (column-major ``K`` at ``w``×``h``) for a ``width``×``height``
    image (pixel centres kept aligned)."""
    k = np.asarray(meta["K"], dtype=np.float64).reshape(3, 3).T
    sx, sy = width / float(meta["w"]), height / float(meta["h"])
    return Intrinsics(
        width=width,
        height=height,
        fx=float(k[0, 0]) * sx,
        fy=float(k[1, 1]) * sy,
        cx=(float(k[0, 2]) + 0.5) * sx - 0.5,
        cy=(float(k[1, 2]) + 0.5) * sy - 0.5,
    )


class Record3dReader(IndexedReader):
    """Reads a Record3D ``.r3d`` capture (see the module docstring)."""

    format_name = "record3d"

    def __init__(
        self, path: str | Path, *, max_width: int | None = 640, min_confidence: int = 2
    ) -> None:
        super().__init__(find_r3d_file(path), single_file=True)
        try:
            self._zip = zipfile.ZipFile(self.root)
        except zipfile.BadZipFile:
            raise DatasetError(
                f"{self.root}: not a zip archive (not a Record3D .r3d file)"
            ) from None
        self._lock = threading.Lock()
        self.min_confidence = min_confidence
        meta = _metadata(self._zip, self.root)
        rgb_w, rgb_h = int(meta["w"]), int(meta["h"])
        self.depth_size = (int(meta.get("dw", 192)), int(meta.get("dh", 256)))
        scale = 1.0 if max_width is None or rgb_w <= max_width else max_width / rgb_w
        self.intrinsics = _scaled(meta, round(rgb_w * scale), round(rgb_h * scale))
        entries: dict[str, set[int]] = {"jpg": set(), "depth": set(), "conf": set()}
        for name in self._zip.namelist():
            match = _FRAME_FILE.match(name)
            if match:
                entries[match.group(2)].add(int(match.group(1)))
        self._has_conf = entries["conf"]
        stamps = meta.get("frameTimestamps") or []
        fps = float(meta.get("fps") or 30.0)
        self.timestamps: list[float] = []
        self._poses: list[Pose] = []
        self._numbers: list[int] = []
        for number, raw in enumerate(meta["poses"]):
            frame_id = str(number)
            if number not in entries["jpg"] or number not in entries["depth"]:
                self._skip(frame_id, "no rgbd/<i>.jpg or rgbd/<i>.depth")
                continue
            try:
                if len(raw) != 7:
                    raise FrameError(f"pose needs 7 numbers, got {len(raw)}")
                arkit = matrix_from_tq(raw[4:], raw[:4])
                pose = to_pose(habitat_to_world(arkit))
            except (FrameError, TypeError, ValueError) as exc:
                self._skip(frame_id, f"invalid pose: {exc}")
                continue
            self.frame_ids.append(frame_id)
            self._numbers.append(number)
            self._poses.append(pose)
            stamp = stamps[number] if number < len(stamps) else number / fps
            self.timestamps.append(float(stamp))
        self._report_skipped()

    def _read(self, name: str) -> bytes:
        with self._lock:
            try:
                return self._zip.read(name)
            except (KeyError, zipfile.BadZipFile, OSError) as exc:
                raise FrameError(f"{self.root}: cannot read {name}: {exc}") from None

    def _depth(self, number: int) -> np.ndarray:
        """Depth in metres at the depth size, 0 where no reading or low confidence."""
        dw, dh = self.depth_size
        name = f"rgbd/{number}.depth"
        raw = _decompress(self._read(name), f"{self.root}:{name}")
        if len(raw) != dw * dh * 4:
            raise FrameError(f"{self.root}:{name}: {len(raw)} bytes, expected {dw}x{dh} float32")
        depth = np.frombuffer(raw, dtype=np.float32).reshape(dh, dw).copy()
        depth[~np.isfinite(depth) | (depth < 0)] = 0.0
        if number in self._has_conf:
            name = f"rgbd/{number}.conf"
            conf = _decompress(self._read(name), f"{self.root}:{name}")
            if len(conf) != dw * dh:
                raise FrameError(f"{self.root}:{name}: {len(conf)} bytes, expected {dw}x{dh}")
            depth[np.frombuffer(conf, dtype=np.uint8).reshape(dh, dw) < self.min_confidence] = 0
        return depth

    def _load(self, index: int) -> Frame:
        number = self._numbers[index]
        size = (self.intrinsics.width, self.intrinsics.height)
        bgr = cv2.imdecode(
            np.frombuffer(self._read(f"rgbd/{number}.jpg"), np.uint8), cv2.IMREAD_COLOR
        )
        if bgr is None:
            raise FrameError(f"{self.root}: cannot decode rgbd/{number}.jpg")
        if bgr.shape[1::-1] != size:
            bgr = cv2.resize(bgr, size, interpolation=cv2.INTER_AREA)
        depth = self._depth(number)
        if depth.shape[::-1] != size:
            depth = cv2.resize(depth, size, interpolation=cv2.INTER_NEAREST_EXACT)
        return Frame(
            index=index,
            frame_id=self.frame_ids[index],
            timestamp=self.timestamps[index],
            rgb=cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB),
            depth=depth,
            pose=self._poses[index],
            intrinsics=self.intrinsics,
        )
