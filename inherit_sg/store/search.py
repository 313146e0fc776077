"""Vector search over the embedding tables.

Small sets are searched exactly: the vectors of a table with at most ``EXACT_MAX_ROWS``
rows are cached in memory (normalised, refreshed when the table changes) and scored
with one matrix product, which is both exact and faster than an HNSW walk at that
size. Larger tables use the HNSW index in ``index.kuzu`` (``QUERY_VECTOR_INDEX`` with
``efs``), or an exact cosine scan when that index cannot be trusted.

A candidate subset (``ids``) is always scored exactly: from the cache when there is
one; else, since Kuzu reads a vector by id slowly (0.15-1 ms) but scans fast, a small
subset is read by id and a large one is scored by one cosine scan inside Kuzu.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass

import kuzu
import numpy as np

from inherit_sg.errors import InputError
from inherit_sg.store.embeddings import as_vector, read_vectors
from inherit_sg.store.indexes import VECTOR_INDEXES, VectorIndex
from inherit_sg.store.kuzu_util import rows, scalar

EXACT_MAX_ROWS = 4096
# Read candidates by id when they are fewer than rows / this; else scan the table.
_LOOKUP_RATIO = 256
Hits = list[tuple[str, float]]


def _normalise(mat: np.ndarray) -> np.ndarray:
    norms = np.linalg.norm(mat, axis=1, keepdims=True)
    return mat / np.maximum(norms, 1e-12)


def exact_top_k(ids: Sequence[str], normed: np.ndarray, query: np.ndarray, k: int) -> Hits:
    """Cosine distances of ``query`` to the rows of ``normed``; the ``k`` smallest."""
    if len(ids) == 0 or k <= 0:
        return []
    q = query / max(float(np.linalg.norm(query)), 1e-12)
    dist = 1.0 - normed @ q
    k = min(k, len(ids))
    part = np.argpartition(dist, k - 1)[:k] if k < len(ids) else np.arange(len(ids))
    order = part[np.lexsort((np.asarray(ids, dtype=object)[part].astype(str), dist[part]))]
    return [(ids[i], float(dist[i])) for i in order]


@dataclass
class _Cached:
    generation: int
    ids: list[str]
    normed: np.ndarray | None  # None: too many rows, use the HNSW index
    rows: int


def _scan(
    conn: kuzu.Connection,
    spec: VectorIndex,
    dim: int,
    query: np.ndarray,
    k: int,
    wanted: set[str] | None,
) -> Hits:
    """Exact search by one cosine scan inside Kuzu (optionally over ``wanted`` ids)."""
    scored = rows(
        conn,
        f"MATCH (v:{spec.table}) RETURN v.id, "
        f"1.0 - array_cosine_similarity(v.vec, CAST($q AS FLOAT[{dim}]))",
        {"q": query.tolist()},
    )
    hits = sorted(
        (float(d), str(i)) for i, d in scored if d is not None and (wanted is None or i in wanted)
    )
    return [(i, d) for d, i in hits[:k]]


class VectorSearcher:
    """Answers nearest-neighbour queries for the four vector sets of one map."""

    def __init__(self, dims: dict[str, int], efs: int) -> None:
        self._dims = dims
        self._efs = efs
        self._generation = dict.fromkeys(VECTOR_INDEXES, 0)
        self._cache: dict[str, _Cached] = {}
        self._lock = threading.Lock()

    def invalidate(self, names: Collection[str] | None = None) -> None:
        """Mark vector sets as changed (all when ``names`` is None)."""
        with self._lock:
            for name in VECTOR_INDEXES if names is None else names:
                self._generation[name] += 1
                self._cache.pop(name, None)

    def spec(self, name: str) -> VectorIndex:
        """The vector set called ``name``; InputError naming the valid ones."""
        try:
            return VECTOR_INDEXES[name]
        except KeyError:
            known = ", ".join(sorted(VECTOR_INDEXES))
            raise InputError(f"unknown vector index {name!r} (known: {known})") from None

    def search(
        self,
        conn: kuzu.Connection,
        name: str,
        vector: Sequence[float] | np.ndarray,
        k: int,
        ids: Collection[str] | None,
        hnsw: Callable[[VectorIndex, np.ndarray, int], Hits | None],
    ) -> Hits:
        """(id, cosine distance) of the ``k`` nearest vectors, nearest first. ``conn``
        reads the graph's vectors; ``hnsw`` queries the index and answers None when it
        cannot be used (e.g. stale after a crash): large tables are then scanned."""
        spec = self.spec(name)
        dim = self._dims[spec.dim_key]
        query = as_vector(vector, dim, f"query vector for {name}")
        if k <= 0:
            return []
        cached = self._cached(conn, spec, dim)
        if ids is not None:
            return self._subset(conn, spec, dim, cached, query, k, set(ids))
        if cached.normed is not None:
            return exact_top_k(cached.ids, cached.normed, query, k)
        hits = hnsw(spec, query, min(int(k), cached.rows))
        return hits if hits is not None else _scan(conn, spec, dim, query, k, None)

    def _subset(
        self,
        conn: kuzu.Connection,
        spec: VectorIndex,
        dim: int,
        cached: _Cached,
        query: np.ndarray,
        k: int,
        wanted: set[str],
    ) -> Hits:
        if cached.normed is not None:
            keep = [i for i, node_id in enumerate(cached.ids) if node_id in wanted]
            return exact_top_k([cached.ids[i] for i in keep], cached.normed[keep], query, k)
        if len(wanted) * _LOOKUP_RATIO < cached.rows:
            found, mat = read_vectors(conn, spec, dim, sorted(wanted))
            return exact_top_k(found, _normalise(mat), query, k)
        return _scan(conn, spec, dim, query, k, wanted)

    def _cached(self, conn: kuzu.Connection, spec: VectorIndex, dim: int) -> _Cached:
        with self._lock:
            generation = self._generation[spec.name]
            hit = self._cache.get(spec.name)
        if hit is not None and hit.generation == generation:
            return hit
        count = int(scalar(conn, f"MATCH (v:{spec.table}) RETURN count(v)") or 0)
        if count > EXACT_MAX_ROWS:
            fresh = _Cached(generation, [], None, count)
        else:
            found, mat = read_vectors(conn, spec, dim)
            fresh = _Cached(generation, found, _normalise(mat), len(found))
        with self._lock:
            if self._generation[spec.name] == generation:
                self._cache[spec.name] = fresh
        return fresh
