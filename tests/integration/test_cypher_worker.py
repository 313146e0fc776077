"""User Cypher in a worker process: a crash or a stuck statement costs only itself, the
time limit holds from outside, and the worker is replaced for the next statement."""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time
from pathlib import Path

import pytest

from inherit_sg.errors import CypherCrashError, MapError, QueryTimeoutError, ReadOnlyViolationError
from inherit_sg.facade import MapService
from inherit_sg.store.cypher_worker import GRACE_S, CypherWorker
from inherit_sg.store.mapdir import GRAPH_FILE
from tests.e2e.oracle_maps import oracle_map

CRASHING = "MATCH (o:Object) RETURN o.id ORDER BY o.id SKIP (20000) LIMIT 5"
COUNT_FLOORS = "MATCH (f:Floor) RETURN count(f)"


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return oracle_map(tmp_path_factory.mktemp("worker"), "house", 3)


SLOW = (
    "UNWIND range(1, 3000) AS a UNWIND range(1, 3000) AS b UNWIND range(1, 3000) AS x "
    "WITH a, b, x WHERE (a * b + x) % 7 = 3 RETURN count(*)"
)


def _crash_during_a_statement(service: MapService) -> None:
    """Run a slow statement and end its worker with SIGSEGV, as a Kuzu crash would."""
    service.cypher(COUNT_FLOORS)  # a worker runs
    worker = service._cypher_worker
    assert worker is not None and worker.pid is not None
    pid = worker.pid
    timer = threading.Timer(0.5, os.kill, (pid, signal.SIGSEGV))
    timer.start()
    try:
        service.cypher(SLOW, timeout_s=60)
    finally:
        timer.cancel()


def test_a_crash_costs_only_its_statement(map_dir: Path) -> None:
    with MapService.open(map_dir) as service:
        assert service.cypher(COUNT_FLOORS).rows == [[1]]
        # the real crashing statement: a segfault on some runs, rows on others
        with contextlib.suppress(CypherCrashError):
            service.cypher(CRASHING)
        for _ in range(2):
            with pytest.raises(CypherCrashError, match="SIGSEGV"):
                _crash_during_a_statement(service)
            assert service.cypher(COUNT_FLOORS).rows == [[1]]
        # the guards of in-process Cypher hold in the worker as well
        with pytest.raises(ReadOnlyViolationError):
            service.cypher("MATCH (o:Object) SET o.label = 'x'")
        rows = service.cypher("MATCH (o:Object) RETURN o.id", max_rows=2)
        assert len(rows.rows) == 2 and rows.truncated


def test_a_stuck_statement_is_stopped_at_its_time_limit(map_dir: Path) -> None:
    worker = CypherWorker(map_dir / GRAPH_FILE)
    try:
        assert worker.run(COUNT_FLOORS).rows == [[1]]
        pid = worker.pid
        assert pid is not None
        # a child that cannot answer at all (stopped): only an outside limit ends it
        os.kill(pid, signal.SIGSTOP)
        started = time.monotonic()
        with pytest.raises(QueryTimeoutError, match="1 s"):
            worker.run(COUNT_FLOORS, timeout_s=1.0)
        waited = time.monotonic() - started
        assert waited >= 1.0 and worker.pid is None, (waited, worker.pid)
        assert worker.run(COUNT_FLOORS).rows == [[1]] and worker.pid != pid
        assert worker.crashes == 1 and GRACE_S > 0
    finally:
        worker.close()


def test_closing_ends_a_running_statement(map_dir: Path) -> None:
    worker = CypherWorker(map_dir / GRAPH_FILE)
    assert worker.run(COUNT_FLOORS).rows == [[1]]
    pid = worker.pid
    assert pid is not None
    os.kill(pid, signal.SIGSTOP)
    caught: list[BaseException] = []

    def run() -> None:
        try:
            worker.run(COUNT_FLOORS)
        except BaseException as exc:  # checked below
            caught.append(exc)

    thread = threading.Thread(target=run)
    thread.start()
    time.sleep(0.3)
    worker.close()
    thread.join(timeout=10)
    assert not thread.is_alive() and caught and isinstance(caught[0], MapError)
    with pytest.raises(MapError, match="closed"):
        worker.run(COUNT_FLOORS)


def test_a_map_open_for_writing_runs_cypher_in_process(map_dir: Path, tmp_path: Path) -> None:
    import shutil

    work = tmp_path / "m"
    shutil.copytree(map_dir, work)
    with MapService.open(work, write=True) as service:
        assert service.cypher(COUNT_FLOORS).rows == [[1]]
        assert service._cypher_worker is None
