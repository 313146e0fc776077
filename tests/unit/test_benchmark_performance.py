"""The performance section of the benchmark page renders what the benchmarks wrote."""

from __future__ import annotations

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
