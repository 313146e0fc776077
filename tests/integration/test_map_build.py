"""End-to-end mapping on a small generated house with the real Kuzu + LanceDB store:
build, quality against ground truth, a second session, missing objects, interruption."""

from __future__ import annotations

import json
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.benchmark.metrics.mapping import evaluate_objects
from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.ingest.synthetic.ground_truth_files import seen_objects
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.model import EdgeKind, Layer, ObjectStatus
from inherit_sg.store import MapStore


@pytest.fixture(scope="module")
def house_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("house") / "h"
    # the walk without close looks: at 240x180 they show things hung on the far side of
    # a thin wall "in clear view" (see the missing-object note in docs/architecture.md)
    write_dataset(generate_house(3, 1, 5), out, width=240, height=180, workers=1, close_looks=False)
    return out


@pytest.fixture(scope="module")
def built(house_dir: Path, tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict]:
    map_dir = tmp_path_factory.mktemp("maps") / "m"
    summary = build_map(house_dir, map_dir)
    return map_dir, summary


def test_build_makes_a_full_hierarchy(built: tuple[Path, dict]) -> None:
    map_dir, summary = built
    assert summary["frames"] > 50 and summary["keyframes"] > 10
    assert summary["dropped_keyframes"] == 0  # recorded datasets never drop keyframes
    assert summary["floors"] == 1 and summary["rooms"] >= 3 and summary["objects"] >= 20
    assert all(Path(p).is_file() for p in summary["bev"])
    with MapStore.open(map_dir) as store:
        graph = store.load_graph()
        stats = store.stats()
        kf_rows = store.cypher(
            "MATCH (o:Object)-[s:SEEN_IN]->(k:Keyframe) RETURN o.id, k.id, s.props LIMIT 5"
        ).rows
        some_kf = store.get_keyframe(kf_rows[0][1], with_image=True)
    assert stats.nodes["Keyframe"] == summary["keyframes"]
    assert some_kf.jpeg is not None and some_kf.jpeg[:2] == b"\xff\xd8"
    props = json.loads(kf_rows[0][2])
    assert len(props["bbox"]) == 4 and props["label"]
    for obj in graph.objects():
        assert graph.parent(obj.id) is not None, f"{obj.id} has no area"
        assert obj.text_embedding is not None and obj.visual_feature is not None
        assert obj.description.startswith(("a ", "an "))
    rooms = list(graph.nodes(Layer.ROOM))
    assert all(graph.parent(r.id) == "floor:0" for r in rooms)
    assert any(r.label != "room" for r in rooms)  # contents name at least one room
    assert sum(1 for _ in graph.edges(EdgeKind.RELATION)) > 0


def test_build_quality_against_ground_truth(built: tuple[Path, dict], house_dir: Path) -> None:
    map_dir, _ = built
    with MapStore.open(map_dir) as store:
        graph = store.load_graph()
    quality = evaluate_objects(
        list(graph.objects()),
        Scene.load(house_dir),
        visible=seen_objects(house_dir),
        relations=graph.edges(EdgeKind.RELATION),
    )
    # small images (240x180) make small objects hard; the benchmark measures full size
    assert quality.precision >= 0.8, quality.to_dict()
    assert quality.recall >= 0.75, quality.to_dict()
    assert quality.duplicate_rate <= 0.1, quality.to_dict()


def _hide_label(src: Path, dst: Path, label: str) -> int:
    """Copy a dataset, removing every detection of ``label`` (the object is 'gone')."""
    shutil.copytree(src, dst)
    hidden = 0
    for meta in sorted((dst / "frames").glob("*.instances.json")):
        labels = json.loads(meta.read_text())
        drop = [int(k) for k, v in labels.items() if v["label"] == label]
        if not drop:
            continue
        png = meta.with_name(meta.name.replace(".json", ".png"))
        ids = cv2.imread(str(png), cv2.IMREAD_UNCHANGED)
        ids[np.isin(ids, drop)] = 0
        cv2.imwrite(str(png), ids)
        meta.write_text(json.dumps({k: v for k, v in labels.items() if int(k) not in drop}))
        hidden += len(drop)
    return hidden


