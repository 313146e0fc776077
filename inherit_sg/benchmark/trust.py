"""The trust tables of the benchmark page: the hostile suite (``bench/hostile.py``) and
user Cypher isolated in a worker process (``bench/cypher_isolation.py``)."""

from __future__ import annotations

from typing import Any

from inherit_sg.benchmark.tables import table


def hostile_section(doc: dict[str, Any]) -> str:
    """Per surface: inputs tried, clear errors, legal answers, recoveries, crashes, data
    lost."""
    rows = doc.get("summary", [])
    if not rows:
        return ""
    head = list(rows[0])
    return table(head, [[r[h] for h in head] for r in rows])


def cypher_isolation_section(doc: dict[str, Any]) -> str:
    """Statement latency in-process and in the worker, time limit and crash recovery."""
    lat = doc.get("statement_latency", {})
    crash = doc.get("crash", {})
    late = doc.get("answered_after_limit_s", {})

    def ms(where: str, key: str) -> str:
        value = lat.get(where, {}).get(key)
        return "–" if value is None else f"{value:.2f} ms"

    rows = [
        [
            "small statement p50 / p99, in-process",
            f"{ms('in_process', 'p50_ms')} / {ms('in_process', 'p99_ms')}",
        ],
        [
            "small statement p50 / p99, worker",
            f"{ms('worker', 'p50_ms')} / {ms('worker', 'p99_ms')}",
        ],
        ["worker start", f"{doc.get('worker_start_s', '–')} s"],
        [
            f"a {doc.get('time_limit_s', '?')} s limit answers after (worker)",
            f"{late.get('worker', '–')} s",
        ],
        ["a crashed statement answers after", f"{crash.get('answered_after_crash_s', '–')} s"],
        ["the next statement (fresh worker)", f"{crash.get('next_statement_s', '–')} s"],
    ]
    return table(["figure", "value"], rows)
