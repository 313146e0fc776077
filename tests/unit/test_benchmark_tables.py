"""Formatting helpers and latency statistics of the benchmark report."""

from __future__ import annotations

import math

from inherit_sg.benchmark.latency import mean_total_ms, stage_latency
from inherit_sg.benchmark.metrics.retrieval import Outcome
from inherit_sg.benchmark.tables import num, pct, ratio_pct, size, table


def test_numbers_and_sizes_format_like_the_paper_tables() -> None:
    assert num(3.14159) == "3.1" and num(2, 0) == "2" and num("n/a") == "n/a"
    assert num(None) == "n/a" and num(math.nan) == "n/a" and pct(50.0) == "50.0"
    assert ratio_pct(0.9657) == "96.6" and ratio_pct(None) == "n/a"
    assert size(155.8) == "156 B"
    assert size(21.1 * 1024) == "21.1 KB"
    assert size(34.0 * 1024**2) == "34.0 MB"
    assert size(18.47 * 1024**3) == "18.47 GB"


def test_table_is_github_markdown() -> None:
    text = table(["a", "b"], [["1", "2"], ["3", "4"]])
    assert text.splitlines() == ["| a | b |", "|---|---|", "| 1 | 2 |", "| 3 | 4 |"]


def _outcome(i: int, timings: dict[str, float]) -> Outcome:
    return Outcome(f"q{i}", "A", "the chair", "obj:o1", 0.2, True, timings)


def test_stage_latency_percentiles_and_mean() -> None:
    outs = [
        _outcome(i, {"parse": 1.0, "retrieve": float(i), "verify": 0.0, "total": 1.0 + i})
        for i in range(1, 101)
    ]
    lat = stage_latency(outs)
    assert set(lat) == {"parse", "retrieve", "verify", "total"}
    assert lat["parse"] == {"p50": 1.0, "p99": 1.0, "mean": 1.0}
    assert lat["retrieve"]["p50"] == 50.5 and math.isclose(lat["retrieve"]["p99"], 99.01)
    assert lat["total"]["mean"] == 51.5
    assert mean_total_ms(outs) == 51.5


def test_stage_latency_skips_untimed_stages_and_empty_input() -> None:
    lat = stage_latency([_outcome(1, {"total": 4.0})])
    assert list(lat) == ["total"]
    assert stage_latency([]) == {}
    assert math.isnan(mean_total_ms([]))


def test_probe_sets_render_a_row_per_set() -> None:
    from inherit_sg.benchmark.page import render_page

    doc = {
        "reverie_style": {"requests": 200, "targets_agree": 0.96, "negations_expected": 16,
                          "negation_recall": 1.0, "negations_invented": 0, "crashes": 0},
        "speaker_relative": {"requests": 200, "targets_agree": 1.0, "negations_expected": 0,
                             "negation_recall": None, "negations_invented": 0, "crashes": 2},
    }  # fmt: skip
    page = render_page([], None, {}, request_sets={"probe": doc})
    assert "| reverie_style | 200 | 96.0 | 100.0 of 16 | 0 | 0 |" in page
    assert "| speaker_relative | 200 | 100.0 | – | – | 2 |" in page
