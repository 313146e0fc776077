"""The benchmark page and figures rendered from result documents made by the real
metric functions."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.accuracy import accuracy_table
from inherit_sg.benchmark.latency import stage_latency
from inherit_sg.benchmark.metrics.retrieval import Outcome, summarise
from inherit_sg.benchmark.page import render_page
from inherit_sg.benchmark.plots import plot_accuracy, plot_latency_scale, plot_storage

PNG_MAGIC = b"\x89PNG"


def _outcomes(hits: int) -> list[Outcome]:
    """Two requests per category; the first ``hits`` are answered within 0.3 m."""
    out = []
    for i, cat in enumerate("AABBCCDDEEFF"):
        dist = 0.3 if i < hits else 2.0
        t = {"parse": 0.5, "retrieve": 2.0 + i, "verify": 1.0, "total": 3.5 + i}
        out.append(Outcome(f"q{i}", cat, "text", "obj:o1", dist, dist < 1.0, t))
    return out


def _node(feat: float, text: float, image: float) -> dict[str, float]:
    return {
        "nodes": 10,
        "feature_bytes": feat,
        "text_bytes": text,
        "text_string_bytes": 90.0,
        "node_bytes": feat + text,
        "image_bytes": image,
        "total_bytes": feat + text + image,
    }


def make_doc(name: str) -> dict[str, Any]:
    outcomes = {"ours": _outcomes(12), "flat": _outcomes(6)}
    quality = {"precision": 0.9, "recall": 0.8}
    return {
        "label": name,
        "description": f"{name} dataset",
        "queries": {"source": "generated", "count": 12, "available": 40},
        "map_size": {"floor": 1, "room": 4, "area": 6, "object": 10},
        "accuracy": accuracy_table(outcomes),
        "latency_ms": {k: stage_latency(v) for k, v in outcomes.items()},
        "ablations": {
            "full pipeline": {"accuracy": summarise(outcomes["ours"]), "mean_latency_ms": 9.0},
            "without verification": {
                "override": "retrieval.verify=False",
                "accuracy": summarise(outcomes["flat"]),
                "mean_latency_ms": 4.25,
            },
            "LLM parser instead of rules": {"skipped": "llm.endpoint is not configured"},
        },
        "mapping": {
            "frames": 120,
            "keyframes": 40,
            "build_s": 12.0,
            "frames_per_s": 10.0,
            "geometry_fps": 31.5,
            "semantic_keyframes_per_s": "n/a",
            "peak_rss_mb": 900.4,
            "quality": {"objects": quality, "rooms": {"precision": 1.0, "recall": 0.75}},
        },
        "storage": {
            "object": _node(1024.0, 1600.0, 13000.0),
            "room": _node(0.0, 1800.0, 0.0),
            "area": _node(0.0, 1500.0, 0.0),
            "map": {"total_bytes": 85 * 1024**2, "without_images_bytes": 83 * 1024**2},
        },
    }


def scale_rows() -> list[dict[str, Any]]:
    def stage(p50: float) -> dict[str, float]:
        return {"p50": p50, "p99": 3 * p50}

    return [
        {
            "objects": n,
            "houses": n // 100,
            "requests": 50,
            "first pass": {
                "parse": stage(0.3),
                "retrieve": stage(n / 500),
                "total": stage(n / 400),
            },
            "repeat pass": {
                "parse": stage(0.01),
                "retrieve": stage(n / 600),
                "total": stage(n / 550),
            },
        }
        for n in (100, 1000, 10000)
    ]


def test_page_has_every_section_with_the_documents_numbers() -> None:
    docs = [make_doc("house-a"), make_doc("house-b")]
    page = render_page(docs, scale_rows(), {"accuracy": "img/a.png"}, "Preamble.")
    for heading in (
        "## Datasets",
        "## Retrieval accuracy (Table II layout)",
        "## Semantic accuracy",
        "## Ablations",
        "## Mapping",
        "## Storage (Table III layout)",
        "## Query latency per stage",
        "## Latency by map size",
    ):
        assert heading in page
    assert "![accuracy within 1 m per category](img/a.png)" in page
    assert "Preamble." in page and "12 / 40 (generated)" in page
    ours_row = next(
        line for line in page.splitlines() if line.startswith("| house-a | INHerit-SG | 100.0")
    )
    assert ours_row.count("100.0") >= 10  # every group, 1 m and 0.5 m, overall and average
    flat_row = next(
        line for line in page.splitlines() if line.startswith("| house-a | flat baseline")
    )
    assert "| 0.0 | 0.0 |" in flat_row and "| 50.0 |" in flat_row
    assert (
        "| house-a | without verification | 100.0 | 0.0 | 0.0 | 0.0 | 50.0 | 50.0 | 4.2 |" in page
    )
    assert "LLM parser instead of rules: skipped (llm.endpoint is not configured)" in page
    assert "| house-a | 10 | 1.0 KB | 12.7 KB | 1.6 KB | 2.6 KB |" in page
    assert "85.0 MB / 83.0 MB" in page
    assert (
        "| house-a | 120 | 40 | 12.0 | 10.0 | 31.5 | n/a | 900 | 90.0 | 80.0 | 100.0 | 75.0 |"
        in page
    )
    assert "| 10000 | 100 | 50 | first pass |" in page


def test_figures_are_written_as_png(tmp_path: Path) -> None:
    docs = [make_doc("house-a"), make_doc("house-b")]
    paths = [
        plot_accuracy(docs, tmp_path / "img" / "acc.png"),
        plot_latency_scale(scale_rows(), tmp_path / "img" / "lat.png"),
        plot_storage(docs, tmp_path / "img" / "sto.png"),
    ]
    for path in paths:
        data = path.read_bytes()
        assert data.startswith(PNG_MAGIC) and len(data) > 5000


def test_page_shows_the_mp3d_rooms_region_by_region() -> None:
    rooms = {
        "regions": [
            {"region": "r0", "type": "bedroom", "area_m2": 17.3, "mapped_m2": 7.9,
             "matched": "room:5", "label": "bedroom", "label_exact": True, "label_top2": True},
            {"region": "r6", "type": "entryway", "area_m2": 7.3, "mapped_m2": 7.2,
             "matched": None, "label": None, "label_exact": False, "label_top2": False},
        ],
        "totals": {"regions": 2, "map_rooms": 2, "matched": 1, "precision": 0.5,
                   "recall": 0.5, "label_exact": 1, "label_top2": 1},
    }  # fmt: skip
    objects = {"categories_seen": 3, "categories_found": 3, "objects_seen": 5,
               "objects_held": 5, "objects_found": 4}  # fmt: skip
    page = render_page(
        [make_doc("house-a")], None, {}, "", {"mp3d_rooms": rooms, "mp3d_objects": objects}
    )
    assert "## Rooms and objects on the Matterport3D house" in page
    assert "| r0 | bedroom | 7.9 / 17.3 | room:5 | bedroom | yes |" in page
    assert "| r6 | entryway | 7.2 / 7.3 | — | — | — |" in page
    assert "precision 0.50, recall 0.50" in page
    assert "3 of 3 categories in view are in the map" in page


def test_trust_tables_are_rendered_from_the_bench_files() -> None:
    hostile = {
        "summary": [
            {"surface": "cli", "inputs": 2, "clear errors": 2, "crashes or wrong outcomes": 0},
            {"surface": "all", "inputs": 2, "clear errors": 2, "crashes or wrong outcomes": 0},
        ]
    }
    isolation = {
        "statement_latency": {"in_process": {"p50_ms": 0.8, "p99_ms": 1.2},
                              "worker": {"p50_ms": 0.9, "p99_ms": 1.0}},
        "worker_start_s": 0.98, "time_limit_s": 10.0,
        "answered_after_limit_s": {"worker": 10.01},
        "crash": {"answered_after_crash_s": 0.015, "next_statement_s": 0.84},
    }  # fmt: skip
    page = render_page(
        [make_doc("house-a")], None, {}, "", {"hostile": hostile, "cypher_isolation": isolation}
    )
    assert "## Hostile inputs" in page and "| cli | 2 | 2 | 0 |" in page
    assert "## User Cypher in a worker process" in page
    assert "| small statement p50 / p99, worker | 0.90 ms / 1.00 ms |" in page
    assert "| a 10.0 s limit answers after (worker) | 10.01 s |" in page


def test_fresh_houses_are_rendered_from_their_summary(tmp_path: Path) -> None:
    """bench/fresh_seeds.py's summary: one row per house, the mean per noise level."""
    import importlib.util

    script = Path(__file__).resolve().parents[2] / "bench" / "fresh_seeds.py"
    spec = importlib.util.spec_from_file_location("fresh_seeds", script)
    assert spec is not None and spec.loader is not None
    fresh = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fresh)
    paths = []
    for name, within, n in (("house-1-clean", 90.0, 300), ("house-2-clean", 80.0, 100)):
        doc = make_doc(name)
        doc["accuracy"]["ours"]["overall"] = {"n": n, "within_1m": within}
        doc["mapping"]["quality"] = {"objects": {"precision": 0.99, "recall": 0.98}}
        path = tmp_path / f"{name}.json"
        path.write_text(json.dumps(doc), encoding="utf-8")
        paths.append(path)
    summary = fresh.summarise(paths)
    assert summary["mean_within_1m"] == {"clean": 87.5}
    page = render_page([make_doc("house-a")], None, {}, "", {"fresh_seeds": summary})
    assert "## Fresh generated houses" in page
    assert "| house-1-clean | 300 | 90.0 |" in page
    assert "Mean within 1 m, weighted by requests: clean 87.5 %." in page
