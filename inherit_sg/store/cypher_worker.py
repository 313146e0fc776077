"""Run user Cypher where a crash cannot reach the caller: a child process per map.

Kuzu 0.11.3 can crash its whole process on some read-only statements (a segmentation
fault on ``ORDER BY … SKIP`` with a large computed offset, for one); guarding the text
will always miss a form. A :class:`CypherWorker` therefore opens the map's graph file
read-only in a child process (started with ``spawn``, so it shares no threads or locks
with the caller) and runs one statement at a time there, with the same guards and row
limit as in-process Cypher. The time limit is enforced from outside: a statement that has
not answered ``GRACE_S`` after its limit is stopped by ending the child. A child that
dies (a crash, a kill, running out of memory) costs only its statement, which answers a
clear :class:`~inherit_sg.errors.CypherCrashError`; the next statement starts a new
child.

Kuzu lets several processes open a database read-only, but none while one writes it, so
a worker serves maps that are open read-only (``MapService`` runs Cypher in-process while
it writes the map), and must be closed before the map is opened for writing.
"""

from __future__ import annotations

import contextlib
import logging
import multiprocessing
import signal
import sys
import threading
import time
import types
from collections.abc import Iterator
from multiprocessing.connection import Connection
from pathlib import Path
from typing import Any

from inherit_sg import errors
from inherit_sg.errors import (
    CypherCrashError,
    CypherError,
    InheritSGError,
    MapError,
    QueryTimeoutError,
)
from inherit_sg.store.kuzu_graph import CypherResult

log = logging.getLogger(__name__)

# Seconds past a statement's time limit before the child is ended.
GRACE_S = 2.0
# Seconds a new child may take to import Kuzu and open the database.
START_TIMEOUT_S = 60.0


_START_LOCK = threading.Lock()


@contextlib.contextmanager
def _caller_script_hidden() -> Iterator[None]:
    """While a ``spawn`` child starts, show it no ``__main__`` to import: ``spawn`` runs
    the caller's script again in the child (as ``__mp_main__``), and a plain script
    without an ``if __name__ == "__main__"`` guard would then build its maps again, or
    fail to start the worker at all. The child needs nothing from the script."""
    main = sys.modules.get("__main__")
    sys.modules["__main__"] = types.ModuleType("__main__")
    try:
        yield
    finally:
        if main is not None:
            sys.modules["__main__"] = main


def _serve(file: str, conn: Connection) -> None:
    """The child: open ``file`` read-only, answer statements until told to stop."""
    from inherit_sg.store.kuzu_graph import KuzuGraph

    try:
        graph = KuzuGraph(Path(file), read_only=True)
    except BaseException as exc:  # every failure goes back to the caller
        conn.send(("error", type(exc).__name__, str(exc)))
        return
    conn.send(("ready",))
    try:
        while True:
            try:
                request = conn.recv()
            except EOFError:
                return  # the caller went away
            if request is None:
                return
            try:
                result = graph.query(
                    request["query"],
                    request["params"],
                    read_only=True,
                    max_rows=request["max_rows"],
                    timeout_s=request["timeout_s"],
                )
                conn.send(("ok", result.columns, result.rows, result.truncated))
            except Exception as exc:  # sent back as the caller's error
                conn.send(("error", type(exc).__name__, str(exc)))
    finally:
        graph.close()


def _error(name: str, message: str) -> InheritSGError:
    """The project error named ``name`` (a CypherError for anything else)."""
    cls = getattr(errors, name, None)
    if isinstance(cls, type) and issubclass(cls, InheritSGError):
        return cls(message)
    return CypherError(f"{name}: {message}")


def _death(code: int | None) -> str:
    if code is not None and code < 0:
        with contextlib.suppress(ValueError):
            return f"signal {signal.Signals(-code).name}"
        return f"signal {-code}"
    return f"exit code {code}"


