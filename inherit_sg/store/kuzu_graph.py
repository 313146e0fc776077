"""One Kuzu database file of a map (``graph.kuzu`` or ``index.kuzu``): one writer
connection behind a lock (single-writer discipline inside the process), per-thread
reader connections, explicit write transactions and read-only execution of user
Cypher."""

from __future__ import annotations

import contextlib
import os
import threading
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import kuzu

from inherit_sg.errors import CypherError, MapError, QueryTimeoutError
from inherit_sg.store.cypher_lex import split_statements
from inherit_sg.store.kuzu_util import arrow_table, next_row, run, translate
from inherit_sg.store.readonly import check_read_only
from inherit_sg.store.skip_guard import check_skip


def _buffer_pool_bytes() -> int:
    """A quarter of physical memory, at least 512 MiB: one write transaction must fit in
    Kuzu's buffer pool (bulk-loading 100k objects with both vectors overflows 1 GiB)."""
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError):
        total = 4 << 30
    return max(512 << 20, total // 4)


@dataclass
class CypherResult:
    """Rows of a Cypher query; ``truncated`` when ``max_rows`` cut the result."""

    columns: list[str]
    rows: list[list[Any]] = field(default_factory=list)
    truncated: bool = False

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form (values as Kuzu returns them)."""
        return {"columns": self.columns, "rows": self.rows, "truncated": self.truncated}


class KuzuGraph:
    """Connections to one Kuzu database file.

    Opening read-only uses a read-only Kuzu database, so writes are impossible there
    whatever the query says; opening for writing holds Kuzu's own file lock as well.
    """

    def __init__(self, file: Path, *, read_only: bool) -> None:
        self.file = file
        self.read_only = read_only
        self._db = kuzu.Database(
            str(file), read_only=read_only, buffer_pool_size=_buffer_pool_bytes()
        )
        self._write_lock = threading.RLock()
        self._local = threading.local()
        self._readers: list[kuzu.Connection] = []
        self._readers_lock = threading.Lock()
        try:
            # The Database opens its file lazily: the first connection takes Kuzu's lock.
            self._writer = None if read_only else kuzu.Connection(self._db)
            self.reader()
        except BaseException:
            self.close()
            raise

    def reader(self) -> kuzu.Connection:
        """This thread's read connection."""
        conn: kuzu.Connection | None = getattr(self._local, "conn", None)
        if conn is None:
            conn = kuzu.Connection(self._db)
            self._local.conn = conn
            with self._readers_lock:
                self._readers.append(conn)
        return conn

    @contextlib.contextmanager
    def snapshot(self) -> Iterator[kuzu.Connection]:
        """This thread's reader inside a read-only transaction: several queries see one
        consistent state even while the writer commits."""
        conn = self.reader()
        run(conn, "BEGIN TRANSACTION READ ONLY")
        try:
            yield conn
        finally:
            with contextlib.suppress(RuntimeError):
                run(conn, "ROLLBACK")

    @contextlib.contextmanager
    def writer(self) -> Iterator[kuzu.Connection]:
        """The writer connection, held exclusively, in auto-commit mode."""
        if self._writer is None:
            raise MapError(f"{self.file} is open read-only")
        with self._write_lock:
            yield self._writer

    @contextlib.contextmanager
    def transaction(self) -> Iterator[kuzu.Connection]:
        """One write transaction: committed when the block ends, rolled back on error."""
        with self.writer() as conn:
            run(conn, "BEGIN TRANSACTION")
            try:
                yield conn
            except BaseException:
                with contextlib.suppress(RuntimeError):
                    run(conn, "ROLLBACK")  # Kuzu may have rolled back already
                raise
            run(conn, "COMMIT")

    def query(
        self,
        query: str,
        params: dict[str, Any] | None = None,
        *,
        read_only: bool = True,
        max_rows: int | None = None,
        timeout_s: float | None = None,
    ) -> CypherResult:
        """Run one user statement. Read-only statements pass the lexical guard and run
        in a ``READ ONLY`` transaction on a reader connection; others need the writer.
        ``timeout_s``: interrupt the statement after that long (QueryTimeoutError)."""
        statements = split_statements(query)
        if len(statements) != 1:
            raise CypherError(f"expected one Cypher statement, got {len(statements)}")
        check_skip(query, params)
        if read_only:
            check_read_only(query)
            with self.snapshot() as conn:
                return self._fetch(conn, query, params, max_rows, timeout_s)
        with self.writer() as conn:
            return self._fetch(conn, query, params, max_rows, timeout_s)

    def column(self, query: str, params: dict[str, Any] | None = None) -> list[Any]:
        """The first column of a read-only statement's rows, read through Arrow: many
        rows cost one conversion instead of a Python call per row."""
        check_read_only(query)
        with self.snapshot() as conn:
            try:
                table = arrow_table(conn, query, params)
            except RuntimeError as exc:
                raise translate(exc, query) from None
            except (ValueError, TypeError) as exc:  # parameters Kuzu cannot bind
                raise CypherError(f"query parameters: {exc}") from None
        return table.column(0).to_pylist() if table.num_columns else []

    @staticmethod
    def _fetch(
        conn: kuzu.Connection,
        query: str,
        params: dict[str, Any] | None,
        max_rows: int | None,
        timeout_s: float | None = None,
    ) -> CypherResult:
        if timeout_s is not None:
            conn.set_query_timeout(max(1, round(timeout_s * 1000)))
        try:
            res = conn.execute(query, params or {})
            assert isinstance(res, kuzu.QueryResult)
            out = CypherResult(columns=list(res.get_column_names()))
            while res.has_next():
                if max_rows is not None and len(out.rows) >= max_rows:
                    out.truncated = True
                    break
                out.rows.append(next_row(res))
            res.close()
            return out
        except RuntimeError as exc:
            if timeout_s is not None and str(exc).strip() == "Interrupted.":
                raise QueryTimeoutError(
                    f"query interrupted after its time limit of {timeout_s:g} s"
                ) from None
            raise translate(exc, query) from None
        except (ValueError, TypeError) as exc:  # parameters Kuzu cannot bind
            raise CypherError(f"query parameters: {exc}") from None
        finally:
            if timeout_s is not None:
                conn.set_query_timeout(0)  # the connection is reused: no limit by default

    def close(self) -> None:
        """Close every connection, then the database (checkpointing the WAL)."""
        with self._readers_lock:
            readers, self._readers = self._readers, []
        for conn in readers:
            with contextlib.suppress(RuntimeError):
                conn.close()
        writer = getattr(self, "_writer", None)
        if writer is not None:
            with self._write_lock:
                with contextlib.suppress(RuntimeError):
                    writer.close()
                self._writer = None
        with contextlib.suppress(RuntimeError):
            self._db.close()
