"""MapService: the one facade that owns a map directory. The CLI and the REST API are
thin faces over it (DESIGN.md §3)."""

from __future__ import annotations

import json
import threading
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from inherit_sg.config import Config, load_config
from inherit_sg.errors import InputError, MapError
from inherit_sg.store import CypherResult, MapStore
from inherit_sg.store.cypher_worker import CypherWorker
from inherit_sg.store.mapdir import GRAPH_FILE
from inherit_sg.store.skip_guard import check_plain_skip

if TYPE_CHECKING:
    import numpy as np

    from inherit_sg.mapping.live import LiveSession
    from inherit_sg.reads.bev import BevTransform
    from inherit_sg.reads.models import (
        AreaPage,
        FloorPage,
        Hierarchy,
        ObjectDetail,
        ObjectPage,
        RoomPage,
        Scene3D,
    )
    from inherit_sg.retrieval.conversation import Conversation
    from inherit_sg.retrieval.result import QueryResult
    from inherit_sg.retrieval.viewer import ViewerPose
    from inherit_sg.store.compact import CompactReport

EXPORT_FORMAT = "inherit-sg-map"
EXPORT_VERSION = 1


def parse_params(items: Iterable[str]) -> dict[str, Any]:
    """``NAME=JSON`` pairs into a parameter dict (plain strings when not JSON)."""
    params: dict[str, Any] = {}
    for item in items:
        name, sep, raw = item.partition("=")
        if not sep or not name.strip().isidentifier():
            raise InputError(f"parameter {item!r}: expected NAME=VALUE")
        try:
            params[name.strip()] = json.loads(raw)
        except json.JSONDecodeError:
            params[name.strip()] = raw
    return params


