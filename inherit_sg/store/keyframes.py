"""Keyframe images and global features in LanceDB (``lance/``, table ``keyframes``).

lancedb is imported only inside these methods: opening a map for a Cypher query or
``inherit-sg info`` never loads it, and the table is created with the first keyframe
(an empty ``lance/`` folder is a map without keyframes). Rows are upserted by id (``merge_insert``), so a
keyframe written twice is stored once. Searching is a flat scan below
``INDEX_MIN_ROWS`` rows (a few ms at that size, and IVF needs rows to train on); once
the table is larger an IVF_HNSW_SQ index (cosine) is built, later rows are still found
by LanceDB's scan of unindexed data until ``optimize`` folds them in.
"""

from __future__ import annotations

import functools
import threading
from collections import OrderedDict
from collections.abc import Callable, Sequence
from datetime import timedelta
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from inherit_sg.errors import InheritSGError, InputError, MapCorruptError
from inherit_sg.model import Keyframe
from inherit_sg.store.embeddings import as_vector

if TYPE_CHECKING:
    import pyarrow as pa

TABLE = "keyframes"
INDEX_MIN_ROWS = 10_000
_COMPACT_AFTER_FRAGMENTS = 32
# JPEG bytes and features kept in memory for repeated lookups (verification of the same
# best views): a Lance lookup costs ~5 ms, a house's keyframes ~8 MB in all.
BLOB_CACHE_BYTES = 32 << 20


F = TypeVar("F", bound=Callable[..., Any])


def _clear_damage(method: F) -> F:
    """Turn what LanceDB raises on a damaged table (a deleted or truncated data file) into
    a MapCorruptError that names the table and how to recover."""

    @functools.wraps(method)
    def wrapper(self: KeyframeBlobs, *args: Any, **kwargs: Any) -> Any:
        try:
            return method(self, *args, **kwargs)
        except InheritSGError:
            raise
        except Exception as exc:  # lance and arrow errors have no common base
            first = str(exc).splitlines()[0][:300] if str(exc) else type(exc).__name__
            raise MapCorruptError(
                f"the keyframe table {self.path / (TABLE + '.lance')} is damaged ({first}). "
                "The scene graph is intact: `inherit-sg export --map MAP --no-images OUT.json` "
                "then `inherit-sg import OUT.json --map NEW` makes a map without keyframe "
                "pictures"
            ) from None

    return wrapper  # type: ignore[return-value]


def _id_column(tbl: Any, *, with_row_id: bool = False) -> pa.Table:
    """Every row's ``id`` (and Lance ``_rowid`` when asked) of the table ``tbl``."""
    query = tbl.search().select(["id"]).with_row_id(with_row_id)
    return query.limit(max(1, int(tbl.count_rows()))).to_arrow()


def _quote(ids: Sequence[str]) -> str:
    return ", ".join("'" + i.replace("'", "''") + "'" for i in ids)


Blob = tuple[bytes | None, np.ndarray | None]


class BlobCache:
    """Least-recently-used (jpeg, feature) pairs by keyframe id, at most ``max_bytes``
    of JPEG and feature data; thread-safe (REST workers share a store)."""

    def __init__(self, max_bytes: int = BLOB_CACHE_BYTES) -> None:
        self.max_bytes = max_bytes
        self._items: OrderedDict[str, tuple[Blob, int]] = OrderedDict()
        self._bytes = 0
        self._lock = threading.Lock()

    def get(self, keyframe_id: str) -> Blob | None:
        """The cached pair, or None."""
        with self._lock:
            hit = self._items.get(keyframe_id)
            if hit is None:
                return None
            self._items.move_to_end(keyframe_id)
            return hit[0]

    def put(self, keyframe_id: str, blob: Blob) -> None:
        """Keep ``blob``, dropping the least recently used pairs beyond the budget."""
        jpeg, feat = blob
        size = len(jpeg or b"") + (feat.nbytes if feat is not None else 0)
        if size > self.max_bytes:
            return
        with self._lock:
            old = self._items.pop(keyframe_id, None)
            if old is not None:
                self._bytes -= old[1]
            self._items[keyframe_id] = (blob, size)
            self._bytes += size
            while self._bytes > self.max_bytes:
                _, (_, dropped) = self._items.popitem(last=False)
                self._bytes -= dropped

    def clear(self) -> None:
        """Forget everything (the table was written, deleted from or compacted)."""
        with self._lock:
            self._items.clear()
            self._bytes = 0


