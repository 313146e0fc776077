"""`inherit-sg bench` end to end on the smallest generated house: the map is built from
rendered frames, the dataset's requests are answered by ours and the flat baseline, and
the results JSON has every section with values in range."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from inherit_sg.cli.main import app
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset

GROUPS = ("A-C", "D", "E", "F", "overall", "group_mean")


@pytest.fixture(scope="module")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("bench-house") / "house"
    write_dataset(generate_house(11, 1, 4), out, width=160, height=120, workers=2)
    return out


def test_bench_builds_measures_and_writes_the_results(dataset: Path, tmp_path: Path) -> None:
    out = tmp_path / "results.json"
    args = ["bench", "--dataset", str(dataset), "--out", str(out), "--max-queries", "12"]
    result = CliRunner().invoke(app, [*args, "--no-ablations", "--set", "retrieval.top_k=5"])
    assert result.exit_code == 0, result.output
    doc = json.loads(out.read_text())
    assert doc["config_overrides"] == ["retrieval.top_k=5"]
    assert doc["queries"]["source"] == "dataset" and doc["queries"]["count"] == 12
    assert doc["ablations"] == {"skipped": "--no-ablations"}
    for system in ("ours", "flat"):
        summary = doc["accuracy"][system]
        assert summary["overall"]["n"] == 12
        for group in GROUPS:
            for metric in ("within_1m", "within_0.5m", "semantic"):
                value = summary[group][metric]
                assert value is None or 0.0 <= value <= 100.0
        assert summary["overall"]["within_0.5m"] <= summary["overall"]["within_1m"]
        lat = doc["latency_ms"][system]["total"]
        assert 0.0 < lat["p50"] <= lat["p99"]
    mapping = doc["mapping"]
    assert mapping["source"] == "build" and mapping["frames"] > 0
    assert mapping["build_s"] > 0 and mapping["frames_per_s"] > 0 and mapping["peak_rss_mb"] > 100
    assert mapping["geometry_fps"] > 0 and mapping["semantic_keyframes_per_s"] > 0
    objects, rooms = mapping["quality"]["objects"], mapping["quality"]["rooms"]
    assert 0.5 < objects["precision"] <= 1.0 and 0.5 < objects["recall"] <= 1.0
    assert 0.0 < rooms["precision"] <= 1.0 and 0.0 < rooms["recall"] <= 1.0
    storage = doc["storage"]
    assert storage["object"]["nodes"] == doc["map_size"]["object"] > 0
    assert storage["object"]["feature_bytes"] > 0 and storage["object"]["image_bytes"] > 0
    assert storage["map"]["total_bytes"] > storage["map"]["without_images_bytes"] > 0
    assert "ours" in result.output and f"results written to {out}" in result.output


def test_bench_refuses_a_folder_without_ground_truth(tmp_path: Path) -> None:
    out = tmp_path / "r.json"
    result = CliRunner().invoke(app, ["bench", "--dataset", str(tmp_path), "--out", str(out)])
    assert result.exit_code == 2 and "scene.json" in result.output
    assert not out.exists()


def test_bench_on_a_given_map_reports_unrecorded_speed_as_na(dataset: Path, tmp_path: Path) -> None:
    from inherit_sg.facade import import_into_new_map

    oracle = tmp_path / "oracle"
    import_into_new_map(dataset / "scene.json", oracle, fmt="scene")
    out = tmp_path / "results.json"
    args = ["bench", "-d", str(dataset), "-m", str(oracle), "-o", str(out), "--max-queries", "6"]
    result = CliRunner().invoke(app, [*args, "--quiet"])
    assert result.exit_code == 0, result.output
    doc = json.loads(out.read_text())
    assert doc["map"] == str(oracle)
    assert doc["mapping"]["source"] == "sessions" and doc["mapping"]["sessions"] == []
    assert doc["mapping"]["build_s"] == "n/a" and doc["mapping"]["peak_rss_mb"] == "n/a"
    assert doc["mapping"]["quality"]["objects"]["precision"] == 1.0
    assert doc["storage"]["object"]["image_bytes"] == 0.0
    ablations = doc["ablations"]
    assert ablations["without verification"]["override"] == "retrieval.verify=False"
    assert ablations["without areas"]["accuracy"]["overall"]["n"] == 6
    assert "skipped" in ablations["LLM parser instead of rules"]
