"""Full-text search over Object (label, description), Area and Room (label, summary).

Kuzu 0.11.3's full-text index cannot be kept up to date row by row (measured):

* one statement inserting several rows indexes all of them with one row's text, and
  one updating the text of several rows crashes the process;
* past ~2k rows even single-row updates and deletes leave it wrong (a third of the
  matches missing at 3k rows), and so do single-row inserts when the index was created
  on an empty table;
* ``DROP_FTS_INDEX`` followed by writes and a new ``CREATE_FTS_INDEX`` on the same
  table corrupts other columns of the rows written in between.

Built in one go over a fresh table it is right (checked to 10k rows, and across
reopen). So the text lives a second time in small tables ``ObjectDoc``, ``AreaDoc`` and
``RoomDoc`` (id + the text columns) in ``index.kuzu`` (see
:mod:`~inherit_sg.store.search_index`), never updated in place: when text changed (the
graph write transaction marks the table dirty in ``_TextIndexState``) the doc table is
dropped, recreated from the node table and indexed again — ~0.2 s at 1k rows, ~0.4 s
at 10k. That happens lazily, before the next text search (or a Cypher statement that
calls ``QUERY_FTS_INDEX``) and when a writer closes or opens the map, so a mapping run
that writes often pays once per search, not once per write. The dirty mark commits with
the data, so a crash before the rebuild is repaired by the next writable open.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import kuzu

from inherit_sg.store.kuzu_util import ARROW_CHUNK_ROWS, index_names, rows, run, scalar, table_names

STATE_TABLE = "_TextIndexState"


@dataclass(frozen=True)
class TextIndex:
    """The searchable text of one node table."""

    table: str  # node table: Object, Area, Room
    doc_table: str  # its rebuilt copy carrying the full-text index
    index: str
    columns: tuple[str, ...]


TEXT_INDEXES: dict[str, TextIndex] = {
    t.table: t
    for t in (
        TextIndex("Object", "ObjectDoc", "object_fts", ("label", "description")),
        TextIndex("Area", "AreaDoc", "area_fts", ("label", "summary")),
        TextIndex("Room", "RoomDoc", "room_fts", ("label", "summary")),
    )
}


def mark_dirty(graph: kuzu.Connection, tables: Iterable[str]) -> None:
    """Record (inside the graph write transaction) that text of ``tables`` changed."""
    for table in sorted(set(tables)):
        run(graph, f"MERGE (s:{STATE_TABLE} {{name: $t}}) SET s.dirty = true", {"t": table})


def stale_tables(graph: kuzu.Connection, index: kuzu.Connection) -> set[str]:
    """Tables whose doc table must be rebuilt before it can be searched: marked dirty,
    or holding rows while their doc table is missing."""
    stale = {r[0] for r in rows(graph, f"MATCH (s:{STATE_TABLE}) WHERE s.dirty RETURN s.name")}
    existing = table_names(index)
    for spec in TEXT_INDEXES.values():
        if spec.doc_table not in existing and scalar(
            graph, f"MATCH (n:{spec.table}) RETURN count(n)"
        ):
            stale.add(spec.table)
    return stale


def rebuild(graph: kuzu.Connection, index: kuzu.Connection, table: str) -> None:
    """Recreate the doc table of ``table`` in the index database from the graph's rows
    and index it (both connections in auto-commit mode, held by the writer)."""
    spec = TEXT_INDEXES[table]
    ret = ", ".join(f"n.{c} AS {c}" for c in ("id", *spec.columns))
    res = graph.execute(f"MATCH (n:{table}) RETURN {ret}")
    assert isinstance(res, kuzu.QueryResult)
    docs = res.get_as_arrow(chunk_size=ARROW_CHUNK_ROWS)
    res.close()
    if (spec.doc_table, spec.index) in index_names(index):
        run(index, f"CALL DROP_FTS_INDEX('{spec.doc_table}', '{spec.index}')")
    run(index, f"DROP TABLE IF EXISTS {spec.doc_table}")
    cols = ", ".join(f"{c} STRING" for c in spec.columns)
    run(index, f"CREATE NODE TABLE {spec.doc_table}(id STRING PRIMARY KEY, {cols})")
    if docs.num_rows:  # never index an empty table
        props = ", ".join(f"{c}: {c}" for c in ("id", *spec.columns))
        run(index, f"LOAD FROM $docs CREATE (:{spec.doc_table} {{{props}}})", {"docs": docs})
        names = ", ".join(f"'{c}'" for c in spec.columns)
        run(
            index,
            f"CALL CREATE_FTS_INDEX('{spec.doc_table}', '{spec.index}', [{names}], "
            "stemmer := 'english')",
        )
    run(graph, f"MERGE (s:{STATE_TABLE} {{name: $t}}) SET s.dirty = false", {"t": table})


def search(index: kuzu.Connection, table: str, text: str, k: int) -> list[tuple[str, float]]:
    """(node id, BM25 score) of the best ``k`` matches, best first ([] when the table
    has no rows and so no index)."""
    spec = TEXT_INDEXES[table]
    if (spec.doc_table, spec.index) not in index_names(index):
        return []
    found = rows(
        index,
        f"CALL QUERY_FTS_INDEX('{spec.doc_table}', '{spec.index}', $q) "
        "RETURN node.id, score ORDER BY score DESC, node.id LIMIT $k",
        {"q": text, "k": int(k)},
    )
    return [(str(i), float(s)) for i, s in found]
