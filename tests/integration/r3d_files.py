"""Write Record3D ``.r3d`` captures from isg frames the way the format specifies (zip with
``metadata`` JSON, ``rgbd/<i>.jpg``, LZFSE float32 ``.depth``, LZFSE uint8 ``.conf``), and
an isg copy holding the very same JPEG colour images and no instance masks."""

from __future__ import annotations

import json
import shutil
import zipfile
from collections.abc import Callable
from pathlib import Path

import cv2
import lzfse
import numpy as np
from scipy.spatial.transform import Rotation

from inherit_sg.ingest.isg import IsgReader
from inherit_sg.ingest.readers.convert import OPENGL_TO_OPENCV, Y_UP_TO_Z_UP

#: isg pose (z-up world, OpenCV camera) -> ARKit pose (y-up world, OpenGL camera)
Convention = Callable[[np.ndarray], np.ndarray]


def to_arkit(t_world_camera: np.ndarray) -> np.ndarray:
    """The correct inverse of the reader's conversion."""
    return np.linalg.inv(Y_UP_TO_Z_UP) @ t_world_camera @ OPENGL_TO_OPENCV


def write_r3d(
    isg_dir: Path,
    out: Path,
    *,
    depth_size: tuple[int, int] | None = None,
    confidence: Callable[[int, int], np.ndarray] | None = None,
    convention: Convention = to_arkit,
    jpeg_copy: Path | None = None,
) -> Path:
    """Write ``out`` (.r3d) from the frames of ``isg_dir``. ``depth_size`` (w, h) stores
    depth at another size (exact nearest neighbour), ``confidence(w, h)`` gives each
    frame's confidence image, ``convention`` turns our poses into what the file holds.
    ``jpeg_copy`` also writes an isg folder with the same JPEG bytes and depth, no masks."""
    reader = IsgReader(isg_dir)
    k = reader.intrinsics
    dw, dh = depth_size or (k.width, k.height)
    poses: list[list[float]] = []
    stamps: list[float] = []
    if jpeg_copy is not None:
        (jpeg_copy / "frames").mkdir(parents=True)
        shutil.copy(isg_dir / "intrinsics.json", jpeg_copy / "intrinsics.json")
        shutil.copy(isg_dir / "poses.txt", jpeg_copy / "poses.txt")
    with zipfile.ZipFile(out, "w", zipfile.ZIP_STORED) as archive:
        for i, frame in enumerate(reader):
            ok, jpg = cv2.imencode(".jpg", cv2.cvtColor(frame.rgb, cv2.COLOR_RGB2BGR))
            assert ok
            archive.writestr(f"rgbd/{i}.jpg", jpg.tobytes())
            depth = frame.depth.astype(np.float32)
            if (dw, dh) != (k.width, k.height):
                depth = cv2.resize(depth, (dw, dh), interpolation=cv2.INTER_NEAREST_EXACT)
            depth = np.where(depth > 0, depth, np.float32(np.nan)).astype(np.float32)
            archive.writestr(f"rgbd/{i}.depth", lzfse.compress(depth.tobytes()))
            if confidence is not None:
                conf = confidence(dw, dh).astype(np.uint8)
                archive.writestr(f"rgbd/{i}.conf", lzfse.compress(conf.tobytes()))
            m = convention(frame.pose.matrix)
            poses.append([*Rotation.from_matrix(m[:3, :3]).as_quat().tolist(), *m[:3, 3].tolist()])
            stamps.append(frame.timestamp)
            if jpeg_copy is not None:
                base = jpeg_copy / "frames" / frame.frame_id
                Path(f"{base}.rgb.jpg").write_bytes(jpg.tobytes())
                shutil.copy(isg_dir / "frames" / f"{frame.frame_id}.depth.png", f"{base}.depth.png")
        metadata = {
            "w": k.width,
            "h": k.height,
            "dw": dw,
            "dh": dh,
            "fps": 30,
            "K": [k.fx, 0.0, 0.0, 0.0, k.fy, 0.0, k.cx, k.cy, 1.0],
            "poses": poses,
            "frameTimestamps": stamps,
            "initPose": poses[0],
            "cameraType": 1,
        }
        archive.writestr("metadata", json.dumps(metadata))
    return out
