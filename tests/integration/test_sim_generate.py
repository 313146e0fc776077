"""`sim generate` end to end: the written folder loads with IsgReader and validates."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from inherit_sg.cli.sim import app
from inherit_sg.ingest.isg import IsgReader
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.ingest.synthetic.scene import Scene

runner = CliRunner()


@pytest.fixture(scope="module")
def house_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("sim") / "H"
    args = ["generate", "--seed", "7", "--floors", "2", "--out", str(out)]
    result = runner.invoke(app, [*args, "--width", "96", "--height", "72", "--json"])
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout[result.stdout.index("{") :])
    return out, summary


def test_generate_writes_a_two_floor_house(house_dir):
    out, summary = house_dir
    scene = Scene.load(out)
    assert len(scene.floors) == 2 and summary["floors"] == 2
    assert len(scene.rooms) >= 8 and summary["rooms"] == len(scene.rooms)
    assert {r.floor for r in scene.rooms} == {0, 1}
    assert summary["objects"] == len(scene.objects) > 50
    intrinsics = json.loads((out / "intrinsics.json").read_text())
    assert (intrinsics["width"], intrinsics["height"]) == (96, 72)


def test_every_frame_loads_and_validates(house_dir):
    out, summary = house_dir
    reader = IsgReader(out)
    assert len(reader) == summary["frames"] > 150
    zs = []
    for frame in reader:  # read() validates every frame
        assert frame.instances is not None
        ids = set(np.unique(frame.instances)) - {0}
        assert ids == set(frame.instance_labels)
        assert ids == set(range(1, len(ids) + 1))  # re-numbered per frame
        zs.append(frame.pose.translation[2])
    assert max(zs) - min(zs) > 2.5  # the walk went upstairs


def test_frame_ids_do_not_reveal_objects(house_dir):
    out, _ = house_dir
    scene = Scene.load(out)
    global_label = {o.instance_id: o.label for o in scene.objects}
    reader = IsgReader(out)
    agree = total = 0
    for index in range(0, len(reader), 10):
        frame = reader.read(index)
        for k, label in frame.instance_labels.items():
            total += 1
            agree += global_label.get(k) == label
    assert total > 50 and agree / total < 0.5


def test_existing_output_needs_force(house_dir):
    out, _ = house_dir
    result = runner.invoke(app, ["generate", "--seed", "1", "--floors", "1", "--out", str(out)])
    assert result.exit_code == 2
    assert "not empty" in result.output and "--force" in result.output


def test_floors_outside_range_are_rejected(tmp_path):
    result = runner.invoke(app, ["generate", "--floors", "4", "--out", str(tmp_path / "x")])
    assert result.exit_code == 2
    assert "--floors" in result.output
    assert not (tmp_path / "x").exists()


def test_force_replaces_a_dataset_and_workers_agree(tmp_path):
    house = generate_house(5, 1, 4)
    a, b = tmp_path / "a", tmp_path / "b"
    write_dataset(house, a, width=64, height=48, workers=1, max_frames=9, noise="noisy")
    write_dataset(house, b, width=64, height=48, workers=2, max_frames=9, noise="noisy")
    for name in (
        "scene.json",
        "poses.txt",
        "frames/000008.rgb.png",
        "frames/000008.instances.json",
    ):
        assert (a / name).read_bytes() == (b / name).read_bytes()
    (a / "notes.txt").write_text("keep me")
    args = ["generate", "--seed", "5", "--floors", "1", "--rooms-per-floor", "4"]
    result = runner.invoke(
        app,
        [*args, "--out", str(a), "--width", "64", "--height", "48", "--max-frames", "3", "--force"],
    )
    assert result.exit_code == 0, result.output
    assert len(IsgReader(a)) == 3 and (a / "notes.txt").read_text() == "keep me"
    assert not (a / "frames" / "000008.rgb.png").exists()
