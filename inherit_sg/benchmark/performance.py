"""The performance section of the benchmark page: map size, build time, memory
(``bench/results/performance.json``) and REST throughput (``bench/results/service.json``),
each next to its goal."""

from __future__ import annotations

from typing import Any

from inherit_sg.benchmark.tables import table

# goals of the performance work, the anchor each figure is compared with
GOALS = {
    "map": "≤ 8 MB without keyframes",
    "dsg": "≤ 2 MB",
    "build": "≤ 30 s",
    "rss": "≤ 1.0 GB",
    "qps": "≥ 300 q/s, 0 errors",
    "qps_mapping": "≥ 150 q/s",
}


def _mb(value: float | None) -> str:
    return "–" if value is None else f"{value:.1f} MB"


def build_rows(perf: dict[str, Any]) -> list[list[str]]:
    """Rows of map size, build time and memory, as built and without compaction."""
    builds = perf.get("builds", {})
    done, raw = builds.get("compacted", {}), builds.get("uncompacted", {})
    rows = [
        [
            "map directory without keyframes (Kuzu files)",
            f"{_mb(done.get('without_keyframes_mb'))} ({_mb(done.get('kuzu_mb'))})",
            f"{_mb(raw.get('without_keyframes_mb'))} ({_mb(raw.get('kuzu_mb'))})",
            GOALS["map"],
        ],
        [
            "whole build (its own clock; wall with model loading)",
            f"{done.get('build_s', '–')} s ({done.get('wall_s', '–')} s)",
            f"{raw.get('build_s', '–')} s ({raw.get('wall_s', '–')} s)",
            GOALS["build"],
        ],
        [
            "semantic stream",
            f"{done.get('semantic_keyframes_per_s', '–')} keyframes/s",
            f"{raw.get('semantic_keyframes_per_s', '–')} keyframes/s",
            "–",
        ],
        [
            "peak resident memory",
            f"{done.get('peak_rss_mb', 0) / 1024:.2f} GB",
            f"{raw.get('peak_rss_mb', 0) / 1024:.2f} GB",
            GOALS["rss"],
        ],
    ]
    dsg = perf.get("spark_dsg") or {}
    if dsg:
        rows.append(
            [
                f"Spark-DSG apartment import ({dsg['compacted']['nodes']} nodes)",
                _mb(dsg["compacted"]["mb"]),
                _mb(dsg["uncompacted"]["mb"]),
                GOALS["dsg"],
            ]
        )
    return rows


def service_rows(service: dict[str, Any]) -> list[list[str]]:
    """Queries/s and latency per server-process count and client count."""
    rows: list[list[str]] = []
    phases = [
        ("1 process", service.get("idle", {})),
        ("1 process, mapping", service.get("mapping", {})),
    ]
    phases += [(f"{n} processes", d) for n, d in service.get("workers", {}).items()]
    for name, data in phases:
        for r in data.get("levels", []):
            rows.append(
                [
                    name,
                    str(r["clients"]),
                    f"{r['qps']:.0f}",
                    str(r["errors"]),
                    f"{r['p50_ms']} / {r['p99_ms']}",
                ]
            )
    return rows


def _speed_sentence(what: str, ref: dict[str, Any]) -> str:
    """The machine-speed reference of a run (:mod:`inherit_sg.benchmark.machine`)."""
    return (
        f"Machine speed during {what} (to compare runs made on different days): a "
        f"pure-Python loop of 3 million additions {ref.get('python_loop_s')} s, a "
        f"1000×1000 matrix product {ref.get('matmul_s')} s."
    )


def floor_sentence(floor: dict[str, Any]) -> str:
    """What one table costs in plain Kuzu, and what that means for a map."""
    text = (
        "What a table costs in plain Kuzu 0.11.3 (after a checkpoint): a node table "
        f"{floor.get('node_table_mb')} MB with its first rows (its primary-key hash index)"
    )
    if "node_table_1000_rows_mb" in floor:
        text += f", {floor['node_table_1000_rows_mb']} MB at 1,000 rows"
    text += f"; a rel table {floor.get('rel_table_mb')} MB once it links two nodes"
    if "rel_table_forward_only_mb" in floor:
        text += (
            f" ({floor['rel_table_forward_only_mb']} MB stored one way only, which makes "
            "Kuzu refuse undirected patterns and DETACH DELETE, both part of the public "
            "Cypher contract)"
        )
    return text + (
        f"; a full-text index {floor.get('fulltext_index_mb')} MB. A map has 13 node and 7 "
        "rel tables in graph.kuzu, and 6 node tables and the text index in index.kuzu: "
        "these floors, not the data (2.6 KB per object), make up nearly all of its Kuzu "
        "files, and the ≤ 8 MB goal cannot be met with this schema on Kuzu."
    )


def performance_section(perf: dict[str, Any] | None, service: dict[str, Any] | None) -> str:
    """Markdown of both tables and the per-table floor of Kuzu."""
    parts: list[str] = []
    if perf:
        parts.append(
            table(
                ["figure", "as built (compacted)", "without compaction", "goal"], build_rows(perf)
            )
        )
        if perf.get("machine_reference"):
            parts.append(_speed_sentence("these builds", perf["machine_reference"]))
        floor = perf.get("kuzu_table_floor") or {}
        if floor:
            parts.append(floor_sentence(floor))
    svc = (service or {}).get("service", service or {})
    rows = service_rows(svc) if svc else []
    if rows:
        parts.append(
            f"REST on loopback, {svc.get('queries', '?')} requests of a generated house, "
            f"verification off, {svc.get('seconds_per_level', '?')} s per level on "
            f"{svc.get('cpus', '?')} cores (goal {GOALS['qps']}; while mapping "
            f"{GOALS['qps_mapping']}):"
        )
        parts.append(table(["server", "clients", "q/s", "errors", "p50 / p99 ms"], rows))
        if svc.get("machine_reference"):
            parts.append(_speed_sentence("this run", svc["machine_reference"]))
    return "\n\n".join(parts)
