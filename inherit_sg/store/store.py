"""MapStore: the one facade over a map directory (Kuzu graph, Kuzu search index,
LanceDB keyframes).

Writes need ``write=True`` (which holds the writer lock); each write call is one
transaction on ``graph.kuzu``, all or nothing, made by the one writer connection, after
which the search index replays it. Reads use their own per-thread connections inside
read-only transactions and may run while the writer works. What was measured about
Kuzu and LanceDB, and the designs that follow from it, is written down in
:mod:`~inherit_sg.store.search_index`, :mod:`~inherit_sg.store.text_index`,
:mod:`~inherit_sg.store.indexes`, :mod:`~inherit_sg.store.search`,
:mod:`~inherit_sg.store.embeddings` and :mod:`~inherit_sg.store.keyframes`.
"""

from __future__ import annotations

import contextlib
import logging
import threading
from collections.abc import Collection, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import TracebackType
from typing import Any

import kuzu
import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import InputError, MapCorruptError, MapError
from inherit_sg.model import ChangeSet, Edge, Keyframe, Node, SceneGraph, Session
from inherit_sg.store import graph_read, graph_write, node_write, text_index
from inherit_sg.store.compact import CompactReport, compact_graph_file
from inherit_sg.store.embeddings import VectorDelta
from inherit_sg.store.indexes import VectorIndex
from inherit_sg.store.keyframes import KeyframeBlobs
from inherit_sg.store.kuzu_graph import CypherResult, KuzuGraph
from inherit_sg.store.kuzu_util import rows
from inherit_sg.store.lock import WriterLock, is_locked, locked_error
from inherit_sg.store.mapdir import (
    GRAPH_FILE,
    INDEX_FILE,
    LANCE_DIR,
    LOCK_FILE,
    MapInfo,
    is_map_dir,
    read_map_info,
    write_map_info,
)
from inherit_sg.store.migrations import latest_version
from inherit_sg.store.open_probe import crashing_files, remember
from inherit_sg.store.search import VectorSearcher
from inherit_sg.store.search_index import SearchIndex, bump_generation, graph_generation
from inherit_sg.store.stats import MapStats, compute_stats, kuzu_bytes
from inherit_sg.store.store_open import (
    CREATE_LEFTOVERS,
    clear_leftovers,
    open_graph,
    open_index,
    remove_database,
)

Hits = list[tuple[str, float]]
log = logging.getLogger(__name__)


@dataclass
class WriteTx:
    """An open graph write transaction and what it changed (vector sets, tables whose
    searchable text changed)."""

    conn: kuzu.Connection
    deltas: dict[str, VectorDelta] = field(default_factory=dict)
    text_dirty: set[str] = field(default_factory=set)