class MapService:
    """Operations on one map directory, shared by the CLI and the REST service."""

    def __init__(self, store: MapStore, config: Config) -> None:
        self.store = store
        self.config = config
        self._cypher_worker: CypherWorker | None = None
        self._worker_lock = threading.Lock()

    @classmethod
    def open(
        cls, path: str | Path, *, write: bool = False, config: Config | None = None
    ) -> MapService:
        """Open an existing map (read-only unless ``write``)."""
        cfg = config or load_config()
        return cls(MapStore.open(path, write=write, config=cfg), cfg)

    def close(self) -> None:
        """Release the map (and stop its Cypher worker)."""
        if self._cypher_worker is not None:
            self._cypher_worker.close()
            self._cypher_worker = None
        self.store.close()

    def __enter__(self) -> MapService:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------------ reads
    def stats(self) -> dict[str, Any]:
        """Counts per table, sessions and bytes on disk, with the map's identity, the
        vocabulary it was mapped with and its label space."""
        from inherit_sg.exchange.records import session_to_record

        stats = self.store.stats().to_dict()
        info = self.store.info
        return {
            "path": str(self.store.path),
            "schema_version": info.schema_version,
            "created": info.created,
            "text_embedder": info.text_embedder,
            "visual_encoder": info.visual_encoder,
            "vocabulary": info.vocabulary,
            "label_space": info.label_space,
            **stats,
            "sessions": [session_to_record(s) for s in self.store.sessions()],
            "bytes": {
                "graph": stats["bytes_graph"],
                "keyframes": stats["bytes_lance"],
                "total": stats["bytes_total"],
            },
        }

    def floors(self, *, label: str | None = None, limit: int = 100, offset: int = 0) -> FloorPage:
        """A page of floors ordered by id, optionally by label, with room and object counts."""
        from inherit_sg.reads.listing import list_floors

        return list_floors(self, label=label, limit=limit, offset=offset)

    def rooms(
        self,
        *,
        floor: str | None = None,
        label: str | None = None,
        limit: int = 100,
        offset: int = 0,
    ) -> RoomPage:
        """A page of rooms ordered by id, filtered by floor id and label, each with its
        inferred types and child counts."""
        from inherit_sg.reads.listing import list_rooms

        return list_rooms(self, floor=floor, label=label, limit=limit, offset=offset)

    def areas(
        self,
        *,
        floor: str | None = None,
        room: str | None = None,
        label: str | None = None,
        limit: int = 100,
        offset: int = 0,
    ) -> AreaPage:
        """A page of functional areas ordered by id, filtered by floor, room and label."""
        from inherit_sg.reads.listing import list_areas

        return list_areas(self, floor=floor, room=room, label=label, limit=limit, offset=offset)

    def objects(
        self,
        *,
        floor: str | None = None,
        room: str | None = None,
        label: str | None = None,
        limit: int = 100,
        offset: int = 0,
    ) -> ObjectPage:
        """A page of objects ordered by id, filtered by floor id, room id and label."""
        from inherit_sg.reads.objects import list_objects

        return list_objects(self, floor=floor, room=room, label=label, limit=limit, offset=offset)

    def object(self, object_id: str) -> ObjectDetail:
        """One object with its relations, its area → room → floor path and its keyframes;
        NodeNotFoundError when there is none."""
        from inherit_sg.reads.objects import get_object

        return get_object(self, object_id)

    def hierarchy(self) -> Hierarchy:
        """The floors → rooms → areas → objects tree (ids and labels)."""
        from inherit_sg.reads.hierarchy import build_hierarchy

        return build_hierarchy(self)

    def scene3d(self, *, floor_id: str | None = None, near: bool = False) -> Scene3D:
        """Floors, room footprints, object boxes and graph edges for a 3D view (one
        floor, or all); ``near`` adds the numerous ``near`` relations."""
        from inherit_sg.reads.scene3d import build_scene3d

        return build_scene3d(self, floor_id=floor_id, near=near)

    def bev_png(self, floor_id: str, *, stored: bool = False) -> tuple[bytes, BevTransform | None]:
        """One floor's bird's-eye view as PNG bytes: drawn from the graph with its
        pixel ↔ world transform, or (``stored``) the picture ``map build`` wrote, whose
        transform is not recorded."""
        from inherit_sg.reads import pictures

        if stored:
            return pictures.stored_bev(self, floor_id), None
        return pictures.graph_bev(self, floor_id)

    def keyframe_jpeg(self, keyframe_id: str) -> bytes:
        """The stored JPEG of one keyframe; NodeNotFoundError when there is none."""
        from inherit_sg.reads.pictures import keyframe_jpeg

        return keyframe_jpeg(self, keyframe_id)

    def best_view(self, node_id: str) -> str:
        """The keyframe id of an object's or a room's best view."""
        from inherit_sg.reads.pictures import best_view

        return best_view(self, node_id)

    def cypher(
        self,
        query: str,
        params: dict[str, Any] | None = None,
        *,
        max_rows: int | None = 1000,
        timeout_s: float | None = None,
    ) -> CypherResult:
        """Run a read-only Cypher query (stopped after ``timeout_s``, if given). On a map
        open read-only the statement runs in a worker process, so a statement that
        crashes the database engine costs only itself (a CypherError) and the next one
        runs in a fresh worker (:mod:`~inherit_sg.store.cypher_worker`); on a map open for
        writing (Kuzu then admits no other process) it runs in this process, and a SKIP
        must then be a plain number or a parameter (:func:`check_plain_skip`)."""
        if self.store.writable:
            check_plain_skip(query)
            return self.store.cypher(
                query, params, read_only=True, max_rows=max_rows, timeout_s=timeout_s
            )
        with self._worker_lock:
            if self._cypher_worker is None:
                self._cypher_worker = CypherWorker(self.store.path / GRAPH_FILE)
            worker = self._cypher_worker
        return worker.run(query, params, max_rows=max_rows, timeout_s=timeout_s)

    def query(
        self,
        text: str,
        *,
        conversation: Conversation | None = None,
        verify: bool | None = None,
        top_k: int | None = None,
        explain: bool = False,
        image: np.ndarray | None = None,
        viewer: ViewerPose | None = None,
    ) -> QueryResult:
        """Answer a natural-language request (the query result JSON of DESIGN.md §4 is
        ``.to_dict()``), optionally with a picture of the object (RGB uint8) and the
        robot's pose (``viewer``: "left", "right", ordinals are then seen from it); one
        engine per service keeps the map in memory between calls."""
        from inherit_sg.retrieval.engine import QueryEngine

        engine: QueryEngine | None = getattr(self, "_query_engine", None)
        if engine is None:
            engine = QueryEngine(self.store, self.config)
            self._query_engine = engine
        return engine.query(
            text,
            conversation=conversation,
            verify=verify,
            top_k=top_k,
            explain=explain,
            image=image,
            viewer=viewer,
        )

    def live_session(
        self, name: str | None = None, *, frame_queue: int = 8, flush_every: int = 20
    ) -> LiveSession:
        """Start a live mapping session on this map (opened with ``write=True``): frames
        go in through :meth:`LiveSession.submit`, queries keep working on this service
        and see the session's objects after each flush (every ``flush_every`` keyframes
        and every global update)."""
        from inherit_sg.mapping.live import LiveSession

        return LiveSession(
            self.store, self.config, name=name, frame_queue=frame_queue, flush_every=flush_every
        )

    # ------------------------------------------------------------ export
    def export_json(self, out: str | Path, *, images: bool = True) -> dict[str, int]:
        """Write the whole map as one JSON document (see :func:`import_json`)."""
        target = Path(out)
        if target.is_dir():
            raise InputError(f"export target {target} is a directory: name a .json file")
        if not target.parent.is_dir():
            raise InputError(f"export target folder {target.parent} does not exist")
        from inherit_sg.exchange.records import (
            edge_to_record,
            keyframe_to_record,
            node_to_record,
            session_to_record,
        )

        graph = self.store.load_graph()
        keyframe_ids = [
            row[0] for row in self.store.cypher("MATCH (k:Keyframe) RETURN k.id ORDER BY k.id").rows
        ]
        doc = {
            "format": EXPORT_FORMAT,
            "version": EXPORT_VERSION,
            "map": self.store.info.to_dict(),
            "nodes": [node_to_record(n) for n in graph.nodes()],
            "edges": [edge_to_record(e) for e in graph.edges()],
            "keyframes": [
                keyframe_to_record(self.store.get_keyframe(k, with_image=images))
                for k in keyframe_ids
            ],
            "sessions": [session_to_record(s) for s in self.store.sessions()],
        }
        # written beside the target and renamed, so a failed export leaves no half file
        partial = target.with_name(target.name + ".partial")
        try:
            partial.write_text(json.dumps(doc), encoding="utf-8")
            partial.replace(target)
        except OSError as exc:
            partial.unlink(missing_ok=True)
            raise InputError(f"cannot write the export to {target}: {exc}") from None
        return {
            "nodes": len(graph),
            "edges": sum(1 for _ in graph.edges()),
            "keyframes": len(keyframe_ids),
        }

    def export_spark_dsg(self, out: str | Path) -> dict[str, int]:
        """Write the scene graph as Spark-DSG JSON with the ``spark_dsg`` package (see
        :mod:`inherit_sg.exchange.spark_dsg_export`); counts are of the written graph."""
        from inherit_sg.exchange.spark_dsg_export import export_spark_dsg

        return {**export_spark_dsg(self.store.load_graph(), out), "keyframes": 0}


