"""`sim render-house` on the real Matterport3D house: the written folder is a complete isg
dataset whose geometry, ground truth and queries stay in the file's own coordinates."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from inherit_sg.cli.sim import app
from inherit_sg.ingest.isg import IsgReader
from inherit_sg.ingest.mp3d_dataset import HouseWorld, load_house_world
from inherit_sg.ingest.synthetic.generate import make_intrinsics
from inherit_sg.ingest.synthetic.queries import read_queries
from inherit_sg.ingest.synthetic.render import Renderer
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.ingest.synthetic.truth import ObjectSpec, SceneIndex, evaluate

REPO_ROOT = Path(__file__).resolve().parents[2]
HOUSE = REPO_ROOT / ".." / "shared" / "data" / "real" / "mp3d" / "example_mp3d_scene.house"
runner = CliRunner()


@pytest.fixture(scope="module")
def house_file() -> Path:
    if not HOUSE.is_file():
        pytest.skip(f"shared real data not found at {HOUSE}")
    return HOUSE


@pytest.fixture(scope="module")
def rendered(house_file: Path, tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict]:
    out = tmp_path_factory.mktemp("mp3d") / "house"
    args = ["render-house", str(house_file), "--out", str(out), "--seed", "1"]
    result = runner.invoke(app, [*args, "--width", "96", "--height", "72", "--json"])
    assert result.exit_code == 0, result.output
    return out, json.loads(result.stdout[result.stdout.index("{") :])


@pytest.fixture(scope="module")
def world(house_file: Path) -> HouseWorld:
    return load_house_world(house_file)


def _o_line(house_file: Path, index: int) -> list[float]:
    for line in house_file.read_text().splitlines():
        parts = line.split()
        if parts[:2] == ["O", str(index)]:
            return [float(v) for v in parts[4:7]]
    raise AssertionError(f"no O line {index}")


def test_scene_has_the_ten_rooms_and_source_coordinates(rendered, house_file):
    out, summary = rendered
    scene = Scene.load(out)
    assert len(scene.rooms) == 10 and summary["rooms"] == 10 and summary["floors"] == 1
    assert summary["objects"] == len(scene.objects) > 120
    bed = next(o for o in scene.objects if o.label == "bed")
    assert bed.centroid == pytest.approx(_o_line(house_file, bed.attributes["mp3d_index"]))
    assert scene.room(bed.room_id or "").type == "bedroom"
    assert all(isinstance(o.attributes.get("colour"), str) for o in scene.objects)
    assert len(scene.doors) >= 9  # every opening between rooms is a door of the ground truth


def test_frames_validate_and_the_walk_covers_every_room(rendered):
    out, summary = rendered
    reader = IsgReader(out)
    assert len(reader) == summary["frames"] > 150
    with_objects = 0
    for frame in reader:  # read() validates every frame
        assert frame.instances is not None
        ids = set(np.unique(frame.instances).tolist()) - {0}
        assert ids == set(frame.instance_labels)
        with_objects += bool(ids)
        x, y, _ = frame.pose.translation
        assert -11.6 < x < 5.2 and -3.0 < y < 6.0  # inside the level's box from the L line
    assert with_objects > 0.8 * len(reader)
    walk = json.loads((out / "walk.json").read_text())
    assert {r for r in walk["rooms"] if r} == {f"r{k}" for k in range(10)}
    visibility = json.loads((out / "visibility.json").read_text())
    assert sum(v["frames"] >= 2 for v in visibility.values()) > 80


def test_written_depth_matches_the_geometry(rendered, world):
    out, _ = rendered
    reader = IsgReader(out)
    k = make_intrinsics(96, 72)
    renderer = Renderer(world.world, world.lights, k)
    traj = world.trajectory(1)
    # the boxes each object is drawn as (the file's boxes, adjusted by inherit_sg.ingest.mp3d_drawn)
    parts = {o.instance_id: world.drawn[o.id].parts for o in world.scene.objects}
    checked = 0
    for index in range(0, len(reader), 25):
        frame = reader.read(index)
        truth = renderer.render(traj.poses[index])
        assert np.abs(frame.depth - truth.depth).max() < 1e-3  # written at 1 mm
        v, u = np.nonzero(truth.instances)
        z = truth.depth[v, u]
        pts = np.stack([(u - k.cx) / k.fx * z, (v - k.cy) / k.fy * z, z], axis=1)
        world_pts = traj.poses[index].transform_points(pts)
        for inst in np.unique(truth.instances[v, u]):
            pts_inst = world_pts[truth.instances[v, u] == inst]
            inside = np.zeros(len(pts_inst), dtype=bool)
            for box in parts[int(inst)]:
                local = (pts_inst - box.center) @ box.axes.T
                inside |= np.all(np.abs(local) <= box.radii + 0.02, axis=1)
            assert inside.all()
            checked += 1
    assert checked > 20


def test_ground_truth_keeps_categories_and_buried_objects_are_seen(rendered, world):
    out, _ = rendered
    scene = Scene.load(out)
    codes = {r.id: r.attributes["mp3d_code"] for r in scene.rooms}
    assert sorted(codes.values()) == sorted("abtavdelfk")
    assert {r.type for r in scene.rooms} >= {"tv room", "family room", "toilet", "entryway"}
    oven = next(o for o in scene.objects if o.label == "oven")
    assert oven.attributes["mpcat40"] == "appliances" and oven.attributes["mp3d_index"] == 179
    # The oven, the dishwasher and the pillows lie inside larger boxes in the file; they
    # are drawn proud of them and so reach the instance masks of the walk.
    assert "proud of o175" in oven.attributes["drawn"]
    visibility = json.loads((out / "visibility.json").read_text())
    buried_in_file = ("oven", "dishwasher", "sink", "coffee table")
    for label in buried_in_file:
        obj = next(o for o in scene.objects if o.label == label and o.room_id in ("r8", "r9"))
        assert visibility.get(obj.id, {}).get("max_pixels", 0) > 0, label
    pillows = [o for o in scene.objects if o.label == "pillow" and o.room_id == "r0"]
    assert sum(visibility.get(o.id, {}).get("max_pixels", 0) > 0 for o in pillows) >= 3


def test_queries_have_verified_answer_sets(rendered):
    out, _ = rendered
    scene = Scene.load(out)
    queries = read_queries(out)
    assert len(queries) > 50 and {q.category for q in queries} >= {"A", "B", "C", "D", "E", "F"}
    index = SceneIndex(scene)
    for q in queries:
        assert sorted(evaluate(scene, ObjectSpec.from_dict(q.gt_constraints), index)) == sorted(
            q.target_ids
        )
        for oid, pos in zip(q.target_ids, q.target_positions, strict=True):
            assert scene.object(oid).centroid == pytest.approx(pos)


def test_render_house_input_errors(rendered, tmp_path):
    out, _ = rendered
    result = runner.invoke(app, ["render-house", str(tmp_path / "none.house"), "--out", str(out)])
    assert result.exit_code == 2 and "not found" in result.output
    result = runner.invoke(app, ["render-house", str(HOUSE), "--out", str(out)])
    assert result.exit_code == 2 and "--force" in result.output
