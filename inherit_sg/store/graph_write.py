"""Writing edges, keyframe metadata and sessions to Kuzu; each function runs inside
the caller's open write transaction."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

import kuzu

from inherit_sg.errors import InputError
from inherit_sg.model import Edge, EdgeKind, Keyframe, Session
from inherit_sg.store import codec, edges
from inherit_sg.store.kuzu_util import rows, run


def _merge_statement(table: str, cols: Sequence[str]) -> str:
    sets = ", ".join(f"n.{c} = {c}" for c in cols if c != "id")
    return f"LOAD FROM $rows MERGE (n:{table} {{id: id}}) SET {sets}"


def _missing_endpoints(conn: kuzu.Connection, kind: EdgeKind, batch: list[dict[str, Any]]) -> str:
    src_t, dst_t = kind.endpoints
    missing: list[str] = []
    for table, ids in ((src_t, {r["src"] for r in batch}), (dst_t, {r["dst"] for r in batch})):
        found = {
            r[0]
            for r in rows(
                conn,
                f"UNWIND $ids AS i MATCH (n:{table} {{id: i}}) RETURN n.id",
                {"ids": sorted(ids)},
            )
        }
        missing += [f"{table} {i!r}" for i in sorted(ids - found)]
    return ", ".join(missing[:5]) + (" …" if len(missing) > 5 else "")


def upsert_edges(conn: kuzu.Connection, all_edges: Iterable[Edge]) -> None:
    """Insert or replace edges; InputError (and so a rolled-back transaction) when an
    endpoint is not in the map."""
    for kind, group in edges.dedupe(all_edges).items():
        _delete_edge_rows(conn, kind, [(e.src, e.dst, e.key[3]) for e in group])
        table = edges.edge_table(kind, group)
        made = rows(conn, edges.create_clause(kind), {"rows": table})
        if int(made[0][0]) != len(group):
            where = _missing_endpoints(conn, kind, table.to_pylist())
            raise InputError(f"cannot add {kind.value} edges: not in the map: {where}")


def delete_edges(conn: kuzu.Connection, keys: Iterable[tuple[str, str, str, str]]) -> None:
    """Delete edges by :attr:`Edge.key`; absent ones are ignored."""
    by_kind: dict[EdgeKind, list[tuple[str, str, str]]] = {}
    for kind_name, src, dst, pred in keys:
        try:
            kind = EdgeKind(kind_name)
        except ValueError:
            raise InputError(f"unknown edge kind {kind_name!r}") from None
        by_kind.setdefault(kind, []).append((src, dst, pred))
    for kind, group in by_kind.items():
        _delete_edge_rows(conn, kind, group)


def _delete_edge_rows(
    conn: kuzu.Connection, kind: EdgeKind, keys: list[tuple[str, str, str]]
) -> None:
    import pyarrow as pa

    src, dst, pred = (list(c) for c in zip(*keys, strict=True))
    table = pa.table({"src": src, "dst": dst, "predicate": pred})
    run(conn, f"LOAD FROM $rows {edges.match_clause(kind)} DELETE r", {"rows": table})


def upsert_keyframes(conn: kuzu.Connection, keyframes: Sequence[Keyframe]) -> None:
    """Insert or replace Keyframe rows (metadata only)."""
    latest = {kf.id: kf for kf in keyframes}
    table = codec.record_table("Keyframe", [codec.keyframe_row(k) for k in latest.values()])
    run(conn, _merge_statement("Keyframe", codec.columns("Keyframe")), {"rows": table})


def upsert_session(conn: kuzu.Connection, session: Session) -> None:
    """Insert or replace one Session row."""
    table = codec.record_table("Session", [codec.session_row(session)])
    run(conn, _merge_statement("Session", codec.columns("Session")), {"rows": table})
