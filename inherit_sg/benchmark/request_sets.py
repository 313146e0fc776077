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


def probe_section(doc: dict[str, Any]) -> str:
    """Parser coverage on the probe sets (``bench/probe_requests.py``): a row per set."""
    header = ["probe set", "requests", "targets agree %", "negations found", "invented", "crashes"]
    rows = []
    for name, row in doc.items():
        recall = row.get("negation_recall")
        found = f"{ratio_pct(recall)} of {row['negations_expected']}" if recall is not None else "–"
        invented = str(row["negations_invented"]) if recall is not None else "–"
        rows.append(
            [name, str(row["requests"]), ratio_pct(row["targets_agree"]), found, invented,
             str(row["crashes"])]
        )  # fmt: skip
    return table(header, rows)


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


def mp3d_rooms_section(rooms: dict[str, Any], objects: dict[str, Any] | None = None) -> str:
    """Region by region: the map room matched to each MP3D region, its label and whether
    the region's type is its label or among its two best types; then the totals, and the
    object categories held (``bench/mp3d_rooms.py``, ``bench/mp3d_objects.py``)."""
    header = ["region", "type", "seen m²", "matched map room", "label", "type is label / top 2"]
    rows = []
    for reg in rooms.get("regions", []):
        ok = "yes" if reg.get("label_exact") else ("top 2" if reg.get("label_top2") else "no")
        rows.append(
            [
                str(reg.get("region", "")),
                str(reg.get("type", "")),
                f"{num(reg.get('mapped_m2'), 1)} / {num(reg.get('area_m2'), 1)}",
                str(reg.get("matched") or "—"),
                str(reg.get("label") or "—"),
                ok if reg.get("matched") else "—",
            ]
        )
    t = rooms.get("totals", {})
    lines = [
        table(header, rows),
        f"Rooms: {t.get('matched', '?')} matched of {t.get('map_rooms', '?')} map rooms and "
        f"{t.get('regions', '?')} regions: precision {num(t.get('precision'), 2)}, recall "
        f"{num(t.get('recall'), 2)}; region type is the label for {t.get('label_exact', '?')}"
        f" and among the two best types for {t.get('label_top2', '?')} of "
        f"{t.get('regions', '?')}.",
    ]
    if objects:
        lines.append(
            f"Objects: {objects.get('categories_found', '?')} of "
            f"{objects.get('categories_seen', '?')} categories in view are in the map; "
            f"{objects.get('objects_held', '?')} of {objects.get('objects_seen', '?')} objects "
            f"in view have a map object of their category within 1 m "
            f"({objects.get('objects_found', '?')} within 0.5 m)."
        )
    return "\n\n".join(lines)


def fresh_seeds_section(doc: dict[str, Any]) -> str:
    """Retrieval per fresh generated house (``bench/fresh_seeds.py``) and the mean per
    noise level."""
    rows = [
        [
            row["house"],
            str(row["requests"]),
            pct(row["within_1m"]),
            *(pct(row["groups"].get(g)) for g in ("A-C", "D", "E", "F")),
            ratio_pct(row["object_precision"]),
            ratio_pct(row["object_recall"]),
            str(row.get("frames") or "—"),
        ]
        for row in doc.get("houses", [])
    ]
    means = ", ".join(
        f"{noise} {pct(value)} %" for noise, value in doc.get("mean_within_1m", {}).items()
    )
    header = ["house", "requests", "within 1 m", "A-C", "D", "E", "F", "object P", "object R",
              "frames"]  # fmt: skip
    note = f"Mean within 1 m, weighted by requests: {means}." if means else ""
    return table(header, rows) + ("\n\n" + note if note else "")
