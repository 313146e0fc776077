"""``map build-many``: one Ray task per map, maps in parallel, sessions in order.

Each task calls :func:`inherit_sg.scale.atomic.build_job`, which runs the project's own
:func:`~inherit_sg.facade.build_map` (the code path of ``map build``) into a temporary
sibling folder and renames it into place only when all its sessions finished. A task
that raises or whose worker dies is retried (``max_retries``); a task that still fails
is reported, and its temporary folder removed, so no half map is left under the root.
A bad dataset (an :class:`~inherit_sg.errors.InputError`) is reported at once: retrying
cannot fix it.
"""

from __future__ import annotations

import os
import time
import uuid
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from inherit_sg.config import Config, load_config
from inherit_sg.errors import InputError
from inherit_sg.scale.atomic import FAULT_VARIABLE, build_job, clean_up
from inherit_sg.scale.cluster import as_completed, error_text, ray_session
from inherit_sg.scale.manifest import MapJob

DEFAULT_RETRIES = 2


def run_job(
    job: MapJob, root: str, run_id: str, config: Config | None, fault: str | None
) -> dict[str, Any]:
    """The body of one Ray task: build ``job``; a bad input becomes a failed record
    (not retried), every other error propagates so that Ray retries the task."""
    if fault:
        os.environ[FAULT_VARIABLE] = fault
    try:
        return build_job(job, root, run_id, config)
    except InputError as exc:
        return failed_record(job, root, f"{type(exc).__name__}: {exc.message}")


def failed_record(job: MapJob, root: str | Path, error: str) -> dict[str, Any]:
    """The summary row of a map that was not built."""
    return {"map": job.name, "path": str(Path(root) / job.name), "status": "failed", "error": error}


def build_many(
    jobs: Sequence[MapJob],
    root: str | Path,
    *,
    address: str | None = None,
    config: Config | None = None,
    max_retries: int = DEFAULT_RETRIES,
    cpus_per_map: float = 1.0,
    num_cpus: int | None = None,
    on_start: Callable[[int], None] | None = None,
    on_done: Callable[[dict[str, Any]], None] | None = None,
) -> dict[str, Any]:
    """Build every job under ``root`` on Ray (``address``, else a local cluster with
    ``num_cpus``), every map with ``config`` (default: this process's configuration, so
    that workers elsewhere map as ``map build`` would here); the report: one record per map in manifest order, counts and wall
    time. ``on_start`` gets the number of tasks, ``on_done`` each record as it lands."""
    base = Path(root).absolute()
    base.mkdir(parents=True, exist_ok=True)
    run_id = uuid.uuid4().hex[:12]
    cfg = config or load_config()
    fault = os.environ.get(FAULT_VARIABLE)
    started = time.perf_counter()
    with ray_session(address, num_cpus=num_cpus) as cluster:
        import ray

        task = ray.remote(num_cpus=cpus_per_map, max_retries=max_retries, retry_exceptions=True)(
            run_job
        )
        refs = [task.remote(job, str(base), run_id, cfg, fault) for job in jobs]
        if on_start is not None:
            on_start(len(refs))
        records: dict[str, dict[str, Any]] = {}
        for i, record, error in as_completed(refs):
            job = jobs[i]
            if error is not None:  # retries exhausted: report, never raise
                record = failed_record(job, base, error_text(error))
            if record["status"] != "built":
                clean_up(base, job.name, run_id)
            records[job.name] = record
            if on_done is not None:
                on_done(record)
    for job in jobs:  # nothing half-written stays
        clean_up(base, job.name, run_id)
    maps = [records[job.name] for job in jobs]
    built = sum(1 for r in maps if r["status"] == "built")
    return {
        "root": str(base),
        "run_id": run_id,
        "ray": cluster,
        "maps": maps,
        "built": built,
        "failed": len(maps) - built,
        "seconds": round(time.perf_counter() - started, 2),
    }
