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
reopen). So the text lives a second time in one small table ``TextDoc`` (id, the node
table it comes from, label and body) in ``index.kuzu`` (see
:mod:`~inherit_sg.store.search_index`), never updated in place: when text changed (the
graph write transaction marks the table dirty in ``_TextIndexState``) the doc table is
dropped, recreated from the node tables and indexed again — ~0.2 s at 1k rows, ~0.4 s
at 10k. That happens lazily, before the next text search and when a writer closes or
opens the map, so a mapping run that writes often pays once per search, not once per
write. The dirty mark commits with the data, so a crash before the rebuild is repaired
by the next writable open.

One table for the three layers, not one each: a full-text index costs ~10 MB of
``index.kuzu`` whatever the number of rows (its term, document and stop-word tables
each carry a primary-key index of at least ~1.1 MB), so three of them took 30 MB of a
house's 34 MB index. A search filters the one index by layer.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import kuzu

from inherit_sg.store.kuzu_util import arrow_table, index_names, rows, run, scalar, table_names

STATE_TABLE = "_TextIndexState"


@dataclass(frozen=True)
class TextIndex:
    """The searchable text of one node table: its label and one longer text column."""

    table: str  # node table: Object, Area, Room
    columns: tuple[str, str]  # (label column, body column)


TEXT_INDEXES: dict[str, TextIndex] = {
    t.table: t
    for t in (
        TextIndex("Object", ("label", "description")),
        TextIndex("Area", ("label", "summary")),
        TextIndex("Room", ("label", "summary")),
    )
}
DOC_TABLE = "TextDoc"
FTS_INDEX = "text_fts"
# the per-table doc tables and indexes of maps made before TextDoc
_LEGACY = {
    "Object": ("ObjectDoc", "object_fts"),
    "Area": ("AreaDoc", "area_fts"),
    "Room": ("RoomDoc", "room_fts"),
}


def mark_dirty(graph: kuzu.Connection, tables: Iterable[str]) -> None:
    """Record (inside the graph write transaction) that text of ``tables`` changed."""
    for table in sorted(set(tables)):
        run(graph, f"MERGE (s:{STATE_TABLE} {{name: $t}}) SET s.dirty = true", {"t": table})


def stale_tables(
    graph: kuzu.Connection, index: kuzu.Connection, *, upgrade: bool = True
) -> set[str]:
    """Tables whose text must be copied again before it can be searched: marked dirty,
    or holding rows while the doc table is missing. With ``upgrade`` False (a reader)
    the per-table doc table of a map made before ``TextDoc`` still serves."""
    stale = {r[0] for r in rows(graph, f"MATCH (s:{STATE_TABLE}) WHERE s.dirty RETURN s.name")}
    names = table_names(index)
    if DOC_TABLE not in names:
        for spec in TEXT_INDEXES.values():
            if not upgrade and _LEGACY[spec.table][0] in names:
                continue
            if scalar(graph, f"MATCH (n:{spec.table}) RETURN count(n)"):
                stale.add(spec.table)
    return stale


def _drop(index: kuzu.Connection, doc_table: str, fts_index: str) -> None:
    if (doc_table, fts_index) in index_names(index):
        run(index, f"CALL DROP_FTS_INDEX('{doc_table}', '{fts_index}')")
    run(index, f"DROP TABLE IF EXISTS {doc_table}")


def rebuild(graph: kuzu.Connection, index: kuzu.Connection) -> None:
    """Recreate the doc table in the index database from the graph's rows of every
    text table and index it (both connections in auto-commit mode, held by the
    writer); every table is then clean."""
    import pyarrow as pa

    parts = []
    for spec in TEXT_INDEXES.values():
        label, body = spec.columns
        query = (
            f"MATCH (n:{spec.table}) RETURN n.id AS id, '{spec.table}' AS layer, "
            f"n.{label} AS label, n.{body} AS body"
        )
        parts.append(arrow_table(graph, query))
    docs = pa.concat_tables(parts)
    for doc_table, fts_index in (*_LEGACY.values(), (DOC_TABLE, FTS_INDEX)):
        _drop(index, doc_table, fts_index)
    run(
        index,
        f"CREATE NODE TABLE {DOC_TABLE}"
        "(id STRING PRIMARY KEY, layer STRING, label STRING, body STRING)",
    )
    if docs.num_rows:  # never index an empty table
        run(
            index,
            f"LOAD FROM $docs CREATE (:{DOC_TABLE} "
            "{id: id, layer: layer, label: label, body: body})",
            {"docs": docs},
        )
        run(
            index,
            f"CALL CREATE_FTS_INDEX('{DOC_TABLE}', '{FTS_INDEX}', ['label', 'body'], "
            "stemmer := 'english')",
        )
    for table in TEXT_INDEXES:
        run(graph, f"MERGE (s:{STATE_TABLE} {{name: $t}}) SET s.dirty = false", {"t": table})


def search(index: kuzu.Connection, table: str, text: str, k: int) -> list[tuple[str, float]]:
    """(node id, BM25 score) of the best ``k`` matches among ``table``'s nodes, best
    first ([] when no node has text and so there is no index)."""
    if table not in TEXT_INDEXES:
        return []
    names = index_names(index)
    params: dict[str, object] = {"q": text, "k": int(k)}
    if (DOC_TABLE, FTS_INDEX) in names:
        query = (
            f"CALL QUERY_FTS_INDEX('{DOC_TABLE}', '{FTS_INDEX}', $q) "
            "WITH node, score WHERE node.layer = $layer "
        )
        params["layer"] = table
    elif _LEGACY[table] in names:  # a map made before TextDoc, opened read-only
        doc_table, fts_index = _LEGACY[table]
        query = f"CALL QUERY_FTS_INDEX('{doc_table}', '{fts_index}', $q) WITH node, score "
    else:
        return []
    query += "RETURN node.id, score ORDER BY score DESC, node.id LIMIT $k"
    found = rows(index, query, params)
    return [(str(i), float(s)) for i, s in found]