class KeyframeBlobs:
    """The LanceDB side of keyframes: JPEG bytes and global feature by keyframe id."""

    def __init__(self, path: Path, feature_dim: int, writable: bool) -> None:
        self.path = path
        self.feature_dim = feature_dim
        self.writable = writable
        self._table: Any = None
        # keyframe id -> Lance row id, read once: a lookup by row id takes about half
        # the time of a filtered scan (3.5 against 7.4 ms on a 311-keyframe house);
        # every use checks the row's id, and writes, deletes and compaction forget it
        self._row_ids: dict[str, int] | None = None
        # keyframe id -> (jpeg, feature): a keyframe's pixels do not change under its id,
        # and this process's writes clear it
        self._cache = BlobCache()

    def _forget(self) -> None:
        """Drop the row-id map and the cached blobs (the table changed)."""
        self._row_ids = None
        self._cache.clear()

    def schema(self) -> pa.Schema:
        """Arrow schema of the ``keyframes`` table."""
        import pyarrow as pa

        return pa.schema(
            [
                pa.field("id", pa.string(), nullable=False),
                pa.field("session_id", pa.string()),
                pa.field("timestamp", pa.float64()),
                pa.field("frame_index", pa.int64()),
                pa.field("floor_id", pa.string()),
                pa.field("pose", pa.list_(pa.float64(), 16)),
                pa.field("width", pa.int32()),
                pa.field("height", pa.int32()),
                pa.field("jpeg", pa.binary()),
                pa.field("feature", pa.list_(pa.float32(), self.feature_dim)),
            ]
        )

    def _tbl(self) -> Any:
        """The LanceDB table; created on first use when writable, None when absent."""
        if self._table is None:
            if not self.writable and not (self.path / f"{TABLE}.lance").exists():
                return None
            import lancedb

            db = lancedb.connect(str(self.path))
            self._table = db.create_table(TABLE, schema=self.schema(), exist_ok=True)
        return self._table

    def _rows(self, keyframes: Sequence[Keyframe]) -> pa.Table:
        import pyarrow as pa

        feats = [
            as_vector(k.global_feature, self.feature_dim, f"global feature of keyframe {k.id}")
            if k.global_feature is not None
            else None
            for k in keyframes
        ]
        return pa.table(
            {
                "id": [k.id for k in keyframes],
                "session_id": [k.session_id for k in keyframes],
                "timestamp": [float(k.timestamp) for k in keyframes],
                "frame_index": [int(k.frame_index) for k in keyframes],
                "floor_id": [k.floor_id for k in keyframes],
                "pose": [list(k.pose.matrix16) for k in keyframes],
                "width": [int(k.width) for k in keyframes],
                "height": [int(k.height) for k in keyframes],
                "jpeg": [k.jpeg for k in keyframes],
                "feature": [f.tolist() if f is not None else None for f in feats],
            },
            schema=self.schema(),
        )

    @_clear_damage
    def version(self) -> int:
        """Current table version (to roll back a failed multi-store write)."""
        return int(self._tbl().version)  # writable only

    @_clear_damage
    def restore(self, version: int) -> None:
        """Make ``version`` the current state again."""
        self._forget()
        self._tbl().restore(version)

    @_clear_damage
    def upsert(self, keyframes: Sequence[Keyframe]) -> None:
        """Insert or replace rows by keyframe id."""
        if not keyframes:
            return
        latest = list({k.id: k for k in keyframes}.values())
        tbl = self._tbl()
        rows = self._rows(latest)
        self._forget()
        # a keyframe imported without its feature keeps a null one (not a "bad vector")
        tbl.merge_insert("id").when_matched_update_all().when_not_matched_insert_all().execute(
            rows, on_bad_vectors="null"
        )
        self._maintain(tbl)

    def _maintain(self, tbl: Any) -> None:
        stats = tbl.stats()
        frags = stats.get("fragment_stats", {}).get("num_small_fragments", 0)
        if frags >= _COMPACT_AFTER_FRAGMENTS:
            tbl.optimize(cleanup_older_than=timedelta(minutes=5))
        if not tbl.list_indices() and stats.get("num_rows", 0) >= INDEX_MIN_ROWS:
            tbl.create_index(
                metric="cosine", vector_column_name="feature", index_type="IVF_HNSW_SQ"
            )

    @_clear_damage
    def delete(self, ids: Sequence[str]) -> None:
        """Delete rows by id (absent ones are ignored)."""
        self._forget()
        for start in range(0, len(ids), 500):
            self._tbl().delete(f"id IN ({_quote(ids[start : start + 500])})")

    @_clear_damage
    def ids(self) -> set[str]:
        """All stored keyframe ids."""
        tbl = self._tbl()
        if tbl is None:
            return set()
        return {str(i) for i in _id_column(tbl).column("id").to_pylist()}

    def _by_row_id(self, tbl: Any, keyframe_id: str) -> dict[str, Any] | None:
        """The row of ``keyframe_id`` looked up by its Lance row id; None when the id
        is not known or the row there is another one (the table changed since)."""
        if self._row_ids is None:
            found = _id_column(tbl, with_row_id=True)
            ids, rids = found.column("id").to_pylist(), found.column("_rowid").to_pylist()
            self._row_ids = {str(i): int(r) for i, r in zip(ids, rids, strict=True)}
        rid = self._row_ids.get(keyframe_id)
        if rid is None:
            return None
        try:
            rows = tbl.take_row_ids([rid]).select(["id", "jpeg", "feature"]).to_arrow()
        except Exception:  # a row id that compaction or a delete removed
            rows = None
        if rows is None or rows.num_rows != 1 or rows.column("id")[0].as_py() != keyframe_id:
            self._forget()
            return None
        return rows.to_pylist()[0]

    @_clear_damage
    def get(self, keyframe_id: str) -> Blob | None:
        """(jpeg, feature) of one keyframe, or None when it has no row."""
        cached = self._cache.get(keyframe_id)
        if cached is not None:
            return cached
        tbl = self._tbl()
        if tbl is None:
            return None
        row = self._by_row_id(tbl, keyframe_id)
        if row is None:
            found = (
                tbl.search()
                .where(f"id = {_quote([keyframe_id])}")
                .select(["jpeg", "feature"])
                .limit(1)
                .to_arrow()
                .to_pylist()
            )
            if not found:
                return None
            row = found[0]
            self._forget()  # a row the id map did not know: another writer's
        feat = row["feature"]
        vec = np.asarray(feat, dtype=np.float32) if feat is not None else None
        if vec is not None:
            vec.setflags(write=False)  # shared with the cache
        blob = row["jpeg"], vec
        self._cache.put(keyframe_id, blob)
        return blob

    @_clear_damage
    def search(self, vector: Sequence[float] | np.ndarray, k: int) -> list[tuple[str, float]]:
        """(id, cosine distance) of the ``k`` nearest keyframe features."""
        query = as_vector(vector, self.feature_dim, "keyframe query vector")
        if k <= 0:
            return []
        if k > 100_000:
            raise InputError(f"k={k} is too large for a keyframe search")
        tbl = self._tbl()
        if tbl is None:
            return []
        found = (
            tbl.search(query.tolist(), vector_column_name="feature")
            .distance_type("cosine")
            .select(["id"])
            .limit(k)
            .to_arrow()
        )
        ids = found.column("id").to_pylist()
        dists = found.column("_distance").to_pylist()
        return sorted(
            ((str(i), float(d)) for i, d in zip(ids, dists, strict=True)),
            key=lambda h: (h[1], h[0]),
        )
