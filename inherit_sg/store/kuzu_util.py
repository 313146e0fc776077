"""Small helpers around the Kuzu Python API: result rows, catalog lookups and turning
Kuzu's exceptions into INHerit-SG errors."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import kuzu

if TYPE_CHECKING:
    import pyarrow as pa

from inherit_sg.errors import CypherError, InheritSGError, ReadOnlyViolationError

# Rows per Arrow batch when reading results: Kuzu's default batch sizing makes even a
# few-row ``get_as_arrow()`` take ~0.5 s, a fixed size keeps small reads instant.
ARROW_CHUNK_ROWS = 8192


def _result(res: kuzu.QueryResult | list[kuzu.QueryResult]) -> kuzu.QueryResult:
    return res[-1] if isinstance(res, list) else res


def next_row(res: kuzu.QueryResult) -> list[Any]:
    """The next row as a list (Kuzu may hand back a dict)."""
    row = res.get_next()
    return list(row.values()) if isinstance(row, dict) else list(row)


def arrow_table(
    conn: kuzu.Connection, query: str, params: dict[str, Any] | None = None
) -> pa.Table:
    """A query's whole result as an Arrow table (columns named by the RETURN aliases)."""
    res = _result(conn.execute(query, params or {}))
    try:
        return res.get_as_arrow(chunk_size=ARROW_CHUNK_ROWS)
    finally:
        res.close()


def run(conn: kuzu.Connection, query: str, params: dict[str, Any] | None = None) -> None:
    """Execute a statement whose result is not needed."""
    res = conn.execute(query, params or {})
    for r in res if isinstance(res, list) else [res]:
        r.close()


def rows(
    conn: kuzu.Connection, query: str, params: dict[str, Any] | None = None
) -> list[list[Any]]:
    """All result rows of a query."""
    res = _result(conn.execute(query, params or {}))
    out: list[list[Any]] = []
    while res.has_next():
        out.append(next_row(res))
    res.close()
    return out


def scalar(conn: kuzu.Connection, query: str, params: dict[str, Any] | None = None) -> Any:
    """First column of the first row (None when there is no row)."""
    found = rows(conn, query, params)
    return found[0][0] if found else None


def table_names(conn: kuzu.Connection) -> set[str]:
    """Names of all node and rel tables."""
    return {r[0] for r in rows(conn, "CALL SHOW_TABLES() RETURN name")}


def index_names(conn: kuzu.Connection) -> set[tuple[str, str]]:
    """(table, index) pairs of all indexes."""
    return {(r[0], r[1]) for r in rows(conn, "CALL SHOW_INDEXES() RETURN *")}


def translate(exc: RuntimeError, query: str) -> InheritSGError:
    """Map a Kuzu error on ``query`` to CypherError / ReadOnlyViolationError."""
    text = str(exc)
    if "read-only" in text or "read only" in text:
        return ReadOnlyViolationError(f"read-only query tried to write: {text}")
    short = query if len(query) <= 200 else query[:200] + "…"
    return CypherError(f"{text} (in query: {short})")
