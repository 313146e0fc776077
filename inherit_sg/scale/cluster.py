"""Connecting to Ray: a running cluster by address, or a local one sized to this machine."""

from __future__ import annotations

import os
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from inherit_sg.scale import require_ray

# The local cluster's shared-memory object store: the tasks pass only small records, so
# a small store keeps Ray's footprint low on a shared machine.
LOCAL_OBJECT_STORE_MB = 256


def local_cpus() -> int:
    """CPUs a local cluster offers: the cores this process may run on."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not Linux
        return max(1, os.cpu_count() or 1)


@contextmanager
def ray_session(
    address: str | None = None,
    *,
    num_cpus: int | None = None,
    object_store_mb: int = LOCAL_OBJECT_STORE_MB,
) -> Iterator[dict[str, Any]]:
    """Ray for the duration of the block: the cluster at ``address`` (``auto`` or
    ``ray://host:10001`` or ``host:6379``), else a local cluster with ``num_cpus`` CPUs
    (default: this machine's) and a small object store, no dashboard. A Ray already
    initialised in this process (a test fixture, a notebook) is used as it is and left
    running. Yields what the cluster offers (``address``, ``cpus``)."""
    ray = require_ray()
    owned = not ray.is_initialized()
    if owned:
        if address:
            ray.init(address=address, log_to_driver=False)
        else:
            ray.init(
                num_cpus=num_cpus or local_cpus(),
                object_store_memory=object_store_mb * 1024 * 1024,
                include_dashboard=False,
                log_to_driver=False,
            )
    try:
        cpus = int(ray.cluster_resources().get("CPU", 0))
        yield {"address": address or "local", "cpus": cpus}
    finally:
        if owned:
            ray.shutdown()


def as_completed(refs: Sequence[Any]) -> Iterator[tuple[int, Any, BaseException | None]]:
    """``(index, result, None)`` or ``(index, None, error)`` for each Ray object ref, in
    the order the tasks finish (an error: the task failed after its retries)."""
    import ray

    index = {ref: i for i, ref in enumerate(refs)}
    pending = list(refs)
    while pending:
        done, pending = ray.wait(pending, num_returns=1)
        for ref in done:
            try:
                result = ray.get(ref)
            except Exception as exc:  # the caller reports it; the other tasks go on
                yield index[ref], None, exc
            else:
                yield index[ref], result, None


def error_text(exc: BaseException) -> str:
    """A one-line reason from a Ray error (the task's own exception where it has one)."""
    cause = getattr(exc, "cause", None)
    err = cause if isinstance(cause, BaseException) else exc
    first = (str(err).strip().splitlines() or [""])[0]
    if type(err).__name__ == "WorkerCrashedError" or "worker died" in first.lower():
        first = "the worker process died (killed or out of memory) on every attempt"
    return f"{type(err).__name__}: {first}"[:300]
