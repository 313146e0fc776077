"""The performance section of the benchmark page renders what the benchmarks wrote."""

from __future__ import annotations

from inherit_sg.benchmark.machine import machine_reference
from inherit_sg.benchmark.performance import performance_section


def _build(mb: float, seconds: float) -> dict[str, object]:
    return {
        "without_keyframes_mb": mb,
        "kuzu_mb": mb - 4,
        "build_s": seconds,
        "wall_s": seconds + 9,
        "semantic_keyframes_per_s": 12.5,
        "peak_rss_mb": 1536.0,
    }


def test_sizes_times_and_throughput_appear_with_their_goals() -> None:
    perf = {
        "builds": {"compacted": _build(44.0, 34.9), "uncompacted": _build(68.5, 33.8)},
        "spark_dsg": {
            "compacted": {"nodes": 10, "mb": 23.4},
            "uncompacted": {"nodes": 10, "mb": 37.5},
        },
        "kuzu_table_floor": {"node_table_mb": 1.09, "rel_table_mb": 2.1, "fulltext_index_mb": 7},
    }
    level = {"clients": 4, "qps": 152.1, "errors": 0, "p50_ms": 25.5, "p99_ms": 48.8}
    service = {
        "service": {
            "queries": 183,
            "seconds_per_level": 10,
            "cpus": 2,
            "idle": {"levels": [level]},
            "mapping": {"levels": [{**level, "qps": 85.0}]},
            "workers": {"2": {"levels": [{**level, "qps": 260.4}]}},
        }
    }
    page = performance_section(perf, service)
    assert "| map directory without keyframes (Kuzu files) | 44.0 MB (40.0 MB) | 68.5 MB" in page
    assert "34.9 s (43.9 s)" in page and "1.50 GB" in page and "≤ 30 s" in page
    assert "Spark-DSG apartment import (10 nodes) | 23.4 MB | 37.5 MB | ≤ 2 MB" in page
    assert "a node table 1.09 MB" in page
    assert "| 2 processes | 4 | 260 | 0 | 25.5 / 48.8 |" in page
    assert "| 1 process, mapping | 4 | 85 |" in page
    assert performance_section(None, None) == ""


def test_the_table_floor_names_what_each_table_costs_and_why() -> None:
    floor = {
        "node_table_mb": 1.1,
        "node_table_1000_rows_mb": 3.13,
        "rel_table_mb": 2.1,
        "rel_table_forward_only_mb": 0.006,
        "fulltext_index_mb": 6.2,
    }
    ref = {"python_loop_s": 0.465, "matmul_s": 0.0277}
    text = performance_section({"kuzu_table_floor": floor, "machine_reference": ref}, None)
    assert "during these builds" in text
    assert "3 million additions 0.465 s, a 1000×1000 matrix product 0.0277 s" in text
    assert "a node table 1.1 MB with its first rows" in text and "3.13 MB at 1,000 rows" in text
    assert "a rel table 2.1 MB once it links two nodes (0.006 MB stored one way only" in text
    assert "a full-text index 6.2 MB" in text and "≤ 8 MB goal cannot be met" in text


def test_the_machine_reference_times_both_workloads() -> None:
    ref = machine_reference()
    assert set(ref) == {"python_loop_s", "matmul_s"}
    assert 0 < ref["python_loop_s"] < 60 and 0 < ref["matmul_s"] < 60
