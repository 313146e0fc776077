"""Benchmark measures on a real map: the small two-floor scene written as an oracle map
(real embedder, Kuzu and LanceDB), with one keyframe and one recorded session."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.benchmark.ablations import ABLATIONS, FULL, run_ablations, with_change
from inherit_sg.benchmark.accuracy import accuracy_table, compare
from inherit_sg.benchmark.mapping_metrics import from_sessions, quality, room_scores
from inherit_sg.benchmark.metrics.mapping import RoomMatching
from inherit_sg.benchmark.storage import storage_breakdown
from inherit_sg.config import Config
from inherit_sg.embed import get_text_embedder
from inherit_sg.errors import ConfigError
from inherit_sg.exchange.scene_truth import scene_to_graph
from inherit_sg.ingest.synthetic.queries import generate_queries
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.mapping.node_text import embed_nodes
from inherit_sg.model import Keyframe, Pose, Session
from inherit_sg.store import MapStore
from tests.fixtures_scenes import small_scene


@pytest.fixture(scope="module")
def oracle(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Scene]:
    scene = small_scene()
    root = tmp_path_factory.mktemp("bench-oracle")
    scene.save(root)
    graph = scene_to_graph(scene)
    embed_nodes(graph, get_text_embedder())
    first = next(iter(graph.objects()))
    image = np.full((48, 64, 3), 120, dtype=np.uint8)
    jpeg = cv2.imencode(".jpg", image)[1].tobytes()
    feature = np.full(256, 1.0 / 16.0, dtype=np.float32)
    kf = Keyframe(
        "kf:1", "session:1", 1.0, Pose.identity(), None, 0, feature, jpeg, width=64, height=48
    )
    graph.add_or_update(replace(first, keyframe_ids=["kf:1"], best_keyframe="kf:1"))
    with MapStore.create(root / "map") as store:
        store.upsert_session(Session("session:1", "s1", 100.0, 110.0, "here", 50, 1))
        store.add_keyframes([kf])
        store.write_changes(graph)
    return root, scene


def test_storage_counts_vectors_strings_and_jpegs(oracle: tuple[Path, Scene]) -> None:
    root, scene = oracle
    with MapStore.open(root / "map") as store:
        st = storage_breakdown(store)
        text_dim, n_obj = store.info.text_dim, len(scene.objects)
        jpeg = len(store.get_keyframe("kf:1", with_image=True).jpeg or b"")
    obj = st["object"]
    assert obj["nodes"] == n_obj and st["room"]["nodes"] == len(scene.rooms)
    # every object has a 384-d float32 text embedding plus its label / description
    assert obj["text_bytes"] > text_dim * 4 and obj["text_string_bytes"] > 3
    assert math.isclose(obj["text_bytes"] - obj["text_string_bytes"], text_dim * 4)
    assert obj["node_bytes"] == obj["feature_bytes"] + obj["text_bytes"]
    assert st["map"]["keyframes"] == 1 and st["map"]["jpeg_bytes"] == jpeg > 0
    assert math.isclose(obj["image_bytes"], jpeg / n_obj)
    assert math.isclose(obj["best_view_image_bytes"], jpeg)
    assert obj["total_bytes"] == obj["node_bytes"] + obj["image_bytes"]
    m = st["map"]
    assert m["total_bytes"] == m["without_images_bytes"] + m["lance_bytes"]
    assert m["graph_bytes"] > 0 and m["lance_bytes"] >= jpeg


def test_sessions_give_build_speed_and_oracle_quality_is_perfect(
    oracle: tuple[Path, Scene],
) -> None:
    root, scene = oracle
    with MapStore.open(root / "map") as store:
        speed = from_sessions(store)
        q = quality(store, root, scene)
    assert speed["frames"] == 50 and speed["build_s"] == 10.0 and speed["frames_per_s"] == 5.0
    assert speed["peak_rss_mb"] == "n/a"
    assert q["objects"]["precision"] == 1.0 and q["objects"]["recall"] == 1.0
    assert q["rooms"]["recall"] == 1.0 and q["rooms"]["precision"] == 1.0


def test_room_scores_report_the_one_to_one_matching() -> None:
    scene = small_scene()
    ids = [r.id for r in scene.rooms]
    matching = RoomMatching(
        precision=0.5,
        recall=2 / len(ids),
        recall_seen=1.0,
        predicted=4,
        true_rooms=len(ids),
        matched=2,
        pairs={"room:a": ids[0], "room:c": ids[1]},
    )
    scores = room_scores(matching)
    assert scores["matched"] == 2 and scores["predicted"] == 4
    assert scores["precision"] == 0.5 and scores["recall"] == 2 / len(ids)
    assert scores["recall_seen"] == 1.0


def test_ours_beats_flat_on_the_oracle_map_and_ablations_are_recorded(
    oracle: tuple[Path, Scene],
) -> None:
    root, scene = oracle
    queries = generate_queries(scene, 3, n=12)
    with MapStore.open(root / "map") as store:
        from inherit_sg.retrieval.engine import QueryEngine

        outcomes = compare(QueryEngine(store), queries, scene)
        ablations = run_ablations(store, Config(), queries[:4], scene)
    table = accuracy_table(outcomes)
    assert set(table) == {"ours", "flat"}
    for summary in table.values():
        assert summary["overall"]["n"] == len(queries)
        assert 0.0 <= summary["overall"]["within_0.5m"] <= summary["overall"]["within_1m"] <= 100
    assert table["ours"]["overall"]["semantic"] > table["flat"]["overall"]["semantic"]
    assert all(o.timings_ms["total"] > 0 for o in outcomes["ours"])
    assert list(ablations) == [FULL, *(a.name for a in ABLATIONS)]
    assert ablations["LLM parser instead of rules"]["skipped"].startswith("llm.endpoint")
    off = ablations["without verification"]
    assert off["override"] == "retrieval.verify=False"
    assert off["accuracy"]["overall"]["n"] == 4 and off["mean_latency_ms"] > 0


def test_with_change_validates_the_new_value() -> None:
    cfg = with_change(Config(), ABLATIONS[0])
    assert cfg.retrieval.use_areas is False and Config().retrieval.use_areas is True
    bad = replace(ABLATIONS[-1], value="neither")
    with pytest.raises((ConfigError, ValueError)):
        with_change(Config(), bad)
