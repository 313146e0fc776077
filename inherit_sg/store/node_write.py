"""Writing scene-graph nodes (and their embeddings) to Kuzu in bulk, and noting which
tables' searchable text changed (see :mod:`inherit_sg.store.text_index`)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field

import kuzu

from inherit_sg.errors import InputError
from inherit_sg.model import Node, layer_of
from inherit_sg.store import codec
from inherit_sg.store.embeddings import VectorDelta, delete_vectors, write_vectors
from inherit_sg.store.indexes import indexes_of
from inherit_sg.store.kuzu_util import rows, run
from inherit_sg.store.text_index import TEXT_INDEXES


def table_of(node_id: str) -> str:
    """Kuzu table holding a scene-graph node id; InputError for other ids."""
    try:
        return layer_of(node_id).table
    except ValueError:
        raise InputError(f"{node_id!r} is not a floor, room, area or object id") from None


def _merge(table: str, cols: Sequence[str]) -> str:
    sets = ", ".join(f"n.{c} = {c}" for c in cols if c != "id")
    return f"LOAD FROM $rows MERGE (n:{table} {{id: id}}) SET {sets}"


@dataclass
class TablePlan:
    """The nodes of one table in an upsert."""

    table: str
    nodes: list[Node] = field(default_factory=list)
    text_changed: bool = False  # a node is new or its searchable text differs


def plan_upserts(conn: kuzu.Connection, nodes: Iterable[Node]) -> dict[str, TablePlan]:
    """Group nodes by table (the last of duplicate ids wins) and compare their
    searchable text with what is stored."""
    by_table: dict[str, dict[str, Node]] = {}
    for node in nodes:
        table = table_of(node.id)
        if node.layer.table != table:
            raise InputError(
                f"node {node.id!r} is a {node.layer.name} node but its id says {table}"
            )
        by_table.setdefault(table, {})[node.id] = node
    plans: dict[str, TablePlan] = {}
    for table, group in by_table.items():
        plan = plans[table] = TablePlan(table, list(group.values()))
        fts = TEXT_INDEXES.get(table)
        if fts is None:
            continue
        ret = ", ".join(f"n.{c}" for c in fts.columns)
        stored = {
            r[0]: tuple(r[1:])
            for r in rows(
                conn,
                f"UNWIND $ids AS i MATCH (n:{table} {{id: i}}) RETURN n.id, {ret}",
                {"ids": list(group)},
            )
        }
        for node in plan.nodes:
            row = codec.node_row(node)
            if stored.get(node.id) != tuple(row[c] for c in fts.columns):
                plan.text_changed = True
                break
    return plans


Deltas = dict[str, VectorDelta]


def merge_deltas(into: Deltas, more: Deltas) -> None:
    """Append the changes of ``more`` to ``into`` (in order)."""
    for name, delta in more.items():
        if delta.empty:
            continue
        target = into.setdefault(name, VectorDelta())
        target.dropped += delta.dropped
        target.added += delta.added


def write_upserts(
    conn: kuzu.Connection, plans: Mapping[str, TablePlan], dims: Mapping[str, int]
) -> Deltas:
    """Write planned nodes with their embeddings (inside the caller's transaction).
    Returns what changed in each vector set."""
    deltas: Deltas = {}
    for table, plan in plans.items():
        rows_ = codec.node_table(table, plan.nodes)
        run(conn, _merge(table, codec.columns(table)), {"rows": rows_})
        for spec in indexes_of(table):
            items = [(n.id, getattr(n, spec.attr)) for n in plan.nodes]
            merge_deltas(deltas, {spec.name: write_vectors(conn, spec, dims[spec.dim_key], items)})
    return deltas


def delete_nodes(conn: kuzu.Connection, ids: Iterable[str]) -> Deltas:
    """Delete nodes, their edges and their embeddings; unknown ids are ignored."""
    by_table: dict[str, list[str]] = {}
    for node_id in dict.fromkeys(ids):
        by_table.setdefault(table_of(node_id), []).append(node_id)
    deltas: Deltas = {}
    for table, group in by_table.items():
        run(conn, f"UNWIND $ids AS i MATCH (n:{table} {{id: i}}) DETACH DELETE n", {"ids": group})
        for spec in indexes_of(table):
            merge_deltas(deltas, {spec.name: delete_vectors(conn, spec, group)})
    return deltas