class CypherWorker:
    """Read-only Cypher on one graph file, run in a child process (see the module
    docstring). Thread-safe: statements run one at a time."""

    def __init__(self, file: str | Path) -> None:
        self.file = Path(file)
        self._lock = threading.Lock()
        self._proc: Any = None
        self._conn: Connection | None = None
        self._closed = False
        self.crashes = 0  # children lost to crashes or time limits (for the service's logs)

    @property
    def pid(self) -> int | None:
        """The running child's process id, if one runs."""
        proc = self._proc
        return proc.pid if proc is not None and proc.is_alive() else None

    def run(
        self,
        query: str,
        params: dict[str, Any] | None = None,
        *,
        max_rows: int | None = None,
        timeout_s: float | None = None,
    ) -> CypherResult:
        """Run one read-only statement; raises what in-process Cypher raises, plus
        :class:`CypherError` when the statement killed the database engine and
        :class:`QueryTimeoutError` when it outran ``timeout_s``."""
        with self._lock:
            if self._closed:
                raise MapError(f"the Cypher worker of {self.file} is closed")
            conn = self._ensure()
            request: dict[str, Any] = {
                "query": query,
                "params": params or {},
                "max_rows": max_rows,
                "timeout_s": timeout_s,
            }
            try:
                conn.send(request)
            except (OSError, ValueError) as exc:  # a dead child, or values not to send
                self._reap()
                raise CypherError(f"the statement could not be sent: {exc}") from None
            wait = None if timeout_s is None else timeout_s + GRACE_S
            try:
                answered = conn.poll(wait)
                reply = conn.recv() if answered else None
            except (EOFError, OSError):
                reply, answered = None, True
            if not answered:
                self._stop()
                self.crashes += 1
                raise QueryTimeoutError(
                    f"query stopped after its time limit of {timeout_s:g} s"
                ) from None
            if reply is None:
                code = self._reap()
                self.crashes += 1
                if self._closed:
                    raise MapError("the map was closed while the statement ran")
                log.error("Cypher worker of %s died (%s) on: %s", self.file, _death(code), query)
                raise CypherCrashError(
                    f"the statement crashed the graph database engine ({_death(code)}); the "
                    "map and the service are unaffected, and the next statement runs in a "
                    "fresh worker"
                )
        if reply[0] == "ok":
            return CypherResult(columns=list(reply[1]), rows=list(reply[2]), truncated=reply[3])
        raise _error(reply[1], reply[2])

    def _ensure(self) -> Connection:
        """The connection to a running child, starting one when needed."""
        if self._proc is not None and self._proc.is_alive() and self._conn is not None:
            return self._conn
        self._reap()
        ctx = multiprocessing.get_context("spawn")
        parent, child = ctx.Pipe()
        proc = ctx.Process(
            target=_serve, args=(str(self.file), child), daemon=True, name="cypher-worker"
        )
        with _START_LOCK, _caller_script_hidden():
            proc.start()
        child.close()
        self._proc, self._conn = proc, parent
        deadline = time.monotonic() + START_TIMEOUT_S
        try:
            if not parent.poll(max(0.0, deadline - time.monotonic())):
                raise MapError(f"the Cypher worker of {self.file} did not start")
            reply = parent.recv()
        except (EOFError, OSError):
            code = self._reap()
            raise MapError(
                f"the Cypher worker of {self.file} ended while opening it ({_death(code)})"
            ) from None
        except MapError:
            self._stop()
            raise
        if reply[0] != "ready":
            self._reap()
            raise _error(reply[1], reply[2])
        return parent

    def _stop(self) -> None:
        """End the child now (it may be stuck in a statement)."""
        proc = self._proc
        if proc is not None and proc.is_alive():
            proc.kill()
        self._reap()

    def _reap(self) -> int | None:
        """Forget the child, collecting its exit code."""
        proc, conn = self._proc, self._conn
        self._proc, self._conn = None, None
        if conn is not None:
            with contextlib.suppress(OSError):
                conn.close()
        if proc is None:
            return None
        proc.join(timeout=5)
        if proc.is_alive():
            proc.kill()
            proc.join(timeout=5)
        code: int | None = proc.exitcode
        return code

    def close(self) -> None:
        """Stop the child (politely, then by force); later statements are refused."""
        self._closed = True
        if not self._lock.acquire(blocking=False):
            # a statement runs: end its child; that call reaps it and reports the close
            proc = self._proc
            if proc is not None and proc.is_alive():
                proc.kill()
            return
        try:
            conn, proc = self._conn, self._proc
            if conn is not None and proc is not None and proc.is_alive():
                with contextlib.suppress(OSError, ValueError):
                    conn.send(None)
                proc.join(timeout=2)
            self._stop()
        finally:
            self._lock.release()
