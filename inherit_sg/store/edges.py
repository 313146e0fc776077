"""Edges <-> rows of the Kuzu rel tables.

``RELATION`` keeps ``predicate`` and ``confidence`` as columns and ``CONNECTS`` keeps
``door``; every other property of an edge goes to the ``props`` JSON column, so edges
round-trip whatever they carry. Edge identity follows :attr:`Edge.key`: relations
differ by predicate; for the other kinds the store keeps one edge per (kind, src, dst).
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from inherit_sg.model import Edge, EdgeKind
from inherit_sg.store.codec import arrow_table, to_json

if TYPE_CHECKING:
    import pyarrow as pa

EdgeKey = tuple[str, str, str, str]

# Columns beyond src/dst/props per kind, with their codec types.
_COLUMNS: dict[EdgeKind, dict[str, str]] = {
    EdgeKind.RELATION: {"predicate": "str", "confidence": "f64"},
    EdgeKind.CONNECTS: {"door": "vec3"},
}


def extra_columns(kind: EdgeKind) -> list[str]:
    """Property columns of ``kind`` besides ``props``."""
    return list(_COLUMNS.get(kind, {}))


def _column_value(name: str, value: Any) -> Any:
    if value is None:
        return None
    if name == "door":
        return [float(x) for x in value]
    if name == "confidence":
        return float(value)
    return str(value)


def edge_row(edge: Edge) -> dict[str, Any]:
    """Row of one edge: src, dst, typed columns and the JSON of the rest."""
    cols = _COLUMNS.get(edge.kind, {})
    props = edge.prop_dict
    row: dict[str, Any] = {"src": edge.src, "dst": edge.dst}
    for name in cols:
        row[name] = _column_value(name, props.pop(name, None))
    what = f"properties of edge {edge.kind.value} {edge.src}->{edge.dst}"
    row["props"] = to_json(props, what) if props else None
    return row


def edge_table(kind: EdgeKind, edges: Iterable[Edge]) -> pa.Table:
    """Arrow rows of edges of one kind."""
    spec = {"src": "str", "dst": "str", **_COLUMNS.get(kind, {}), "props": "str"}
    return arrow_table(spec, [edge_row(e) for e in edges])


def edge_from_row(kind: EdgeKind, row: dict[str, Any]) -> Edge:
    """Edge from a row with src, dst, the typed columns and props."""
    props: dict[str, Any] = json.loads(row["props"]) if row.get("props") else {}
    for name in _COLUMNS.get(kind, {}):
        value = row.get(name)
        if value is None:
            continue
        props[name] = tuple(float(x) for x in value) if name == "door" else value
    return Edge.make(kind, row["src"], row["dst"], **props)


def dedupe(edges: Iterable[Edge]) -> dict[EdgeKind, list[Edge]]:
    """Edges grouped by kind, one per store identity (the last one wins)."""
    by_key: dict[tuple[str, str, str, str], Edge] = {}
    for e in edges:
        pred = e.key[3] if e.kind is EdgeKind.RELATION else ""
        by_key[(e.kind.value, e.src, e.dst, pred)] = e
    out: dict[EdgeKind, list[Edge]] = {}
    for e in by_key.values():
        out.setdefault(e.kind, []).append(e)
    return out


def match_clause(kind: EdgeKind) -> str:
    """``MATCH`` pattern binding ``r`` to the stored edge(s) with a row's identity."""
    src, dst = kind.endpoints
    pattern = f"MATCH (a:{src} {{id: src}})-[r:{kind.value}]->(b:{dst} {{id: dst}})"
    if kind is EdgeKind.RELATION:
        pattern += " WHERE coalesce(r.predicate, '') = predicate"
    return pattern


def create_clause(kind: EdgeKind) -> str:
    """Statement creating one edge per ``LOAD FROM`` row and returning the count made.

    SEEN_IN may name a keyframe not stored yet: a placeholder Keyframe row is merged
    and filled in when the keyframe itself is added."""
    src, dst = kind.endpoints
    props = ", ".join(f"{c}: {c}" for c in [*extra_columns(kind), "props"])
    if kind is EdgeKind.SEEN_IN:
        head = f"MATCH (a:{src} {{id: src}}) MERGE (b:{dst} {{id: dst}}) ON CREATE SET b.label = ''"
    else:
        head = f"MATCH (a:{src} {{id: src}}), (b:{dst} {{id: dst}})"
    return f"LOAD FROM $rows {head} CREATE (a)-[:{kind.value} {{{props}}}]->(b) RETURN count(*)"
