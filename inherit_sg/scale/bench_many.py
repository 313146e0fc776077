"""``inherit-sg bench --ray``: one Ray task per dataset, the benchmarks in parallel.

Each task runs :func:`inherit_sg.benchmark.runner.run_benchmark` (the code path of
``inherit-sg bench`` on one dataset), so every dataset's results JSON has the same shape
as a sequential run; it is written to a temporary name and renamed when complete. A task
that fails is retried once, then reported; the other datasets go on. Mapping speed
figures of datasets that ran side by side share the machine's cores: compare them with
runs made the same way.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.runner import BenchOptions, run_benchmark
from inherit_sg.json_values import jsonable
from inherit_sg.scale.cluster import as_completed, error_text, ray_session

DEFAULT_RETRIES = 1


@dataclass(frozen=True)
class BenchJob:
    """One dataset to benchmark and where its results JSON goes."""

    options: BenchOptions
    out: Path


def run_bench_job(job: BenchJob) -> dict[str, Any]:
    """Benchmark one dataset and write its JSON (complete or not at all); its record."""
    started = time.perf_counter()
    doc = run_benchmark(job.options, lambda _line: None)
    job.out.parent.mkdir(parents=True, exist_ok=True)
    partial = job.out.with_name(f".{job.out.name}.{os.getpid()}.partial")
    partial.write_text(json.dumps(jsonable(doc), indent=1) + "\n", encoding="utf-8")
    partial.replace(job.out)
    ours = doc["accuracy"]["ours"]["overall"]
    return {
        "dataset": str(job.options.dataset),
        "out": str(job.out),
        "status": "done",
        "requests": ours["n"],
        "within_1m": ours["within_1m"],
        "seconds": round(time.perf_counter() - started, 2),
    }


def bench_many(
    jobs: Sequence[BenchJob],
    *,
    address: str | None = None,
    max_retries: int = DEFAULT_RETRIES,
    on_start: Callable[[int], None] | None = None,
    on_done: Callable[[dict[str, Any]], None] | None = None,
) -> dict[str, Any]:
    """Run every job on Ray (``address``, else a local cluster sized to this machine);
    the report: one record per dataset in the given order, counts and wall time."""
    started = time.perf_counter()
    with ray_session(address) as cluster:
        import ray

        task = ray.remote(num_cpus=1, max_retries=max_retries, retry_exceptions=True)(run_bench_job)
        refs = [task.remote(job) for job in jobs]
        if on_start is not None:
            on_start(len(refs))
        records: dict[int, dict[str, Any]] = {}
        for i, record, error in as_completed(refs):
            if error is not None:  # retries exhausted: report, go on
                record = {
                    "dataset": str(jobs[i].options.dataset),
                    "out": str(jobs[i].out),
                    "status": "failed",
                    "error": error_text(error),
                }
            records[i] = record
            if on_done is not None:
                on_done(record)
    results = [records[i] for i in range(len(jobs))]
    failed = sum(1 for r in results if r["status"] != "done")
    return {
        "ray": cluster,
        "datasets": results,
        "done": len(results) - failed,
        "failed": failed,
        "seconds": round(time.perf_counter() - started, 2),
    }
