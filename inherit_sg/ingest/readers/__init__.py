"""Dataset readers: a registry of formats, layout auto-detection and :func:`open_dataset`.

Every reader yields :class:`inherit_sg.model.Frame` in the z-up world frame with OpenCV
camera axes, depth in metres and colour in RGB order. Adding a format is one
:class:`ReaderSpec` entry (built-ins below, or :func:`register_format` from elsewhere);
reader modules are imported only when a dataset of their format is opened.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from fnmatch import fnmatch
from pathlib import Path
from typing import Any, cast

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.readers.base import FrameSource, IndexedReader


@dataclass(frozen=True)
class ReaderSpec:
    """One dataset format.

    ``loader`` is ``"module:attribute"`` naming a callable ``(path, **options) ->
    FrameSource``. ``markers`` are glob patterns relative to the dataset folder that must
    all match for auto-detection; a trailing ``/`` asks for a folder. A spec whose only
    marker is a file pattern also matches a path to such a file. ``alternatives`` are
    further marker sets, any one of which also identifies the format.
    """

    name: str
    loader: str
    markers: tuple[str, ...]
    alternatives: tuple[tuple[str, ...], ...] = ()

    def matches(self, path: Path) -> bool:
        """Whether ``path`` has this format's layout."""
        return any(_layout_matches(path, m) for m in (self.markers, *self.alternatives))

    def load(self) -> Callable[..., FrameSource]:
        """Import and return the reader callable."""
        module_name, _, attribute = self.loader.partition(":")
        return cast(
            Callable[..., FrameSource], getattr(importlib.import_module(module_name), attribute)
        )


def _layout_matches(path: Path, markers: tuple[str, ...]) -> bool:
    if path.is_file():
        return len(markers) == 1 and not markers[0].endswith("/") and fnmatch(path.name, markers[0])
    return path.is_dir() and all(_has_marker(path, m) for m in markers)


def _has_marker(root: Path, marker: str) -> bool:
    want_dir = marker.endswith("/")
    pattern = marker.rstrip("/")
    return any(p.is_dir() if want_dir else p.is_file() for p in root.glob(pattern))


_REGISTRY: dict[str, ReaderSpec] = {}

#: Built-in formats, in detection priority order.
BUILTIN_FORMATS: tuple[ReaderSpec, ...] = (
    ReaderSpec("isg", "inherit_sg.ingest.isg:IsgReader", ("intrinsics.json", "poses.txt")),
    ReaderSpec(
        "replica",
        "inherit_sg.ingest.readers.replica:ReplicaReader",
        ("results/", "traj.txt", "cam_params.json"),
    ),
    ReaderSpec(
        "scannet",
        "inherit_sg.ingest.readers.scannet:ScanNetReader",
        ("color/", "depth/", "pose/", "intrinsic/"),
    ),
    ReaderSpec("tum", "inherit_sg.ingest.readers.tum:TumReader", ("rgb.txt", "depth.txt")),
    ReaderSpec("hm3d", "inherit_sg.ingest.readers.hm3d:Hm3dReader", ("rgb/", "depth/", "pose/")),
    ReaderSpec("mp3d", "inherit_sg.ingest.readers.mp3d:Mp3dReader", ("*.house",)),
    ReaderSpec("record3d", "inherit_sg.ingest.readers.record3d:Record3dReader", ("*.r3d",)),
    # a ROS 2 bag folder, a ROS 1 .bag file (or a folder of them), an .mcap file
    ReaderSpec(
        "rosbag",
        "inherit_sg.ingest.readers.rosbag:RosbagReader",
        ("metadata.yaml",),
        (("*.bag",), ("*.mcap",)),
    ),
)


def register_format(spec: ReaderSpec, replace: bool = False) -> None:
    """Add a format; detection tries formats in registration order."""
    if spec.name == "auto":
        raise ValueError("'auto' is reserved for detection")
    if spec.name in _REGISTRY and not replace:
        raise ValueError(f"dataset format {spec.name!r} is already registered")
    _REGISTRY[spec.name] = spec


for _spec in BUILTIN_FORMATS:
    register_format(_spec)


def formats() -> list[str]:
    """Registered format names, in detection order."""
    return list(_REGISTRY)


def detect_format(path: str | Path) -> str:
    """Name of the first registered format whose layout ``path`` has; DatasetError
    listing what was looked for when none fits."""
    root = Path(path)
    if not root.exists():
        raise DatasetError(f"dataset path not found: {root}")
    for spec in _REGISTRY.values():
        if spec.matches(root):
            return spec.name
    looked_for = "; ".join(f"{s.name} ({', '.join(s.markers)})" for s in _REGISTRY.values())
    raise DatasetError(f"{root}: no known dataset layout; looked for {looked_for}")


def open_dataset(path: str | Path, format: str = "auto", **options: Any) -> FrameSource:
    """Open ``path`` as a frame source of ``format`` (``"auto"`` detects it). Extra keyword
    options go to the reader (e.g. ``camera="fr2"`` for TUM, ``hfov_deg`` for HM3D,
    ``rgb_topic`` for rosbag)."""
    name = detect_format(path) if format == "auto" else format
    spec = _REGISTRY.get(name)
    if spec is None:
        raise DatasetError(f"unknown dataset format {name!r}; known: auto, {', '.join(_REGISTRY)}")
    return spec.load()(Path(path), **options)


__all__ = [
    "BUILTIN_FORMATS",
    "FrameSource",
    "IndexedReader",
    "ReaderSpec",
    "detect_format",
    "formats",
    "open_dataset",
    "register_format",
]
