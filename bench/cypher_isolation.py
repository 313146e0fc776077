"""User Cypher in the worker process against in-process Cypher: the cost per statement,
how long a time limit takes to answer, and how long a crash takes to recover from.

Measured on a map built from a generated house (``tests/e2e/oracle_maps``), read-only:
- per-statement latency (p50 / p99) of a small statement, in-process and in the worker;
- the first statement's cost (starting the worker);
- wall time until a statement that outruns a limit of ``--limit`` seconds answers, in
  the worker and in-process (Kuzu's own interrupt);
- whether the real crashing statement crashed this run, how long a statement whose
  engine dies (SIGSEGV sent to the worker) takes to answer, and the next statement (a new
  worker).

Run: ``python bench/cypher_isolation.py [--limit S] [--out FILE]``; writes
``bench/results/cypher_isolation.json`` by default.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from inherit_sg.errors import CypherCrashError, QueryTimeoutError  # noqa: E402
from inherit_sg.facade import MapService  # noqa: E402
from inherit_sg.store.cypher_worker import CypherWorker  # noqa: E402
from inherit_sg.store.kuzu_graph import KuzuGraph  # noqa: E402
from inherit_sg.store.mapdir import GRAPH_FILE  # noqa: E402
from tests.e2e.oracle_maps import oracle_map  # noqa: E402

SMALL = "MATCH (o:Object) RETURN o.id, o.label ORDER BY o.id LIMIT 20"
SLOW = (
    "UNWIND range(1, 3000) AS a UNWIND range(1, 3000) AS b UNWIND range(1, 3000) AS x "
    "WITH a, b, x WHERE (a * b + x) % 7 = 3 RETURN count(*)"
)
CRASHING = "MATCH (o:Object) RETURN o.id ORDER BY o.id SKIP (20000) LIMIT 5"


def _latency(run: Any, n: int = 200) -> dict[str, float]:
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        run()
        times.append((time.perf_counter() - t0) * 1000)
    times.sort()
    return {"p50_ms": statistics.median(times), "p99_ms": times[int(0.99 * (len(times) - 1))]}


def _until_answer(run: Any) -> float:
    t0 = time.perf_counter()
    with contextlib.suppress(QueryTimeoutError, CypherCrashError):
        run()
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--limit", type=float, default=10.0, help="time limit of the slow statement")
    ap.add_argument(
        "--out", type=Path, default=ROOT / "bench" / "results" / "cypher_isolation.json"
    )
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        map_dir = oracle_map(Path(tmp), "house", 3)
        graph = KuzuGraph(map_dir / GRAPH_FILE, read_only=True)
        in_process = _latency(lambda: graph.query(SMALL, read_only=True))
        limit_in_process = _until_answer(
            lambda: graph.query(SLOW, read_only=True, timeout_s=args.limit)
        )
        graph.close()
        worker = CypherWorker(map_dir / GRAPH_FILE)
        t0 = time.perf_counter()
        worker.run(SMALL)
        first = time.perf_counter() - t0
        in_worker = _latency(lambda: worker.run(SMALL))
        limit_worker = _until_answer(lambda: worker.run(SLOW, timeout_s=args.limit))
        worker.close()
        with MapService.open(map_dir) as service:
            service.cypher(SMALL)
            # the real statement crashes Kuzu on some runs; a SIGSEGV sent to the worker
            # in the middle of a statement makes the crash certain
            crashed = False
            try:
                service.cypher(CRASHING)
            except CypherCrashError:
                crashed = True
            service.cypher(SMALL)
            worker_now = service._cypher_worker
            assert worker_now is not None and worker_now.pid is not None
            timer = threading.Timer(0.5, os.kill, (worker_now.pid, signal.SIGSEGV))
            timer.start()
            crash = _until_answer(lambda: service.cypher(SLOW, timeout_s=60)) - 0.5
            t0 = time.perf_counter()
            service.cypher(SMALL)
            after_crash = time.perf_counter() - t0
    out = {
        "statement_latency": {"in_process": in_process, "worker": in_worker},
        "worker_start_s": round(first, 3),
        "time_limit_s": args.limit,
        "answered_after_limit_s": {
            "worker": round(limit_worker, 2),
            "in_process": round(limit_in_process, 2),
        },
        "crash": {
            "real_statement_crashed": crashed,
            "answered_after_crash_s": round(crash, 3),
            "next_statement_s": round(after_crash, 3),
        },
    }
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    print(json.dumps(out, indent=1))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
