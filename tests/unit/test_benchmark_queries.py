"""The benchmark's request set: the dataset's queries.jsonl or requests generated from
scene.json, and the category-balanced cut."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from inherit_sg.benchmark.queries import balanced_subset, load_scene, request_set
from inherit_sg.errors import DatasetError
from inherit_sg.ingest.synthetic.queries import QueryGT, generate_queries, write_queries
from tests.fixtures_scenes import small_scene


def _q(i: int, cat: str) -> QueryGT:
    return QueryGT(f"q{i}", f"request {i}", cat, ["o1"], [[0.0, 0.0, 0.0]])


def test_balanced_subset_takes_categories_round_robin_in_order() -> None:
    qs = [_q(i, "A") for i in range(10)] + [_q(10 + i, "D") for i in range(3)] + [_q(20, "F")]
    cut = balanced_subset(qs, 6)
    assert [q.id for q in cut] == ["q0", "q10", "q20", "q1", "q11", "q2"]
    assert balanced_subset(qs, None) == qs and balanced_subset(qs, 99) == qs


def test_request_set_generates_from_scene_without_queries_file(tmp_path: Path) -> None:
    scene = small_scene()
    scene.save(tmp_path)
    loaded = load_scene(tmp_path)
    reqs = request_set(tmp_path, loaded, limit=12)
    assert reqs.source == "generated" and len(reqs.queries) == 12
    assert reqs.available == len(generate_queries(loaded, loaded.seed or 0))
    assert len(Counter(q.category for q in reqs.queries)) >= 4


def test_request_set_prefers_the_dataset_file(tmp_path: Path) -> None:
    scene = small_scene()
    scene.save(tmp_path)
    write_queries(tmp_path, [_q(1, "E"), _q(2, "D")])
    reqs = request_set(tmp_path, load_scene(tmp_path))
    assert reqs.source == "dataset" and [q.id for q in reqs.queries] == ["q1", "q2"]


def test_dataset_without_ground_truth_is_refused(tmp_path: Path) -> None:
    with pytest.raises(DatasetError, match=r"scene\.json"):
        load_scene(tmp_path)