def test_second_session_appends_and_marks_missing(
    built: tuple[Path, dict], house_dir: Path, tmp_path: Path
) -> None:
    map_dir, _ = built
    work = tmp_path / "m"
    shutil.copytree(map_dir, work)
    with MapStore.open(work) as store:
        before = {o.id: o for o in store.load_graph().objects()}
    target = next(
        o.label for o in before.values() if o.label in ("bed", "sofa", "desk", "table", "wardrobe")
    )
    variant = tmp_path / "h2"
    assert _hide_label(house_dir, variant, target) > 0
    second = build_map(variant, work, session_name="second visit")
    with MapStore.open(work) as store:
        sessions = store.sessions()
        after = {o.id: o for o in store.load_graph().objects()}
    assert [s.name for s in sessions] == ["session-1", "second visit"]
    assert [s.state for s in sessions] == ["finished", "finished"]
    # re-observation updates existing nodes instead of duplicating them
    assert len(after) <= len(before) * 1.1
    kept = [i for i in before if i in after and after[i].status is ObjectStatus.ACTIVE]
    assert sum(after[i].last_seen > before[i].last_seen for i in kept) >= 0.8 * len(kept)
    missing = [o for o in after.values() if o.status is ObjectStatus.MISSING]
    assert missing and {o.label for o in missing} == {target}
    assert second["missing"] == len(missing)


def test_rewalking_part_of_an_unchanged_house_marks_nothing_missing(
    built: tuple[Path, dict], house_dir: Path, tmp_path: Path
) -> None:
    """Ground truth: nothing moved, so nothing may go missing when the robot walks the
    first half of the same house again (a partial view of a large object, a far or tiny
    one, is no evidence that it left)."""
    map_dir, first = built
    work = tmp_path / "again"
    shutil.copytree(map_dir, work)
    half = len((house_dir / "poses.txt").read_text().splitlines()) // 2
    second = build_map(house_dir, work, session_name="part again", max_frames=half)
    assert second["missing"] == 0, second
    with MapStore.open(work) as store:
        graph = store.load_graph()
        statuses = {o.status for o in graph.objects()}
        # which keyframes saw each object is stored, so this can be measured
        seen_in = list(graph.edges(EdgeKind.SEEN_IN))
    assert statuses == {ObjectStatus.ACTIVE}
    assert len({e.src for e in seen_in}) >= 0.9 * first["objects"]


def test_interrupted_build_leaves_an_openable_map(house_dir: Path, tmp_path: Path) -> None:
    map_dir = tmp_path / "killed"
    code = (
        "import sys; from inherit_sg.facade import build_map; build_map(sys.argv[1], sys.argv[2])"
    )
    proc = subprocess.Popen([sys.executable, "-c", code, str(house_dir), str(map_dir)])
    deadline = time.time() + 120
    # wait until at least one batch was committed, then kill without warning
    while time.time() < deadline:
        state = map_dir / "geometry.npz"
        if state.is_file():
            break
        time.sleep(0.2)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    assert (map_dir / "geometry.npz").is_file(), "no batch was committed before the deadline"
    with MapStore.open(map_dir) as store:
        # a read-only open changes nothing: the killed session still shows no end
        assert [s.state for s in store.sessions()] == [""]
    with MapStore.open(map_dir, write=True) as store:  # the lock of the dead writer is stale
        # the next writable open records the killed session as interrupted
        (killed,) = store.sessions()
        assert killed.state == "interrupted" and killed.finished is None
        graph = store.load_graph()
        assert len(list(graph.objects())) > 0
        for obj in graph.objects():
            # early in a walk an object may lie outside every room seen so far
            assert (graph.parent(obj.id) is not None) == (obj.room_id is not None), obj.id


class _Payload:
    """Unpickling this runs ``touch <marker>``: what a planted map file could do."""

    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self) -> tuple[object, tuple[str, ...]]:
        import os

        return (os.system, (f"touch {self.marker}",))


def test_a_planted_state_file_runs_nothing(
    built: tuple[Path, dict], house_dir: Path, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    import pickle

    map_dir, _ = built
    work = tmp_path / "shared-map"
    shutil.copytree(map_dir, work)
    marker = tmp_path / "payload-ran"
    # the old file name, as a map of an earlier version (or an attacker) would leave it
    (work / "geometry.npz").unlink()
    (work / "geometry.pkl").write_bytes(pickle.dumps(_Payload(marker)))
    with caplog.at_level("WARNING"):
        build_map(house_dir, work, session_name="after the plant", max_frames=20)
    assert not marker.exists(), "a map file ran code"
    assert "not read" in caplog.text and "geometry.pkl" in caplog.text
    # the same payload under the new name is refused as data, and nothing runs either
    (work / "geometry.npz").write_bytes(pickle.dumps(_Payload(marker)))
    caplog.clear()
    with caplog.at_level("WARNING"):
        build_map(house_dir, work, session_name="third", max_frames=20)
    assert not marker.exists(), "a map file ran code"
    assert "ignoring geometry state" in caplog.text
    with MapStore.open(work) as store:
        assert [s.name for s in store.sessions()][-2:] == ["after the plant", "third"]
