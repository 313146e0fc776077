"""Format registry, layout detection and open_dataset."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import inherit_sg.ingest.readers as readers
from inherit_sg.errors import DatasetError
from inherit_sg.ingest.isg import IsgReader, IsgWriter
from inherit_sg.ingest.readers import (
    FrameSource,
    ReaderSpec,
    detect_format,
    formats,
    open_dataset,
    register_format,
)
from inherit_sg.model import Intrinsics, Pose

LAYOUTS = {
    "isg": ["intrinsics.json", "poses.txt"],
    "replica": ["results/", "traj.txt", "cam_params.json"],
    "scannet": ["color/", "depth/", "pose/", "intrinsic/"],
    "tum": ["rgb.txt", "depth.txt"],
    "hm3d": ["rgb/", "depth/", "pose/"],
}


def _touch(root: Path, entries: list[str]) -> Path:
    root.mkdir(parents=True, exist_ok=True)
    for entry in entries:
        if entry.endswith("/"):
            (root / entry).mkdir(exist_ok=True)
        else:
            (root / entry).write_text("")
    return root


@pytest.mark.parametrize("name", list(LAYOUTS))
def test_each_layout_is_detected(tmp_path: Path, name: str) -> None:
    assert detect_format(_touch(tmp_path / name, LAYOUTS[name])) == name


def test_builtin_formats_are_registered_in_priority_order() -> None:
    assert formats()[:5] == ["isg", "replica", "scannet", "tum", "hm3d"]


def test_a_folder_missing_one_marker_is_not_that_format(tmp_path: Path) -> None:
    almost = _touch(tmp_path / "almost", ["color/", "depth/", "intrinsic/"])  # ScanNet, no pose/
    with pytest.raises(
        DatasetError, match=r"no known dataset layout; looked for isg \(intrinsics\.json"
    ):
        detect_format(almost)
    with pytest.raises(DatasetError, match="not found"):
        detect_format(tmp_path / "missing")


def test_open_dataset_opens_an_isg_folder_and_rejects_unknown_formats(tmp_path: Path) -> None:
    intr = Intrinsics(8, 6, 5.0, 5.0, 3.5, 2.5, 1000.0)
    with IsgWriter(tmp_path / "isg", intr) as writer:
        writer.write(
            "f0", np.zeros((6, 8, 3), np.uint8), np.ones((6, 8), np.float32), Pose.identity()
        )
    source = open_dataset(tmp_path / "isg")
    assert isinstance(source, IsgReader) and isinstance(source, FrameSource)
    assert len(source) == 1 and source.read(0).depth[0, 0] == pytest.approx(1.0)
    with pytest.raises(DatasetError, match="unknown dataset format 'bogus'"):
        open_dataset(tmp_path / "isg", format="bogus")
    with pytest.raises(DatasetError, match="not found"):
        open_dataset(tmp_path / "nowhere", format="replica")


def test_adding_a_format_is_one_registration(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(readers, "_REGISTRY", dict(readers._REGISTRY))
    register_format(ReaderSpec("house", "inherit_sg.ingest.isg:IsgReader", ("*.layout",)))
    house = tmp_path / "scene.layout"
    house.write_text("ASCII 1.1\n")
    assert detect_format(house) == "house"  # a single file pattern also matches the file itself
    assert detect_format(_touch(tmp_path / "folder", ["a.layout"])) == "house"
    with pytest.raises(ValueError, match="already registered"):
        register_format(ReaderSpec("house", "x:y", ("*.layout",)))
    with pytest.raises(ValueError, match="reserved"):
        register_format(ReaderSpec("auto", "x:y", ("*",)))
