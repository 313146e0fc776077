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

from inherit_sg.store import search as exact_search
from inherit_sg.store.embeddings import (
    VectorDelta,
    delete_rows,
    insert_rows,
    read_digests,
    read_vectors,
)
from inherit_sg.store.graph_read import count
from inherit_sg.store.indexes import VECTOR_INDEXES, VectorIndex, ensure_vector_indexes
from inherit_sg.store.kuzu_graph import KuzuGraph
from inherit_sg.store.kuzu_util import index_names, rows, run, scalar

INDEX_FORMAT = 2  # bump when this database's layout changes: it is then rebuilt
META_TABLE = "_IndexMeta"
_MIRROR = "mirror:"  # meta name prefix of a vector set the mirror holds


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

    def _mirrored(self, conn: kuzu.Connection) -> set[str]:
        """Vector sets this mirror holds (the others are searched exactly)."""
        found = rows(conn, f"MATCH (m:{META_TABLE}) WHERE m.value = 1 RETURN m.name")
        return {str(r[0])[len(_MIRROR) :] for r in found if str(r[0]).startswith(_MIRROR)}

    def apply(
        self,
        deltas: Mapping[str, VectorDelta],
        generation: int,
        graph_conn: kuzu.Connection | None = None,
    ) -> None:
        """Replay one graph write's vector changes, then build missing HNSW indexes. A
        vector set is mirrored only once it holds more than ``EXACT_MAX_ROWS`` rows (it is
        then copied whole from ``graph_conn``); smaller sets are searched exactly over
        the graph's vectors and cost the mirror nothing."""
        with self.db.transaction() as conn:
            mirrored = self._mirrored(conn)
            for name, delta in deltas.items():
                spec = VECTOR_INDEXES[name]
                if name not in mirrored:
                    if (
                        graph_conn is None
                        or count(graph_conn, spec.table) <= exact_search.EXACT_MAX_ROWS
                    ):
                        continue
                    delta = self._whole(graph_conn, spec, read_digests(graph_conn, spec.table))
                    delta.dropped = list(read_digests(conn, spec.table))
                    self._set_meta(conn, _MIRROR + name, 1)
                delete_rows(conn, spec.table, delta.dropped)
                for added in delta.added:
                    insert_rows(conn, spec.table, added)
            self._set_meta(conn, "format", INDEX_FORMAT)
            self._set_meta(conn, "generation", generation)
        with self.db.writer() as conn:
            ensure_vector_indexes(conn)

    def _whole(
        self, graph_conn: kuzu.Connection, spec: VectorIndex, truth: Mapping[str, str]
    ) -> VectorDelta:
        """The rows of ``truth``'s ids, read from the graph, as one delta."""
        import pyarrow as pa

        dim = self.dims[spec.dim_key]
        delta = VectorDelta()
        ids_wanted = list(truth)
        for start in range(0, len(ids_wanted), 20_000):
            ids, mat = read_vectors(graph_conn, spec, dim, ids_wanted[start : start + 20_000])
            if ids:
                vecs = pa.FixedSizeListArray.from_arrays(
                    pa.array(mat.reshape(-1), type=pa.float32()), dim
                )
                digests = [truth[i] for i in ids]
                delta.added.append(pa.table({"id": ids, "vec": vecs, "digest": digests}))
        return delta

    def resync(self, graph_conn: kuzu.Connection, generation: int) -> int:
        """Make the mirror equal to the graph's vectors (by digest) for the vector sets
        it holds, and empty for the small ones; returns the number of rows fixed."""
        deltas: dict[str, VectorDelta] = {}
        with self.db.snapshot() as conn:
            mirror = {n: read_digests(conn, s.table) for n, s in VECTOR_INDEXES.items()}
            mirrored = self._mirrored(conn)
        fixed = 0
        mark: list[str] = []
        for name, spec in VECTOR_INDEXES.items():
            truth = read_digests(graph_conn, spec.table)
            have = mirror[name]
            if name not in mirrored and len(truth) <= exact_search.EXACT_MAX_ROWS:
                deltas[name] = VectorDelta(dropped=list(have))  # maps made before the rule
                fixed += len(have)
                continue
            if name not in mirrored:
                mark.append(name)
            drop = [i for i in have if truth.get(i) != have[i]]
            add = {i: d for i, d in truth.items() if have.get(i) != d}
            fixed += len(drop) + len(add)
            delta = deltas[name] = self._whole(graph_conn, spec, add)
            delta.dropped = drop
        if mark:  # marked first: apply then replays their deltas as it does for any held set
            with self.db.transaction() as conn:
                for name in mark:
                    self._set_meta(conn, _MIRROR + name, 1)
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
