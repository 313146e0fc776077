"""Benchmark page sections for the request sets measured outside ``inherit-sg bench``:
the parser on the development set (``bench/parse.py``, ``bench/results/parse.json``)
and human-written requests on the real Matterport3D house (``bench/mp3d_requests.py``,
``bench/results/mp3d_requests.json``). Each section is a table with a row per set."""

from __future__ import annotations

from typing import Any

from inherit_sg.benchmark.tables import num, pct, ratio_pct, table


def parse_section(doc: dict[str, Any]) -> str:
    """Parser accuracy on the development set and parse latency."""
    parts: list[str] = []
    acc = doc.get("accuracy")
    if acc:
        header = ["set", "requests", "targets right", "negations found", "invented", "crashes"]
        row = [
            "development set (tests/data/dev_requests)",
            str(acc["requests"]),
            ratio_pct(acc["target_accuracy"]),
            f"{ratio_pct(acc['negation_recall'])} of {acc['negations_expected']}",
            str(acc["negations_invented"]),
            str(acc["crashes"]),
        ]
        parts.append(table(header, [row]))
        kinds = acc.get("constraint_recall", {})
        if kinds:
            rows = [
                [k, f"{v['found']} / {v['annotated']}", pct(100.0 * v["found"] / v["annotated"])]
                for k, v in kinds.items()
                if v["annotated"]
            ]
            parts.append(table(["constraint kind", "found / annotated", "recall %"], rows))
    lat = doc.get("latency")
    if lat:
        header = ["requests timed", "p50 ms", "p90 ms", "p99 ms", "max ms", "first parse ms"]
        row = [
            f"{lat['requests']} × {lat['parses'] // max(1, lat['requests'])}",
            num(lat["p50_ms"], 2),
            num(lat["p90_ms"], 2),
            num(lat["p99_ms"], 2),
            num(lat["max_ms"], 2),
            num(lat.get("first_parse_ms"), 0),
        ]
        parts.append(table(header, [row]))
    return "\n\n".join(parts)


def requests_section(doc: dict[str, Any]) -> str:
    """Accuracy per request form on the MP3D house (a row per form and overall)."""
    totals = doc.get("totals", {})
    header = ["form", "requests", "within 1 m", "within 0.5 m", "semantic"]
    rows = [
        [form, str(v["n"]), pct(v["within_1m"]), pct(v["within_0.5m"]), pct(v["semantic"])]
        for form, v in totals.items()
    ]
    lat = doc.get("latency_ms", {}).get("total", {})
    note = (
        f"Verification {'on' if doc.get('verify') else 'off'}; query latency p50 "
        f"{num(lat.get('p50'))} ms, p99 {num(lat.get('p99'))} ms (first pass)."
    )
    return table(header, rows) + "\n\n" + note
