"""The geometric stream on a small generated house: rooms and floors against the
simulator's ground truth, and the stream feeding a scene graph."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.geometry import FloorChanged, GeometricStream
from inherit_sg.model import EdgeKind, RoomNode, SceneGraph

generate = pytest.importorskip("inherit_sg.ingest.synthetic.generate")
isg = pytest.importorskip("inherit_sg.ingest.isg")
geo_eval = pytest.importorskip("inherit_sg.benchmark.metrics.geometry")


@pytest.fixture(scope="module")
def two_floor_house(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("house") / "isg"
    house = generate.generate_house(8, 2, open_plan=False)  # rooms walled: doors divide them
    generate.write_dataset(house, out, width=160, height=120, workers=1)
    return out


def test_rooms_and_floors_match_ground_truth(two_floor_house: Path) -> None:
    from inherit_sg.ingest.synthetic.scene import Scene

    reader = isg.IsgReader(two_floor_house)
    stream = GeometricStream(enqueue_keyframes=False)
    camera_z = []
    changes = []
    for frame in reader:
        changes += [e for e in stream.process(frame) if isinstance(e, FloorChanged)]
        camera_z.append(float(frame.pose.translation[2]))
    stream.refine()
    scene = Scene.load(two_floor_house)
    report = geo_eval.evaluate_stream(stream, scene, camera_z)
    assert report.floors.count_exact and len(changes) == 1
    assert report.floors.frame_accuracy > 0.95
    assert report.rooms.precision >= 0.85 and report.rooms.recall >= 0.85
    assert report.rooms.mean_iou > 0.7
    live = geo_eval.evaluate_stream(stream, scene, camera_z, refined=False)
    assert live.rooms.precision >= 0.85 and live.rooms.recall >= 0.85

    graph = SceneGraph()
    stream.apply_to(graph)
    rooms = [n for n in graph.nodes() if isinstance(n, RoomNode)]
    assert len(rooms) == report.rooms.predicted
    assert all(r.best_view is not None for r in rooms)
    assert len(list(graph.edges(EdgeKind.STAIRS))) == 1
    doors = [d for d in scene.doors if len(d.rooms) == 2]
    assert len(list(graph.edges(EdgeKind.CONNECTS))) >= 0.8 * len(doors)
