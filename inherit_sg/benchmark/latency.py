"""Query latency per stage (parse / retrieve / verify / total) from judged outcomes."""

from __future__ import annotations

import statistics

from inherit_sg.benchmark.metrics.retrieval import Outcome, percentile

STAGES = ("parse", "retrieve", "verify", "total")


def stage_latency(outcomes: list[Outcome]) -> dict[str, dict[str, float]]:
    """p50 / p99 / mean (ms) of each stage in :data:`STAGES` that the outcomes timed."""
    out: dict[str, dict[str, float]] = {}
    for stage in STAGES:
        values = sorted(o.timings_ms[stage] for o in outcomes if stage in o.timings_ms)
        if not values:
            continue
        out[stage] = {
            "p50": percentile(values, 50),
            "p99": percentile(values, 99),
            "mean": statistics.fmean(values),
        }
    return out


def mean_total_ms(outcomes: list[Outcome]) -> float:
    """Mean whole-request latency (ms); NaN without timed outcomes."""
    values = [o.timings_ms["total"] for o in outcomes if "total" in o.timings_ms]
    return statistics.fmean(values) if values else float("nan")
