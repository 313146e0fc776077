"""Compacting a map's graph database: rewrite ``graph.kuzu`` without its dead pages.

Kuzu 0.11.3 hardly reuses the pages that updates and deletes free, so a map that was
written many times (a mapping session flushes after every few keyframes) grows far past
its data: the graph of a 240-object house takes 48 MB after mapping and 25 MB when the
same rows are written once. Compaction exports the database (``EXPORT DATABASE``, as
Parquet), imports it into a new file (``IMPORT DATABASE``), checks that every table
holds the same rows, and only then puts the new file in place of the old one.

What no rewrite removes (measured): every node table that holds a row costs at least
~1.1 MB, the size of Kuzu's primary-key hash index at its smallest, whatever the
number of rows (three rows of ``_Migration`` take 1.1 MB).

The caller holds the map's writer lock and has closed every connection to the file.
"""

from __future__ import annotations

import hashlib
import logging
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import kuzu

from inherit_sg.errors import MapError
from inherit_sg.store.kuzu_util import rows, run
from inherit_sg.store.stats import kuzu_bytes

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class TableDigest:
    """Rows and a content hash of one table."""

    rows: int
    digest: str


def _columns(conn: kuzu.Connection, table: str) -> tuple[list[str], str | None]:
    """A table's property names and its primary key (None for a rel table)."""
    info = rows(conn, f"CALL TABLE_INFO('{table}') RETURN *")
    names = [str(r[1]) for r in info]
    keys = [str(r[1]) for r in info if len(r) > 4 and r[4] is True]
    return names, (keys[0] if keys else None)


def _hash_rows(found: list[list[Any]]) -> str:
    h = hashlib.sha256()
    for row in found:
        h.update(repr(row).encode("utf-8"))
        h.update(b"\n")
    return h.hexdigest()


def table_digests(conn: kuzu.Connection) -> dict[str, TableDigest]:
    """Every table's row count and a hash of its rows in a fixed order: node tables by
    primary key, rel tables by their ends' keys and then their properties."""
    out: dict[str, TableDigest] = {}
    tables = rows(conn, "CALL SHOW_TABLES() RETURN name, type ORDER BY name")
    for name, kind in tables:
        cols, key = _columns(conn, name)
        if kind == "NODE":
            ret = ", ".join(f"n.`{c}`" for c in cols)
            found = rows(conn, f"MATCH (n:`{name}`) RETURN {ret} ORDER BY n.`{key}`")
        elif kind == "REL":
            ends = rows(conn, f"CALL SHOW_CONNECTION('{name}') RETURN *")
            parts: list[list[Any]] = []
            for src, dst, src_key, dst_key in ends:
                ret = ", ".join([f"a.`{src_key}`", f"b.`{dst_key}`", *(f"r.`{c}`" for c in cols)])
                parts += rows(conn, f"MATCH (a:`{src}`)-[r:`{name}`]->(b:`{dst}`) RETURN {ret}")
            found = sorted(parts, key=repr)
        else:  # pragma: no cover - a map holds only node and rel tables
            continue
        out[name] = TableDigest(len(found), _hash_rows(found))
    return out


def _digests_of(file: Path) -> dict[str, TableDigest]:
    db = kuzu.Database(str(file), read_only=True)
    try:
        return table_digests(kuzu.Connection(db))
    finally:
        db.close()


@dataclass(frozen=True)
class CompactResult:
    """What rewriting one database file kept."""

    tables: int
    rows: int


@dataclass(frozen=True)
class CompactReport:
    """What compacting a map did: bytes of each database file (with its log) before and
    after, and the tables and rows the graph holds."""

    before: dict[str, int]
    after: dict[str, int]
    tables: int
    rows: int

    @property
    def saved(self) -> int:
        """Bytes freed."""
        return sum(self.before.values()) - sum(self.after.values())


def compact_graph_file(file: Path) -> CompactResult:
    """Rewrite the Kuzu database ``file`` by export and import, check that every table
    holds the same rows, and replace ``file`` with the rewrite. On any failure the
    original is left as it was and :class:`MapError` says why."""
    before = kuzu_bytes(file)
    work = Path(tempfile.mkdtemp(prefix=".compact-", dir=file.parent))
    new = work / file.name
    try:
        db = kuzu.Database(str(file))
        try:
            conn = kuzu.Connection(db)
            run(conn, "CHECKPOINT")
            old = table_digests(conn)
            run(conn, f"EXPORT DATABASE '{work / 'export'}' (format = 'parquet')")
        finally:
            db.close()
        db = kuzu.Database(str(new))
        try:
            conn = kuzu.Connection(db)
            run(conn, f"IMPORT DATABASE '{work / 'export'}'")
            run(conn, "CHECKPOINT")
        finally:
            db.close()
        if kuzu_bytes(new) != new.stat().st_size:
            raise MapError(f"compacting {file} was abandoned: the rewrite kept a log")
        fresh = _digests_of(new)
        if fresh != old:
            differ = sorted(t for t in old.keys() | fresh.keys() if old.get(t) != fresh.get(t))
            raise MapError(
                f"compacting {file} was abandoned: the rewritten database differs in "
                f"{', '.join(differ)}; the map is unchanged"
            )
        _replace(file, new)
    except RuntimeError as exc:
        raise MapError(f"compacting {file} failed ({exc}); the map is unchanged") from None
    finally:
        shutil.rmtree(work, ignore_errors=True)
    after = kuzu_bytes(file)
    total = sum(d.rows for d in old.values())
    log.info("compacted %s: %.1f MB -> %.1f MB", file, before / 1e6, after / 1e6)
    return CompactResult(len(old), total)


def _replace(file: Path, new: Path) -> None:
    """Put ``new`` in place of ``file`` with one rename (same directory), after syncing
    it; the old file's write-ahead log, empty after the checkpoint, goes too."""
    with open(new, "rb") as fh:
        os.fsync(fh.fileno())
    os.replace(new, file)
    file.with_name(file.name + ".wal").unlink(missing_ok=True)
    dir_fd = os.open(file.parent, os.O_RDONLY)
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)