def _config_for_export(doc: dict[str, Any], base: Config) -> Config:
    """The base config with the vector dimensions the exported map was made with."""
    info = doc.get("map", {})
    store = base.store.model_copy(
        update={k: info[k] for k in ("visual_dim", "text_dim", "image_feature_dim") if k in info}
    )
    return base.model_copy(update={"store": store})


def import_into_new_map(
    source: str | Path,
    map_dir: str | Path,
    *,
    fmt: str = "json",
    label_space: str | Path | None = None,
    config: Config | None = None,
) -> dict[str, int]:
    """Create ``map_dir`` from an INHerit-SG JSON export or a Spark-DSG JSON file."""
    from inherit_sg.exchange.records import (
        edge_from_record,
        keyframe_from_record,
        node_from_record,
        session_from_record,
    )
    from inherit_sg.model import SceneGraph

    cfg = config or load_config()
    src = Path(source)
    if not src.is_file():
        raise InputError(f"file to import not found: {src}")
    if fmt == "spark-dsg":
        from inherit_sg.exchange.spark_dsg import load_label_space, spark_dsg_to_graph

        names = load_label_space(label_space) if label_space else None
        graph = spark_dsg_to_graph(src, names)
        with MapStore.create(map_dir, cfg) as store:
            store.write_changes(graph)
            _compact_if_asked(store, cfg)
        return {"nodes": len(graph), "edges": sum(1 for _ in graph.edges()), "keyframes": 0}
    if fmt == "scene":
        from inherit_sg.embed import get_text_embedder
        from inherit_sg.exchange.scene_truth import scene_file_to_graph
        from inherit_sg.mapping.node_text import embed_nodes

        graph = scene_file_to_graph(src)
        embedder = get_text_embedder(
            cfg.embedder.model,
            batch_size=cfg.embedder.batch_size,
            device=cfg.embedder.device,
            backend=cfg.embedder.backend,
        )
        embed_nodes(graph, embedder)
        with MapStore.create(map_dir, cfg) as store:
            store.write_changes(graph)
            _compact_if_asked(store, cfg)
        return {"nodes": len(graph), "edges": sum(1 for _ in graph.edges()), "keyframes": 0}
    if fmt != "json":
        raise InputError(f"unknown import format {fmt!r}: use json, spark-dsg or scene")
    try:
        doc = json.loads(src.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{src}: invalid JSON: {exc}") from None
    if not isinstance(doc, dict) or doc.get("format") != EXPORT_FORMAT:
        raise InputError(
            f"{src}: not an INHerit-SG map export (use --format spark-dsg for Hydra graphs)"
        )
    if int(doc.get("version", 0)) > EXPORT_VERSION:
        raise MapError(
            f"{src}: export version {doc['version']} is newer than this inherit-sg understands"
        )
    graph = SceneGraph()
    for rec in doc.get("nodes", []):
        graph.add_or_update(node_from_record(rec))
    for rec in doc.get("edges", []):
        graph.add_edge(edge_from_record(rec))
    keyframes = [keyframe_from_record(r) for r in doc.get("keyframes", [])]
    with MapStore.create(map_dir, _config_for_export(doc, cfg)) as store:
        for rec in doc.get("sessions", []):
            store.upsert_session(session_from_record(rec))
        if keyframes:
            store.add_keyframes(keyframes)
        store.write_changes(graph)
        _compact_if_asked(store, cfg)
    return {"nodes": len(graph), "edges": len(doc.get("edges", [])), "keyframes": len(keyframes)}


def _compact_if_asked(store: MapStore, cfg: Config) -> CompactReport | None:
    """A finished build or import leaves dead pages: compact the map when the config
    asks (store.compact_on_finish, on by default); what it did, else None."""
    return store.compact() if cfg.store.compact_on_finish else None


def compact_map(map_dir: str | Path, config: Config | None = None) -> dict[str, Any]:
    """Rewrite a map's databases without the pages earlier writes left dead (see
    :meth:`MapStore.compact`); needs the writer lock. Bytes of each file before and
    after, and the tables and rows kept."""
    path = Path(map_dir)
    with MapStore.open(path, write=True, config=config or Config()) as store:
        report = store.compact()
    return {
        "map": str(path),
        "before": report.before,
        "after": report.after,
        "saved": report.saved,
        "tables": report.tables,
        "rows": report.rows,
    }


def build_map(
    dataset: str | Path,
    map_dir: str | Path,
    *,
    fmt: str = "auto",
    session_name: str | None = None,
    config: Config | None = None,
    max_frames: int | None = None,
    progress: Any = None,
    total: Any = None,
    observer: Any = None,
    reader_options: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Map a dataset into ``map_dir`` as one new session (the map is created when absent).

    ``progress`` receives :class:`~inherit_sg.mapping.orchestrator.BuildProgress`
    counters; ``total`` is called once with the number of frames to expect; ``observer``
    (a :class:`~inherit_sg.mapping.orchestrator.MapObserver`) sees every frame and the
    graph after every global update; ``reader_options`` go to the dataset reader (e.g.
    ``rgb_topic`` for a ROS bag).
    """
    import itertools

    from inherit_sg.ingest.readers import open_dataset
    from inherit_sg.mapping.allocator import limit_arenas
    from inherit_sg.mapping.bev_pictures import write_bev_pictures
    from inherit_sg.mapping.orchestrator import Mapper
    from inherit_sg.mapping.sessions import new_session

    limit_arenas()  # before the database, the models and the mapping threads start
    if max_frames is not None and max_frames < 1:
        raise InputError(f"max_frames must be at least 1, got {max_frames}")
    cfg = config or load_config()
    source = open_dataset(dataset, fmt, **(reader_options or {}))
    if len(source) == 0:
        raise InputError(f"dataset {dataset} has no frames (is its pose list empty?)")
    n_frames = len(source) if max_frames is None else min(len(source), max_frames)
    frames = iter(source)
    first = next(frames, None)  # a dataset whose frames cannot be read fails before a map
    if first is None:
        raise InputError(f"dataset {dataset} yields no frames")
    if total is not None:
        total(n_frames)
    path = Path(map_dir)
    store = (
        MapStore.open(path, write=True, config=cfg)
        if (path / "map.json").is_file()
        else MapStore.create(path, cfg)
    )
    with store:
        session = new_session(
            store, session_name, dataset=str(dataset), default_prefix="session", taken=InputError
        )
        store.upsert_session(session)
        mapper = Mapper(store, cfg, session, progress=progress, observer=observer)
        summary = mapper.run(itertools.islice(itertools.chain([first], frames), n_frames))
        pictures = write_bev_pictures(mapper, path)
        compacted = _compact_if_asked(store, cfg)
    out = summary.to_dict()
    out["map"] = str(path)
    if compacted is not None:
        out["compacted"] = {"before": compacted.before, "after": compacted.after}
    out["bev"] = [str(p) for p in pictures]
    return out
