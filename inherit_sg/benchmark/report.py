"""The benchmark report (``docs/benchmarks.md``): markdown tables over the results of
several ``inherit-sg bench`` runs, plus the latency-by-map-size rows of
``bench/results/retrieval.json``. Pure functions of the JSON documents."""

from __future__ import annotations

from typing import Any

from inherit_sg.benchmark.tables import num, pct, ratio_pct, size, table

GROUPS = ("A-C", "D", "E", "F")
SYSTEMS = {"ours": "INHerit-SG", "flat": "flat baseline"}


def dataset_name(doc: dict[str, Any]) -> str:
    """The name a results document is shown under (its label, else the dataset's)."""
    return str(doc.get("label") or doc.get("dataset_name") or doc.get("dataset", "?"))


def accuracy_section(docs: list[dict[str, Any]]) -> str:
    """Table II layout: within 1 m / 0.5 m per group, overall and the group average."""
    header = ["dataset", "system"]
    header += [f"{g} {t}" for g in GROUPS for t in ("1m", "0.5m")]
    header += ["overall 1m", "overall 0.5m", "average 1m", "average 0.5m", "requests"]
    rows = []
    for doc in docs:
        for system, s in doc["accuracy"].items():
            cells = [pct(s[g][m]) for g in GROUPS for m in ("within_1m", "within_0.5m")]
            cells += [pct(s["overall"]["within_1m"]), pct(s["overall"]["within_0.5m"])]
            cells += [pct(s["group_mean"]["within_1m"]), pct(s["group_mean"]["within_0.5m"])]
            rows.append(
                [dataset_name(doc), SYSTEMS.get(system, system), *cells, str(s["overall"]["n"])]
            )
    return table(header, rows)


def semantic_section(docs: list[dict[str, Any]]) -> str:
    """Semantic accuracy (right object by ground truth) per group."""
    header = ["dataset", "system", *GROUPS, "overall", "average"]
    rows = [
        [
            dataset_name(doc),
            SYSTEMS.get(system, system),
            *(pct(s[g]["semantic"]) for g in GROUPS),
            pct(s["overall"]["semantic"]),
            pct(s["group_mean"]["semantic"]),
        ]
        for doc in docs
        for system, s in doc["accuracy"].items()
    ]
    return table(header, rows)


def ablation_section(docs: list[dict[str, Any]]) -> str:
    """Accuracy within 1 m per group and mean latency per request of each variant."""
    header = ["dataset", "variant", *GROUPS, "overall", "semantic", "mean latency (ms)"]
    rows = []
    for doc in docs:
        ablations = doc.get("ablations", {})
        if "skipped" in ablations:
            rows.append([dataset_name(doc), f"skipped ({ablations['skipped']})", *[""] * 7])
            continue
        for name, res in ablations.items():
            if "skipped" in res:
                rows.append([dataset_name(doc), f"{name}: skipped ({res['skipped']})", *[""] * 7])
                continue
            s = res["accuracy"]
            rows.append(
                [
                    dataset_name(doc),
                    name,
                    *(pct(s[g]["within_1m"]) for g in GROUPS),
                    pct(s["overall"]["within_1m"]),
                    pct(s["overall"]["semantic"]),
                    num(res["mean_latency_ms"]),
                ]
            )
    return table(header, rows)


def mapping_section(docs: list[dict[str, Any]]) -> str:
    """Speed, memory and quality of each map."""
    header = [
        "dataset",
        "frames",
        "keyframes",
        "build (s)",
        "frames/s",
        "geometry fps",
        "semantic kf/s",
        "peak RSS (MB)",
        "object P",
        "object R",
        "room P",
        "room R",
    ]
    rows = []
    for doc in docs:
        m = doc["mapping"]
        obj, room = m["quality"]["objects"], m["quality"]["rooms"]
        rows.append(
            [
                dataset_name(doc),
                str(m["frames"]),
                str(m["keyframes"]),
                num(m["build_s"]),
                num(m["frames_per_s"]),
                num(m["geometry_fps"]),
                num(m["semantic_keyframes_per_s"]),
                num(m["peak_rss_mb"], 0),
                ratio_pct(obj["precision"]),
                ratio_pct(obj["recall"]),
                ratio_pct(room["precision"]),
                ratio_pct(room["recall"]),
            ]
        )
    return table(header, rows)


def storage_section(docs: list[dict[str, Any]]) -> str:
    """Table III layout: per-object storage and the map size with / without images."""
    header = [
        "dataset",
        "objects",
        "feat.",
        "img",
        "txt",
        "node",
        "room node",
        "area node",
        "map (with / without images)",
    ]
    rows = []
    for doc in docs:
        st = doc["storage"]
        obj, mp = st["object"], st["map"]
        rows.append(
            [
                dataset_name(doc),
                str(obj["nodes"]),
                size(obj["feature_bytes"]),
                size(obj["image_bytes"]),
                size(obj["text_bytes"]),
                size(obj["node_bytes"]),
                size(st["room"]["node_bytes"]),
                size(st["area"]["node_bytes"]),
                f"{size(mp['total_bytes'])} / {size(mp['without_images_bytes'])}",
            ]
        )
    return table(header, rows)


def latency_section(docs: list[dict[str, Any]]) -> str:
    """p50 / p99 per stage of ours and the flat baseline."""
    stages = ("parse", "retrieve", "verify", "total")
    header = ["dataset", "system", *(f"{s} p50 / p99" for s in stages)]
    rows = []
    for doc in docs:
        for system, lat in doc["latency_ms"].items():
            cells = [
                f"{num(lat[s]['p50'])} / {num(lat[s]['p99'])}" if s in lat else "n/a"
                for s in stages
            ]
            rows.append([dataset_name(doc), SYSTEMS.get(system, system), *cells])
    return table(header, rows)


def scale_section(rows: list[dict[str, Any]]) -> str:
    """Latency by map size (``bench/results/retrieval.json``, verification off)."""
    header = ["objects", "houses", "requests", "pass", "parse p50", "retrieve p50 / p99"]
    header += ["total p50 / p99"]
    out = []
    for row in rows:
        for name in ("first pass", "repeat pass"):
            p = row.get(name)
            if not p:
                continue
            out.append(
                [
                    str(row["objects"]),
                    str(row.get("houses", "")),
                    str(row.get("requests", "")),
                    name,
                    num(p["parse"]["p50"], 2),
                    f"{num(p['retrieve']['p50'])} / {num(p['retrieve']['p99'])}",
                    f"{num(p['total']['p50'])} / {num(p['total']['p99'])}",
                ]
            )
    return table(header, out)
