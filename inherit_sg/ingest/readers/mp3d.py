"""Matterport3D ``.house`` files as a frame source: the house is rendered on the fly.

A ``.house`` file holds a layout, not images: regions with floor outlines, oriented
object boxes with categories. Opening one builds the same world and exploration walk as
``inherit-sg sim render-house`` (:mod:`inherit_sg.ingest.mp3d_dataset`) and :meth:`Mp3dReader.read`
renders frame ``index`` of that walk through the same noise model, so mapping a
``.house`` directly gives the frames a rendered folder would hold (depth in whole
millimetres, as a written depth PNG stores it). Render the folder instead when the
ground truth is needed too (``scene.json``, ``queries.jsonl``) or frames are read often.

The path may be the ``.house`` file or a folder holding exactly one (e.g. an MP3D scan's
``house_segmentations/``). Coordinates are the file's own, z-up metres.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.mp3d_dataset import HouseWorld, load_house_world
from inherit_sg.ingest.synthetic.generate import DRIFT_STREAM, make_intrinsics, render_frame
from inherit_sg.ingest.synthetic.noise import PoseDrift, noise_config
from inherit_sg.ingest.synthetic.render import Renderer
from inherit_sg.model import Frame, Intrinsics, Pose


def find_house_file(path: str | Path) -> Path:
    """The ``.house`` file at ``path`` (a file, or a folder with exactly one)."""
    p = Path(path)
    if p.is_file():
        return p
    if not p.is_dir():
        raise DatasetError(f"MP3D house file not found: {p}")
    found = sorted(p.glob("*.house"))
    if len(found) != 1:
        raise DatasetError(f"{p}: expected one .house file, found {len(found)}")
    return found[0]


class Mp3dReader:
    """Renders the exploration walk of an MP3D house frame by frame (see module doc).

    ``width``/``height`` set the image size, ``seed`` the walk and the noise, ``noise`` the
    perception noise level (``clean`` or ``noisy``), ``max_frames`` keeps the start of the
    walk only.
    """

    format_name = "mp3d"

    def __init__(
        self,
        path: str | Path,
        *,
        width: int = 640,
        height: int = 480,
        seed: int = 0,
        noise: str = "clean",
        max_frames: int | None = None,
    ) -> None:
        self.path = find_house_file(path)
        self.house: HouseWorld = load_house_world(self.path)
        self.intrinsics: Intrinsics = make_intrinsics(width, height)
        self.seed = seed
        self.noise = noise_config(noise)
        poses = self.house.trajectory(seed).poses
        self.true_poses: list[Pose] = poses[:max_frames] if max_frames is not None else poses
        drift = PoseDrift(self.noise, np.random.default_rng([seed, DRIFT_STREAM]))
        self.poses = [drift.apply(p) for p in self.true_poses]
        self._labels = {o.instance_id: o.label for o in self.house.scene.objects}
        self._renderer: Renderer | None = None

    def __len__(self) -> int:
        return len(self.poses)

    def __iter__(self) -> Iterator[Frame]:
        for index in range(len(self)):
            yield self.read(index)

    def read(self, index: int) -> Frame:
        """Render frame ``index``; IndexError outside ``range(len(self))``."""
        if not 0 <= index < len(self):
            raise IndexError(f"frame index {index} out of range 0..{len(self) - 1}")
        if self._renderer is None:
            self._renderer = Renderer(self.house.world, self.house.lights, self.intrinsics)
        _, rgb, depth, ids, labels, _ = render_frame(
            self._renderer, index, self.true_poses[index], self.seed, self.noise, self._labels
        )
        scale = np.float32(self.intrinsics.depth_scale)
        depth_mm = np.clip(np.round(depth * scale), 0, 65535) / scale
        frame = Frame(
            index=index,
            frame_id=f"{index:06d}",
            timestamp=float(index),
            rgb=rgb,
            depth=depth_mm.astype(np.float32),
            pose=self.poses[index],
            intrinsics=self.intrinsics,
            instances=ids,
            instance_labels=labels,
        )
        return frame.validate()
