"""``map build-many`` on a local Ray cluster: three small generated houses built in
parallel equal the maps built one by one; a worker killed mid-map is retried and the
map is whole, and with retries exhausted the map is reported with nothing half-written
left under the root."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import pytest
from typer.testing import CliRunner

from inherit_sg.cli.main import app
from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.scale.atomic import FAULT_VARIABLE
from inherit_sg.scale.build_many import build_many
from inherit_sg.scale.compare import map_signature, same_objects
from inherit_sg.scale.manifest import read_manifest

ray = pytest.importorskip("ray")
from inherit_sg.scale.cluster import LOCAL_OBJECT_STORE_MB, local_cpus  # noqa: E402

SEEDS = (3, 4, 5)
FRAMES = 40  # the start of each walk: about 5 s per map on one core


@pytest.fixture(scope="module")
def houses(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("houses")
    lines = []
    for seed in SEEDS:
        write_dataset(
            generate_house(seed, 1, 4),
            root / f"walk{seed}",
            width=128,
            height=96,
            workers=1,
            max_frames=FRAMES,
            close_looks=False,
        )
        lines.append(json.dumps({"dataset": f"walk{seed}", "map": f"house{seed}"}))
    (root / "manifest.jsonl").write_text("\n".join(lines) + "\n", encoding="utf-8")
    return root


@pytest.fixture(scope="module")
def one_by_one(houses: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The reference: each house built alone with ``build_map`` (what ``map build`` does)."""
    root = tmp_path_factory.mktemp("one_by_one")
    for seed in SEEDS:
        build_map(houses / f"walk{seed}", root / f"house{seed}")
    return {f"house{seed}": root / f"house{seed}" for seed in SEEDS}


@pytest.fixture(scope="module")
def local_ray() -> Iterator[None]:
    """One small local Ray cluster for the module (the commands use it as it is)."""
    ray.init(
        num_cpus=local_cpus(),
        object_store_memory=LOCAL_OBJECT_STORE_MB * 1024 * 1024,
        include_dashboard=False,
        log_to_driver=False,
    )
    try:
        yield
    finally:
        ray.shutdown()


def test_build_many_equals_one_by_one(
    houses: Path, one_by_one: dict[str, Path], local_ray: None, tmp_path: Path
) -> None:
    out = tmp_path / "maps"
    res = CliRunner().invoke(
        app, ["map", "build-many", str(houses / "manifest.jsonl"), "--out", str(out), "--json"]
    )
    assert res.exit_code == 0, res.output
    report = json.loads(res.stdout[res.stdout.index("{") :])
    assert [m["map"] for m in report["maps"]] == list(one_by_one)
    assert {m["status"] for m in report["maps"]} == {"built"}
    assert sorted(p.name for p in out.iterdir()) == sorted(one_by_one)  # no temp folders
    for name, reference in one_by_one.items():
        got, want = map_signature(out / name), map_signature(reference)
        assert got["objects"] and got["seen_in"]
        assert same_objects(got, want), name
        # floors and their rooms exist in both; the room split itself depends on when the
        # global updates ran (see inherit_sg/scale/compare.py)
        assert got["counts"]["nodes"]["Floor"] == want["counts"]["nodes"]["Floor"]
        assert got["counts"]["nodes"]["Room"] >= 1


def test_killed_worker_is_retried_and_the_map_is_whole(
    houses: Path,
    one_by_one: dict[str, Path],
    local_ray: None,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    marks = tmp_path / "kills"
    fault = {"map": "house4", "after_frames": 12, "times": 1, "marks": str(marks)}
    monkeypatch.setenv(FAULT_VARIABLE, json.dumps(fault))
    jobs = [j for j in read_manifest(houses / "manifest.jsonl") if j.name == "house4"]
    report = build_many(jobs, tmp_path / "maps", max_retries=2)
    assert len(list(marks.iterdir())) == 1  # the first attempt's worker was SIGKILLed
    assert report["built"] == 1, report
    assert [p.name for p in (tmp_path / "maps").iterdir()] == ["house4"]
    got, want = map_signature(tmp_path / "maps" / "house4"), map_signature(one_by_one["house4"])
    assert same_objects(got, want)  # the retry mapped the whole walk, once


def test_retries_exhausted_reports_and_leaves_nothing(
    houses: Path, local_ray: None, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    marks = tmp_path / "kills"
    fault = {"map": "house5", "after_frames": 8, "times": 99, "marks": str(marks)}
    monkeypatch.setenv(FAULT_VARIABLE, json.dumps(fault))
    jobs = [j for j in read_manifest(houses / "manifest.jsonl") if j.name == "house5"]
    report = build_many(jobs, tmp_path / "maps", max_retries=1)
    assert len(list(marks.iterdir())) == 2  # first try and one retry, both killed
    assert report["failed"] == 1 and report["built"] == 0
    record = report["maps"][0]
    assert record["status"] == "failed"
    assert "died" in record["error"], record
    assert list((tmp_path / "maps").iterdir()) == []  # no map, no temp folder


def test_sessions_run_in_order_and_extend_an_existing_map(
    houses: Path, local_ray: None, tmp_path: Path
) -> None:
    out = tmp_path / "maps"
    manifest = tmp_path / "days.jsonl"
    day = {"dataset": str(houses / "walk3"), "max_frames": 10}
    manifest.write_text(
        json.dumps({"map": "house3", "sessions": [{**day, "session": "mon"}]}) + "\n",
        encoding="utf-8",
    )
    assert build_many(read_manifest(manifest), out)["built"] == 1
    manifest.write_text(
        json.dumps(
            {
                "map": "house3",
                "sessions": [{**day, "session": "tue"}, {**day, "session": "wed"}],
            }
        )
        + "\n",
        encoding="utf-8",
    )
    report = build_many(read_manifest(manifest), out)
    assert report["built"] == 1, report
    names = [s[1] for s in map_signature(out / "house3")["sessions"]]
    assert names == ["mon", "tue", "wed"]
    assert [p.name for p in out.iterdir()] == ["house3"]


def test_bad_dataset_is_reported_without_retries(local_ray: None, tmp_path: Path) -> None:
    (tmp_path / "empty").mkdir()
    manifest = tmp_path / "bad.jsonl"
    manifest.write_text(json.dumps({"dataset": "empty"}) + "\n", encoding="utf-8")
    res = CliRunner().invoke(
        app, ["map", "build-many", str(manifest), "--out", str(tmp_path / "maps")]
    )
    assert res.exit_code == 1, res.output
    assert "0 built, 1 failed" in res.output
    assert list((tmp_path / "maps").iterdir()) == []