class MapStore:
    """A map directory opened for reading or writing."""

    def __init__(
        self,
        path: Path,
        info: MapInfo,
        graph: KuzuGraph,
        index: SearchIndex | None,
        lock: WriterLock | None,
        config: Config,
    ) -> None:
        self.path = path
        self.info = info
        self._graph: KuzuGraph | None = graph
        self._index = index
        self._lock = lock
        self._config = config
        self._blobs = KeyframeBlobs(path / LANCE_DIR, info.image_feature_dim, lock is not None)
        self._blobs_checked = lock is None  # read-only stores never reconcile
        self._search = VectorSearcher(info.dims, config.store.vector_efs)
        self._text_lock = threading.RLock()  # full-text rebuilds vs. full-text reads
        self._index_ok = False  # the vector mirror matches the graph's generation

    # ------------------------------------------------------------ lifecycle
    @classmethod
    def create(cls, path: str | Path, config: Config | None = None) -> MapStore:
        """Create a new map at ``path`` (a missing or empty directory) and open it for
        writing. MapError when a map or other files are already there."""
        cfg = config or Config()
        root = Path(path).expanduser().absolute()
        if root.exists() and not root.is_dir():
            raise MapError(f"cannot create map {root}: it is a file")
        root.mkdir(parents=True, exist_ok=True)
        had_lock_file = (root / LOCK_FILE).exists()
        lock = WriterLock(root / LOCK_FILE, root)
        lock.acquire(cfg.store.lock_timeout_s)
        try:
            if is_map_dir(root):
                raise MapError(f"cannot create map {root}: a map already exists there")
            others = sorted(p.name for p in root.iterdir() if p.name not in CREATE_LEFTOVERS)
            if others:
                raise MapError(f"cannot create map {root}: directory is not empty ({others[0]})")
            clear_leftovers(root)
            info = MapInfo.from_config(cfg, latest_version())
            store = cls._assemble(root, info, lock, cfg, create=True)
            (root / LANCE_DIR).mkdir(exist_ok=True)
            write_map_info(root, info)  # last: from now on the directory is a map
        except BaseException:
            lock.release()
            if not had_lock_file and not is_map_dir(root):
                (root / LOCK_FILE).unlink(missing_ok=True)  # a refused create leaves nothing
            raise
        return store

    @classmethod
    def open(
        cls, path: str | Path, *, write: bool = False, config: Config | None = None
    ) -> MapStore:
        """Open an existing map. ``write=True`` takes the writer lock (MapLockedError
        naming the holder otherwise), applies pending schema migrations and repairs the
        search index after a crash. A read-only open changes nothing: a map older than
        this code raises SchemaVersionError asking for one writable open, a newer one
        always does. Vector sizes come from the map's ``map.json``, not from ``config``."""
        cfg = config or Config()
        root = Path(path).expanduser().absolute()
        info = read_map_info(root)
        lock: WriterLock | None = None
        if write:
            lock = WriterLock(root / LOCK_FILE, root)
            lock.acquire(cfg.store.lock_timeout_s)
        elif is_locked(root / LOCK_FILE):
            raise locked_error(root, root / LOCK_FILE)
        try:
            store = cls._assemble(root, info, lock, cfg, create=False)
        except BaseException:
            if lock is not None:
                lock.release()
            raise
        return store

    @classmethod
    def _assemble(
        cls, root: Path, info: MapInfo, lock: WriterLock | None, cfg: Config, *, create: bool
    ) -> MapStore:
        write = lock is not None
        # a damaged file can crash the engine as it opens: try each in a child first
        crashed = {} if create else crashing_files(root, [GRAPH_FILE, INDEX_FILE])
        graph = open_graph(root, info, write=write, create=create, crashed=crashed.get(GRAPH_FILE))
        index: SearchIndex | None = None
        try:
            index = open_index(root, info, write=write, crashed=crashed.get(INDEX_FILE))
            store = cls(root, info, graph, index, lock, cfg)
            store._check_index()
            if write and not create:
                store._sync_map_json(latest_version())
                store._refresh_text()  # finishes a rebuild a crash cut short
                store._mark_interrupted()
        except BaseException:
            if index is not None:
                index.close()
            graph.close()
            raise
        return store

    def _mark_interrupted(self) -> None:
        """Sessions that never ended were cut short (this open holds the writer lock, so
        none of them still runs): record them as interrupted."""
        cut = [s for s in self.sessions() if not s.state and s.finished is None]
        for session in cut:
            session.state = "interrupted"
            self.upsert_session(session)
            log.warning(
                "map %s: session %s (%s) was interrupted", self.path, session.id, session.name
            )

    def close(self) -> None:
        """Bring the full-text copies up to date (writers), close both databases
        (checkpointing them) and release the writer lock."""
        if self._graph is None:
            return
        try:
            if self.writable:
                self._refresh_text()
        finally:
            graph, self._graph = self._graph, None
            if self._index is not None:
                self._index.close()
            graph.close()
            if self._lock is not None:
                # what this writer leaves behind it wrote itself: no need to probe it
                remember(self.path, [GRAPH_FILE, INDEX_FILE])
                self._lock.release()

    def compact(self) -> CompactReport:
        """Rewrite ``graph.kuzu`` without the pages earlier writes left dead and build
        ``index.kuzu`` afresh (see :mod:`~inherit_sg.store.compact`), keeping the writer
        lock throughout; the store stays open. Nothing is lost: the rewrite replaces the
        graph only when every table holds the same rows."""
        if not self.writable:
            raise MapError(f"map {self.path} is open read-only; compacting needs write=True")
        self._refresh_text()
        if self._index is not None:
            self._index.close()
            self._index = None
        graph, self._graph = self._graph, None
        assert graph is not None
        graph.close()  # checkpoints: the sizes are those a closed map would have
        before = {n: kuzu_bytes(self.path / n) for n in (GRAPH_FILE, INDEX_FILE)}
        try:
            done = compact_graph_file(self.path / GRAPH_FILE)
            remove_database(self.path / INDEX_FILE)  # derived: built again below
        finally:
            self._graph = open_graph(self.path, self.info, write=True)
            self._index = open_index(self.path, self.info, write=True)
            self._index_ok = False
            self._check_index()
            self._refresh_text()
        after = {n: kuzu_bytes(self.path / n) for n in (GRAPH_FILE, INDEX_FILE)}
        return CompactReport(before, after, done.tables, done.rows)

    def __enter__(self) -> MapStore:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    @property
    def writable(self) -> bool:
        """Whether this store holds the writer lock."""
        return self._lock is not None and self._graph is not None

    @property
    def closed(self) -> bool:
        """Whether :meth:`close` was called."""
        return self._graph is None

    def _g(self) -> KuzuGraph:
        if self._graph is None:
            raise MapError(f"map {self.path} is closed")
        return self._graph

    def _sync_map_json(self, schema_version: int) -> None:
        sessions = [vars(s).copy() for s in self.sessions()]
        if self.info.sessions != sessions or self.info.schema_version != schema_version:
            self.info.sessions = sessions
            self.info.schema_version = schema_version
            write_map_info(self.path, self.info)

    def _check_index(self) -> None:
        """Compare the mirror's generation with the graph's; a writer re-syncs it."""
        with self._g().snapshot() as conn:
            want = graph_generation(conn)
        have = self._index.generation() if self._index is not None else None
        if have == want:
            self._index_ok = True
        elif self.writable and self._index is not None:
            with self._g().writer() as conn:
                fixed = self._index.resync(conn, want)
            log.info("map %s: search index re-synced (%d rows)", self.path, fixed)
            self._index_ok = True

    # --------------------------------------------------------------- writes
    @contextlib.contextmanager
    def _write(self) -> Iterator[WriteTx]:
        """One graph transaction under the writer lock; after the commit the search
        index replays its vector changes and caches of changed vector sets are dropped."""
        if not self.writable:
            raise MapError(f"map {self.path} is open read-only; open it with write=True")
        graph = self._g()
        with graph.writer() as wconn:
            tx = WriteTx(wconn)
            try:
                with graph.transaction():
                    yield tx
                    text_index.mark_dirty(wconn, tx.text_dirty)
                    bump_generation(wconn)
            except RuntimeError as exc:
                raise MapError(f"map {self.path}: write rolled back: {exc}") from None
            finally:
                self._search.invalidate(tx.deltas)
            self._replay(tx)

    def _replay(self, tx: WriteTx) -> None:
        """Mirror a committed write into the search index; if that fails the index is
        marked stale (searches fall back to exact scans) and re-synced on next open."""
        if self._index is None:
            return
        try:
            self._index.apply(tx.deltas, graph_generation(tx.conn), tx.conn)
        except RuntimeError as exc:
            self._index_ok = False
            log.warning(
                "map %s: search index update failed (%s); searching exactly", self.path, exc
            )

    def write_changes(self, graph: SceneGraph) -> ChangeSet:
        """Persist ``graph.flush_changes()`` in one transaction. On failure nothing is
        written and the changes are put back into the graph's log."""
        changes = graph.flush_changes()
        if changes.empty:
            return changes
        try:
            nodes = [graph.get(i) for i in changes.new_nodes | changes.updated_nodes if i in graph]
            new_edges = [e for k in changes.new_edges if (e := graph.edge(k)) is not None]
            self._persist(nodes, changes.removed_nodes, new_edges, changes.removed_edges)
        except BaseException:
            graph.restore_changes(changes)
            raise
        return changes

    def _persist(
        self,
        nodes: Sequence[Node],
        removed: Collection[str],
        new_edges: Sequence[Edge],
        removed_edges: Collection[tuple[str, str, str, str]],
    ) -> None:
        with self._g().writer() as wconn:
            plans = node_write.plan_upserts(wconn, nodes)
            with self._write() as tx:
                graph_write.delete_edges(tx.conn, removed_edges)
                node_write.merge_deltas(tx.deltas, node_write.delete_nodes(tx.conn, removed))
                upserted = node_write.write_upserts(tx.conn, plans, self.info.dims)
                node_write.merge_deltas(tx.deltas, upserted)
                graph_write.upsert_edges(tx.conn, new_edges)
                tx.text_dirty |= {node_write.table_of(i) for i in removed}
                tx.text_dirty |= {t for t, p in plans.items() if p.text_changed}

    def upsert_nodes(self, nodes: Iterable[Node]) -> None:
        """Insert or replace nodes (with their embeddings)."""
        self._persist(list(nodes), (), (), ())

    def delete_nodes(self, ids: Iterable[str]) -> None:
        """Delete nodes with their edges and embeddings."""
        self._persist((), list(ids), (), ())

    def upsert_edges(self, edges: Iterable[Edge]) -> None:
        """Insert or replace edges; InputError when an endpoint is missing."""
        self._persist((), (), list(edges), ())

    def delete_edges(self, keys: Iterable[tuple[str, str, str, str]]) -> None:
        """Delete edges by :attr:`Edge.key`."""
        self._persist((), (), (), list(keys))

    def add_keyframes(self, keyframes: Sequence[Keyframe]) -> None:
        """Store keyframes: metadata in Kuzu, JPEG and feature in LanceDB. LanceDB is
        written first and rolled back if the Kuzu transaction fails; rows a crash
        leaves only in LanceDB are removed on the next writable use."""
        if not keyframes:
            return
        for kf in keyframes:
            if not kf.id:
                raise InputError("keyframe without id")
        with self._g().writer():
            self._check_blobs()
            before = self._blobs.version()
            self._blobs.upsert(keyframes)
            try:
                with self._write() as tx:
                    graph_write.upsert_keyframes(tx.conn, keyframes)
            except BaseException:
                self._blobs.restore(before)
                raise

    def upsert_session(self, session: Session) -> None:
        """Insert or replace a session (Session node and map.json list)."""
        with self._write() as tx:
            graph_write.upsert_session(tx.conn, session)
        self._sync_map_json(self.info.schema_version)

    def _check_blobs(self) -> None:
        """Drop LanceDB rows whose keyframe never committed to Kuzu (after a crash)."""
        if self._blobs_checked:
            return
        with self._g().snapshot() as conn:
            stored = {r[0] for r in rows(conn, "MATCH (k:Keyframe) RETURN k.id")}
        orphans = sorted(self._blobs.ids() - stored)
        if orphans:
            self._blobs.delete(orphans)
        self._blobs_checked = True

    # ---------------------------------------------------------------- reads
    def load_graph(self) -> SceneGraph:
        """The whole scene graph with embeddings; its change log is empty. Stored values
        that cannot be decoded (a damaged graph.kuzu) raise MapCorruptError."""
        with self._g().snapshot() as conn:
            try:
                return graph_read.load_graph(conn, self.info.dims)
            except (UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
                raise MapCorruptError(
                    f"map {self.path}: {GRAPH_FILE} holds values that cannot be read "
                    f"({type(exc).__name__}: {str(exc)[:160]}); the file is damaged: restore "
                    "the map from a backup, or import an earlier export "
                    "(inherit-sg import FILE --map NEW)"
                ) from None

    def get_node(self, node_id: str) -> Node:
        """One node with its embeddings; NodeNotFoundError when absent."""
        with self._g().snapshot() as conn:
            return graph_read.get_node(conn, node_id, self.info.dims)

    def get_keyframe(self, keyframe_id: str, with_image: bool = False) -> Keyframe:
        """Keyframe metadata; with ``with_image`` also its JPEG bytes and global feature
        (from LanceDB). NodeNotFoundError when absent."""
        with self._g().snapshot() as conn:
            kf = graph_read.get_keyframe(conn, keyframe_id)
        if with_image:
            blob = self.keyframe_blob(keyframe_id)
            if blob is not None:
                kf.jpeg, kf.global_feature = blob
        return kf

    def keyframe_blob(self, keyframe_id: str) -> tuple[bytes | None, np.ndarray | None] | None:
        """(JPEG bytes, global feature) of a keyframe from LanceDB (recently used ones from
        memory), or None when it has none. The feature array is read-only."""
        self._check_blobs()
        return self._blobs.get(keyframe_id)

    def sessions(self) -> list[Session]:
        """All sessions, oldest first."""
        with self._g().snapshot() as conn:
            return graph_read.read_sessions(conn)

    def cypher_column(self, query: str, params: dict[str, Any] | None = None) -> list[Any]:
        """The first column of a read-only Cypher statement's result (retrieval's
        candidate steps: many ids at once, fetched through Arrow)."""
        return self._g().column(query, params)

    def cypher(
        self,
        query: str,
        params: dict[str, Any] | None = None,
        *,
        read_only: bool = True,
        max_rows: int | None = None,
        timeout_s: float | None = None,
    ) -> CypherResult:
        """Run one Cypher statement against the graph (the public tables), interrupted
        after ``timeout_s`` if given (QueryTimeoutError). Read-only by
        default (ReadOnlyViolationError for writes); ``read_only=False`` needs a
        writable store (the search index is re-synced after it) and may not create
        indexes in the graph database (see :mod:`~inherit_sg.store.search_index`)."""
        if read_only:
            return self._g().query(
                query, params, read_only=True, max_rows=max_rows, timeout_s=timeout_s
            )
        if not self.writable:
            raise MapError(f"map {self.path} is open read-only; open it with write=True")
        if any(w in query.upper() for w in ("CREATE_VECTOR_INDEX", "CREATE_FTS_INDEX")):
            raise InputError(
                "indexes may not be created in the graph database: with an index there "
                "Kuzu 0.11.3 corrupts position lists at checkpoint; the map's search "
                "indexes live in index.kuzu"
            )
        try:
            return self._g().query(
                query, params, read_only=False, max_rows=max_rows, timeout_s=timeout_s
            )
        finally:  # whatever it changed: re-check every derived structure
            self._search.invalidate()
            with self._g().transaction() as conn:
                text_index.mark_dirty(conn, text_index.TEXT_INDEXES)
                bump_generation(conn)
            self._check_index()

    def vector_search(
        self,
        index: str,
        vector: Sequence[float] | np.ndarray,
        k: int = 10,
        ids: Collection[str] | None = None,
    ) -> Hits:
        """(node id, cosine distance) of the ``k`` nearest vectors of ``index`` (one of
        object_visual, object_text, area_text, room_text), nearest first; ``ids``
        restricts the search to those nodes (exact)."""
        mirror = self._index if self._index_ok else None

        def hnsw(spec: VectorIndex, query: np.ndarray, k_: int) -> Hits | None:
            if mirror is None or not mirror.has_hnsw(spec):
                return None
            return mirror.hnsw_search(spec, query, k_, self._config.store.vector_efs)

        with self._g().snapshot() as conn:
            return self._search.search(conn, index, vector, k, ids, hnsw)

    def text_search(self, table: str, text: str, k: int = 10) -> Hits:
        """(node id, BM25 score) of full-text matches in Object (label, description),
        Area or Room (label, summary), best first."""
        if table not in text_index.TEXT_INDEXES:
            raise InputError(f"no full-text index on {table!r} (use Object, Area or Room)")
        if not text.strip() or k <= 0:
            return []
        with self._text_lock:
            self._refresh_text()
            if self._index is None:
                return []
            with self._index.db.snapshot() as conn:
                return text_index.search(conn, table, text, k)

    def _refresh_text(self) -> None:
        """Rebuild stale full-text copies (see :mod:`~inherit_sg.store.text_index`);
        a read-only store cannot, and says so when one is stale."""
        with self._text_lock:
            index = self._index
            with self._g().snapshot() as conn:
                if index is None:
                    stale = {t for t in text_index.TEXT_INDEXES if graph_read.count(conn, t)}
                else:
                    with index.db.snapshot() as iconn:
                        stale = text_index.stale_tables(conn, iconn, upgrade=self.writable)
            if not stale:
                return
            if not self.writable or index is None:
                raise MapError(
                    f"map {self.path}: the full-text index of {', '.join(sorted(stale))} is "
                    "out of date (its writer stopped before rebuilding it); open the map "
                    "once for writing to rebuild it"
                )
            with self._g().writer() as conn, index.db.writer() as iconn:
                text_index.rebuild(conn, iconn)

    def keyframe_search(self, vector: Sequence[float] | np.ndarray, k: int = 10) -> Hits:
        """(keyframe id, cosine distance) of the nearest keyframe global features."""
        self._check_blobs()
        hits = self._blobs.search(vector, k)
        with self._g().snapshot() as conn:
            stored = graph_read.existing_keyframes(conn, [h[0] for h in hits])
        return [h for h in hits if h[0] in stored]

    def stats(self) -> MapStats:
        """Rows per table, sessions and bytes on disk."""
        with self._g().snapshot() as conn:
            return compute_stats(conn, self.path)
