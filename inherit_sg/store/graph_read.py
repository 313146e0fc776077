"""Read operations on the Kuzu graph: nodes with their embeddings, edges, keyframe
metadata and sessions, read in bulk through Arrow."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import kuzu

from inherit_sg.errors import InputError, NodeNotFoundError
from inherit_sg.model import Edge, EdgeKind, Keyframe, Layer, Node, SceneGraph, Session
from inherit_sg.store import codec, edges
from inherit_sg.store.embeddings import read_vectors
from inherit_sg.store.indexes import indexes_of
from inherit_sg.store.kuzu_util import arrow_table, scalar
from inherit_sg.store.node_write import table_of


def arrow_rows(
    conn: kuzu.Connection, query: str, params: dict[str, Any] | None = None
) -> list[dict[str, Any]]:
    """Result rows as dicts keyed by the RETURN aliases."""
    return arrow_table(conn, query, params).to_pylist()


def _returns(var: str, cols: Sequence[str]) -> str:
    return ", ".join(f"{var}.{c} AS {c}" for c in cols)


def read_nodes(
    conn: kuzu.Connection,
    table: str,
    dims: Mapping[str, int],
    ids: Sequence[str] | None = None,
) -> list[Node]:
    """Nodes of one layer table (all, or those of ``ids``) with their vectors."""
    ret = _returns("n", codec.columns(table))
    if ids is None:
        found = arrow_rows(conn, f"MATCH (n:{table}) RETURN {ret}")
    else:
        found = arrow_rows(
            conn, f"UNWIND $ids AS i MATCH (n:{table} {{id: i}}) RETURN {ret}", {"ids": list(ids)}
        )
    nodes = [codec.node_from_row(table, r) for r in found]
    for spec in indexes_of(table):
        vec_ids, mat = read_vectors(conn, spec, dims[spec.dim_key], ids)
        by_id = dict(zip(vec_ids, mat, strict=True))
        for node in nodes:
            setattr(node, spec.attr, by_id.get(node.id))
    return nodes


def read_edges(conn: kuzu.Connection, kind: EdgeKind) -> list[Edge]:
    """All stored edges of one kind."""
    src, dst = kind.endpoints
    extra = "".join(f", r.{c} AS {c}" for c in edges.extra_columns(kind))
    query = (
        f"MATCH (a:{src})-[r:{kind.value}]->(b:{dst}) "
        f"RETURN a.id AS src, b.id AS dst{extra}, r.props AS props"
    )
    return [edges.edge_from_row(kind, r) for r in arrow_rows(conn, query)]


def load_graph(conn: kuzu.Connection, dims: Mapping[str, int]) -> SceneGraph:
    """The whole scene graph with embeddings; its change log is empty."""
    graph = SceneGraph()
    for layer in Layer:
        for node in read_nodes(conn, layer.table, dims):
            graph.add_or_update(node)
    for kind in EdgeKind:
        for edge in read_edges(conn, kind):
            graph.add_edge(edge)
    graph.flush_changes()
    return graph


def get_node(conn: kuzu.Connection, node_id: str, dims: Mapping[str, int]) -> Node:
    """One node with its vectors; NodeNotFoundError when absent."""
    try:
        table = table_of(node_id)
    except InputError:
        raise NodeNotFoundError(f"no node {node_id!r} in the map") from None
    found = read_nodes(conn, table, dims, [node_id])
    if not found:
        raise NodeNotFoundError(f"no node {node_id!r} in the map")
    return found[0]


def get_keyframe(conn: kuzu.Connection, keyframe_id: str) -> Keyframe:
    """Keyframe metadata; NodeNotFoundError when absent or only referenced so far."""
    ret = _returns("k", codec.columns("Keyframe"))
    found = arrow_rows(conn, f"MATCH (k:Keyframe {{id: $id}}) RETURN {ret}", {"id": keyframe_id})
    if not found or found[0]["pose"] is None:
        raise NodeNotFoundError(f"no keyframe {keyframe_id!r} in the map")
    return codec.keyframe_from_row(found[0])


def existing_keyframes(conn: kuzu.Connection, ids: Sequence[str]) -> set[str]:
    """Which of ``ids`` are stored keyframes."""
    query = "UNWIND $ids AS i MATCH (k:Keyframe {id: i}) WHERE k.pose IS NOT NULL RETURN k.id AS id"
    return {r["id"] for r in arrow_rows(conn, query, {"ids": list(ids)})}


def read_sessions(conn: kuzu.Connection) -> list[Session]:
    """All sessions, oldest first."""
    ret = _returns("s", codec.columns("Session"))
    found = arrow_rows(conn, f"MATCH (s:Session) RETURN {ret} ORDER BY s.started, s.id")
    return [codec.session_from_row(r) for r in found]


def count(conn: kuzu.Connection, table: str, rel: bool = False) -> int:
    """Rows in a node table (or edges in a rel table)."""
    pattern = f"()-[r:{table}]->()" if rel else f"(r:{table})"
    return int(scalar(conn, f"MATCH {pattern} RETURN count(r)") or 0)
