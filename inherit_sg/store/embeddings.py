"""Embedding rows: one row per owning node in ``ObjectVisual``/``ObjectText``/
``AreaText``/``RoomText`` (id, vec, digest); ``None`` on the node means no row.

These tables in ``graph.kuzu`` are the truth; ``index.kuzu`` keeps an indexed mirror
(see :mod:`~inherit_sg.store.search_index`). Rows are only ever inserted or deleted,
never updated: a changed vector is a delete + insert, and a vector that did not change
is left alone. The comparison uses the stored digest because reading vectors back by
id is slow in Kuzu 0.11.3 (~0.15 ms a row, while a scan reads ~50k rows a second).
Each write returns a :class:`VectorDelta` that the mirror replays.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import kuzu
import numpy as np

from inherit_sg.errors import InputError, MapCorruptError
from inherit_sg.store.indexes import VectorIndex
from inherit_sg.store.kuzu_util import arrow_table, rows, run

if TYPE_CHECKING:
    import pyarrow as pa


def as_vector(value: Any, dim: int, what: str) -> np.ndarray:
    """``value`` as a finite float32 vector of length ``dim``; InputError otherwise."""
    vec = np.asarray(value, dtype=np.float32).reshape(-1)
    if vec.shape != (dim,):
        raise InputError(f"{what}: expected a vector of {dim} numbers, got shape {vec.shape}")
    if not np.all(np.isfinite(vec)):
        raise InputError(f"{what}: vector contains NaN or infinite values")
    return vec


def digest(vec: np.ndarray) -> str:
    """Short hash of a float32 vector's bytes."""
    return hashlib.blake2b(vec.tobytes(), digest_size=8).hexdigest()


@dataclass
class VectorDelta:
    """What one write did to one vector set: ids whose rows went away, rows added."""

    dropped: list[str] = field(default_factory=list)
    added: list[pa.Table] = field(default_factory=list)

    @property
    def empty(self) -> bool:
        """True when nothing changed."""
        return not self.dropped and not self.added


def vector_table(ids: Sequence[str], vecs: Sequence[np.ndarray], dim: int) -> pa.Table:
    """Arrow rows (id, vec FLOAT[dim], digest) for an embedding table."""
    import pyarrow as pa

    flat = np.stack(list(vecs)).reshape(-1) if len(vecs) else np.zeros(0, np.float32)
    return pa.table(
        {
            "id": pa.array(list(ids), type=pa.string()),
            "vec": pa.FixedSizeListArray.from_arrays(pa.array(flat, type=pa.float32()), dim),
            "digest": pa.array([digest(v) for v in vecs], type=pa.string()),
        }
    )


def insert_rows(conn: kuzu.Connection, table: str, rows_: pa.Table) -> None:
    """Append embedding rows (ids must not exist). Not COPY: ~4x faster, but in a
    transaction that also deleted rows it left other tables wrong (Kuzu 0.11.3)."""
    run(
        conn,
        f"LOAD FROM $rows CREATE (:{table} {{id: id, vec: vec, digest: digest}})",
        {"rows": rows_},
    )


def delete_rows(conn: kuzu.Connection, table: str, ids: Sequence[str]) -> None:
    """Remove the rows of ``ids`` (absent ones are ignored)."""
    if ids:
        run(conn, f"UNWIND $ids AS i MATCH (v:{table} {{id: i}}) DELETE v", {"ids": list(ids)})


def read_vectors(
    conn: kuzu.Connection, spec: VectorIndex, dim: int, ids: Sequence[str] | None = None
) -> tuple[list[str], np.ndarray]:
    """Ids and (n, dim) float32 matrix of stored vectors (all, or those of ``ids``)."""
    if ids is None:
        query, params = f"MATCH (v:{spec.table}) RETURN v.id AS id, v.vec AS vec", {}
    else:
        query = f"UNWIND $ids AS i MATCH (v:{spec.table} {{id: i}}) RETURN v.id AS id, v.vec AS vec"
        params = {"ids": list(ids)}
    table = arrow_table(conn, query, params)
    if table.num_rows == 0:
        return [], np.zeros((0, dim), dtype=np.float32)
    out_ids = [str(x) for x in table.column("id").to_pylist()]
    flat = table.column("vec").combine_chunks().flatten().to_numpy(zero_copy_only=False)
    if flat.size != len(out_ids) * dim:
        stored = flat.size // max(1, len(out_ids))
        raise MapCorruptError(
            f"{spec.table} holds vectors of {stored} numbers, but map.json says {dim} "
            f"({spec.dim_key}): set {spec.dim_key} to {stored} in map.json, or restore map.json "
            "from a backup"
        )
    return out_ids, np.asarray(flat, dtype=np.float32).reshape(len(out_ids), dim)


def read_digests(conn: kuzu.Connection, table: str) -> dict[str, str]:
    """id -> digest of every row of an embedding table."""
    found = arrow_table(conn, f"MATCH (v:{table}) RETURN v.id AS id, v.digest AS digest")
    return dict(
        zip(found.column("id").to_pylist(), found.column("digest").to_pylist(), strict=True)
    )


def write_vectors(
    conn: kuzu.Connection,
    spec: VectorIndex,
    dim: int,
    items: Sequence[tuple[str, np.ndarray | None]],
) -> VectorDelta:
    """Make the stored vectors of ``items`` match (None = no row)."""
    wanted = {
        nid: (as_vector(v, dim, f"{spec.name} vector of {nid}") if v is not None else None)
        for nid, v in items
    }
    stored = dict(
        rows(
            conn,
            f"UNWIND $ids AS i MATCH (v:{spec.table} {{id: i}}) RETURN v.id, v.digest",
            {"ids": list(wanted)},
        )
    )
    present = {i: v for i, v in wanted.items() if v is not None}
    digests = {i: digest(v) for i, v in present.items()}
    delta = VectorDelta(dropped=[i for i in stored if stored[i] != digests.get(i)])
    add = [i for i in digests if stored.get(i) != digests[i]]
    delete_rows(conn, spec.table, delta.dropped)
    if add:
        table = vector_table(add, [present[i] for i in add], dim)
        insert_rows(conn, spec.table, table)
        delta.added.append(table)
    return delta


def delete_vectors(conn: kuzu.Connection, spec: VectorIndex, ids: Sequence[str]) -> VectorDelta:
    """Remove the rows of ``ids``; the delta names them all (absent ones are harmless)."""
    delete_rows(conn, spec.table, ids)
    return VectorDelta(dropped=list(ids))
