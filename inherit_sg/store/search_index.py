"""The search index of a map: ``index.kuzu``, a second Kuzu database derived from
``graph.kuzu``, holding HNSW-indexed copies of the embedding tables and the full-text
doc tables.

Why a second database (measured with Kuzu 0.11.3): once any vector or full-text index
exists in a database, a checkpoint after rows were both updated in a list column
(``position``, ``bbox_min``…) and appended in the same checkpoint interval gives the
appended rows wrong list values. ``graph.kuzu`` therefore holds no index at all, and
this database only ever sees inserts, deletes and whole-table rebuilds, never updates.

The graph is the truth. Each write transaction there bumps a generation counter; after
the commit the store replays the write's vector changes here and records the same
generation. A crash in between leaves the generations different: a writable open then
re-syncs by comparing vector digests, and a read-only store searches the graph's
vectors exactly instead (correct, slower).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import kuzu
import numpy as np

from inherit_sg.store.embeddings import (
    VectorDelta,
    delete_rows,
    insert_rows,
    read_digests,
    read_vectors,
)
from inherit_sg.store.indexes import VECTOR_INDEXES, VectorIndex, ensure_vector_indexes
from inherit_sg.store.kuzu_graph import KuzuGraph
from inherit_sg.store.kuzu_util import index_names, rows, run, scalar

INDEX_FORMAT = 1  # bump when this database's layout changes: it is then rebuilt
META_TABLE = "_IndexMeta"


def graph_generation(conn: kuzu.Connection) -> int:
    """Write generation recorded in ``graph.kuzu``."""
    return int(scalar(conn, "MATCH (s:_State {name: 'generation'}) RETURN s.value") or 0)


def bump_generation(conn: kuzu.Connection) -> None:
    """Inside a graph write transaction: one more write."""
    run(
        conn,
        "MERGE (s:_State {name: 'generation'}) "
        "ON CREATE SET s.value = 1 ON MATCH SET s.value = s.value + 1",
    )


class SearchIndex:
    """``index.kuzu``: vector mirror with HNSW indexes, and full-text doc tables."""

    def __init__(self, file: Path, dims: Mapping[str, int], *, read_only: bool) -> None:
        self.file = file
        self.dims = dims
        self.db = KuzuGraph(file, read_only=read_only)
        if not read_only:
            with self.db.writer() as conn:
                self._init_schema(conn)

    def _init_schema(self, conn: kuzu.Connection) -> None:
        run(
            conn,
            f"CREATE NODE TABLE IF NOT EXISTS {META_TABLE}(name STRING PRIMARY KEY, value INT64)",
        )
        for spec in VECTOR_INDEXES.values():
            dim = self.dims[spec.dim_key]
            run(
                conn,
                f"CREATE NODE TABLE IF NOT EXISTS {spec.table}"
                f"(id STRING PRIMARY KEY, vec FLOAT[{dim}], digest STRING)",
            )

    def _meta(self, conn: kuzu.Connection, name: str) -> int | None:
        if META_TABLE not in {r[0] for r in rows(conn, "CALL SHOW_TABLES() RETURN name")}:
            return None
        value = scalar(conn, f"MATCH (m:{META_TABLE} {{name: $n}}) RETURN m.value", {"n": name})
        return None if value is None else int(value)

    def generation(self) -> int | None:
        """Graph generation this mirror reflects (None when never synced)."""
        with self.db.snapshot() as conn:
            if self._meta(conn, "format") != INDEX_FORMAT:
                return None
            return self._meta(conn, "generation")

    def _set_meta(self, conn: kuzu.Connection, name: str, value: int) -> None:
        run(conn, f"MERGE (m:{META_TABLE} {{name: $n}}) SET m.value = $v", {"n": name, "v": value})

    def apply(self, deltas: Mapping[str, VectorDelta], generation: int) -> None:
        """Replay one graph write's vector changes, then build missing HNSW indexes."""
        with self.db.transaction() as conn:
            for name, delta in deltas.items():
                table = VECTOR_INDEXES[name].table
                delete_rows(conn, table, delta.dropped)
                for added in delta.added:
                    insert_rows(conn, table, added)
            self._set_meta(conn, "format", INDEX_FORMAT)
            self._set_meta(conn, "generation", generation)
        with self.db.writer() as conn:
            ensure_vector_indexes(conn)

    def resync(self, graph_conn: kuzu.Connection, generation: int) -> int:
        """Make the mirror equal to the graph's vectors (by digest); returns the number
        of rows fixed."""
        import pyarrow as pa

        deltas: dict[str, VectorDelta] = {}
        with self.db.snapshot() as conn:
            mirror = {n: read_digests(conn, s.table) for n, s in VECTOR_INDEXES.items()}
        fixed = 0
        for name, spec in VECTOR_INDEXES.items():
            truth = read_digests(graph_conn, spec.table)
            have = mirror[name]
            drop = [i for i in have if truth.get(i) != have[i]]
            add = [i for i in truth if have.get(i) != truth[i]]
            fixed += len(drop) + len(add)
            delta = deltas[name] = VectorDelta(dropped=drop)
            for start in range(0, len(add), 20_000):
                ids, mat = read_vectors(
                    graph_conn, spec, self.dims[spec.dim_key], add[start : start + 20_000]
                )
                if ids:
                    vecs = pa.FixedSizeListArray.from_arrays(
                        pa.array(mat.reshape(-1), type=pa.float32()), self.dims[spec.dim_key]
                    )
                    digests = [truth[i] for i in ids]
                    delta.added.append(pa.table({"id": ids, "vec": vecs, "digest": digests}))
        self.apply(deltas, generation)
        return fixed

    def has_hnsw(self, spec: VectorIndex) -> bool:
        """Whether the HNSW index of ``spec`` exists."""
        with self.db.snapshot() as conn:
            return (spec.table, spec.index) in index_names(conn)

    def hnsw_search(
        self, spec: VectorIndex, query: np.ndarray, k: int, efs: int
    ) -> list[tuple[str, float]]:
        """(id, cosine distance) from the HNSW index, nearest first."""
        with self.db.snapshot() as conn:
            hits = rows(
                conn,
                f"CALL QUERY_VECTOR_INDEX('{spec.table}', '{spec.index}', $q, $k, efs := $efs) "
                "RETURN node.id, distance ORDER BY distance, node.id",
                {"q": query.tolist(), "k": int(k), "efs": max(efs, int(k))},
            )
        return [(str(i), float(d)) for i, d in hits]

    def close(self) -> None:
        """Close the database."""
        self.db.close()
