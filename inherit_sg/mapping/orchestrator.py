"""Dual-stream orchestration (paper §III-B/C): the geometric stream runs on every frame
in the caller's thread; the semantic stream runs on a worker thread fed by the
keyframe queue; hard (floor change) and soft (supervisor) triggers schedule a global
update (a remote supervisor decides on its own thread, so a slow model never stalls the
geometric stream) that refines rooms, rebuilds the hierarchy and persists the diff through the
single writer.

Back-pressure: for recorded datasets (``block``) the producer waits while the queue is
full, so no keyframe is lost; for live streams (``drop``) the queue drops its oldest
non-hard keyframe and counts it, so the geometric stream never stalls.

Durability: the working graph is flushed at every update and every ``flush_every``
keyframes, so an interrupted build loses at most the last unflushed batch; the map on
disk is always a consistent committed state.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Protocol

import cv2
import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import ConfigError, InheritSGError
from inherit_sg.geometry.events import FloorChanged, RoomEntered
from inherit_sg.geometry.gating import PendingKeyframe
from inherit_sg.mapping.adapters import (
    create_area_labeller,
    create_relation_verifier,
    create_supervisor,
)
from inherit_sg.mapping.allocator import release_free_memory
from inherit_sg.mapping.decisions import DecisionRunner
from inherit_sg.mapping.geometry_state import load_geometry, new_queue, save_geometry
from inherit_sg.mapping.missing import MissingTracker
from inherit_sg.mapping.object_map import ObjectMap
from inherit_sg.mapping.open_plan import SplitParams, whole_room_id
from inherit_sg.mapping.relation_verifier import Box, GeometricVerifier
from inherit_sg.mapping.semantic import LabelSimilarity, SemanticStream
from inherit_sg.mapping.supervisor import Supervisor
from inherit_sg.mapping.update import HierarchyBuilder
from inherit_sg.model import (
    Edge,
    EdgeKind,
    Frame,
    Keyframe,
    ObjectNode,
    ObjectStatus,
    SceneGraph,
    Session,
)
from inherit_sg.perception.base import blind_without_instances
from inherit_sg.store import MapStore
from inherit_sg.store.mapdir import record_session_vocabulary

log = logging.getLogger(__name__)


# How often a producer waiting for room in the keyframe queue checks the worker is alive.
# A recorded dataset's geometric stream runs ahead of the semantic one by at most this
# many pending keyframes: enough to keep the semantic worker busy, where a full queue
# (geometry.queue_capacity, for live bursts) held ~700 MB of frames for nothing.
BLOCK_AHEAD = 8
WAIT_CHECK_S = 0.1


@dataclass
class BuildProgress:
    """Counters reported to the progress callback."""

    frames: int = 0
    keyframes: int = 0
    keyframes_done: int = 0
    objects: int = 0
    updates: int = 0
    dropped: int = 0


@dataclass
class BuildSummary:
    """What a mapping session did."""

    session_id: str
    frames: int
    keyframes: int
    dropped_keyframes: int
    objects: int
    rooms: int
    floors: int
    areas: int
    relations: int
    missing: int
    updates: dict[str, int]
    seconds: float
    geometry_fps: float
    semantic_keyframes_per_s: float
    timings_s: dict[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict[str, object]:
        """JSON-able form."""
        return dict(vars(self))


class MapObserver(Protocol):
    """Watches a session as it maps (e.g. :class:`inherit_sg.viz.rerun_log.RerunLog`)."""

    def frame(self, frame: Frame) -> None:
        """Called for every frame, after the geometric stream took it."""

    def graph(self, graph: SceneGraph) -> None:
        """Called after every global update with the whole graph (under the mapper's lock:
        read it, do not keep it)."""


class Mapper:
    """Builds one mapping session into an open, writable :class:`MapStore`."""

    def __init__(
        self,
        store: MapStore,
        config: Config,
        session: Session,
        *,
        backpressure: str = "block",
        flush_every: int = 40,
        progress: Callable[[BuildProgress], None] | None = None,
        supervisor: Supervisor | None = None,
        observer: MapObserver | None = None,
    ) -> None:
        from inherit_sg.embed import get_text_embedder
        from inherit_sg.perception import create_describer, create_segmenter, create_visual_encoder

        if backpressure not in ("block", "drop"):
            raise ValueError("backpressure must be 'block' or 'drop'")
        self.store, self.config, self.session = store, config, session
        self.backpressure, self.flush_every, self._progress_cb = backpressure, flush_every, progress
        self.progress = BuildProgress()
        self.observer = observer
        self.embedder = get_text_embedder(
            config.embedder.model,
            batch_size=config.embedder.batch_size,
            device=config.embedder.device,
            backend=config.embedder.backend,
        )
        self.embedder.embed(["warm-up"])  # load the model now, not inside the worker's lock
        self.graph = store.load_graph()
        self.graph.flush_changes()
        earlier = [o for o in self.graph.objects() if o.status is not ObjectStatus.REMOVED]
        self.objects = ObjectMap(LabelSimilarity(self.embedder))
        for node in earlier:
            self.objects.adopt(node)
        self.missing = MissingTracker(earlier)
        self.geometry = load_geometry(store.path, config, session.id)
        if backpressure == "block":
            new_queue(self.geometry, max(8, config.geometry.queue_capacity))
        describer = create_describer(config)
        encoder = create_visual_encoder(config)
        _check_feature_sizes(store, encoder.dim, encoder.image_dim, encoder.name)
        self.semantic = SemanticStream(create_segmenter(config), encoder, describer, self.objects)
        verifier = create_relation_verifier(config)
        self.builder = HierarchyBuilder(
            self.embedder,
            refresh_descriptions=describer.name == "offline",
            area_labeller=create_area_labeller(config),
            relation_verifier=verifier,
            keyframe_view=None if isinstance(verifier, GeometricVerifier) else self._keyframe_view,
            open_plan=SplitParams(min_room_m2=config.geometry.open_plan_min_area)
            if config.geometry.split_open_plan
            else None,
        )
        self.builder.remember_embedded(self.graph)
        self.supervisor = supervisor or create_supervisor(config, self._bev_png)
        self.decisions = DecisionRunner(
            self.supervisor, lambda reason: self._request_update(f"soft: {reason}", "soft")
        )
        self._seen_index: dict[str, dict[str, tuple[Box, float]]] | None = None
        self._lock = threading.RLock()  # geometric stream, working graph, object map
        self._update_reason: str | None = None
        self._pending_keyframes: list[Keyframe] = []
        self._pending_seen: list[Edge] = []
        self._since_flush = 0
        self._error: BaseException | None = None
        self._updates = {"hard": 0, "soft": 0, "periodic": 0, "final": 0}
        self._timings = {"geometry": 0.0, "semantic": 0.0, "update": 0.0, "persist": 0.0}
        self._worker = threading.Thread(target=self._work, name="semantic-stream", daemon=True)

    # ------------------------------------------------------------------ producer
    def run(self, frames: Iterable[Frame]) -> BuildSummary:
        """Consume every frame, then finish the session (final update and flush)."""
        start = time.perf_counter()
        self.start()
        try:
            for frame in frames:
                self._raise_worker_error()
                self.process_frame(frame)
        finally:
            self.geometry.queue.close()
            self._worker.join()
        self._raise_worker_error()
        return self.finish(time.perf_counter() - start)

    def start(self) -> None:
        """Start the semantic worker (live sessions; :meth:`run` starts it itself)."""
        self._worker.start()

    def drain(self) -> None:
        """Close the keyframe queue, wait until the worker has emptied it and surface
        its error, if any; call :meth:`finish` next."""
        self.geometry.queue.close()
        if self._worker.is_alive():
            self._worker.join()
        self._raise_worker_error()

    def check(self) -> None:
        """Raise the semantic worker's error, if it failed (live sessions poll this)."""
        self._raise_worker_error()

    @property
    def worker_alive(self) -> bool:
        """Whether the semantic worker thread is running."""
        return self._worker.is_alive()

    def process_frame(self, frame: Frame) -> None:
        """Geometric stream on one frame; schedules updates on trigger events."""
        queue = self.geometry.queue
        if self.backpressure == "block":
            # wait for the semantic worker to take a keyframe (woken by the queue itself);
            # look up every WAIT_CHECK_S whether the worker is still there to take one
            while not queue.wait_below(min(queue.capacity - 1, BLOCK_AHEAD), WAIT_CHECK_S):
                if not self._worker.is_alive():
                    break
        t0 = time.perf_counter()
        # the geometric stream locks itself; it never waits for the semantic side
        events = self.geometry.process(frame.validate())
        self._timings["geometry"] += time.perf_counter() - t0
        self.progress.frames += 1
        if self.observer is not None:
            self.observer.frame(frame)
        for event in events:
            if isinstance(event, FloorChanged):
                self._request_update(
                    f"hard: floor change {event.from_floor} → {event.to_floor}", "hard"
                )
            elif isinstance(event, RoomEntered):
                inside = [o.id for o in self.objects_in(event.room_id)]
                self.decisions.room_entered(event.room_id, inside)
        self.progress.keyframes = self.geometry.stats.keyframes
        self.progress.dropped = queue.dropped
        self._report()

    def _request_update(self, reason: str, kind: str) -> None:
        with self._lock:
            if self._update_reason is None:
                self._update_reason = reason
                self._updates[kind] += 1

    # -------------------------------------------------------------- semantic worker
    def _work(self) -> None:
        try:
            while True:
                item = self.geometry.queue.get(timeout=0.05)
                if item is not None:
                    self._process_keyframe(item)
                elif self.geometry.queue.closed and len(self.geometry.queue) == 0:
                    return
                reason = self._update_reason
                if reason is not None and (
                    len(self.geometry.queue) == 0 or reason.startswith("hard")
                ):
                    self.global_update(reason)
                elif self._since_flush >= self.flush_every:
                    self._updates["periodic"] += 1
                    self.global_update("periodic flush")
        except BaseException as exc:  # surfaced in the producer thread
            self._error = exc

    def _process_keyframe(self, item: PendingKeyframe) -> None:
        t0 = time.perf_counter()
        frame, kf = item.frame, item.keyframe
        frame_at = self.session.started + frame.timestamp
        seen = self.semantic.perceive(frame)
        for obs in seen.observations:
            obs.timestamp, obs.keyframe_id = frame_at, kf.id
        with self._lock:
            assigned, _ = self.semantic.integrate(frame, seen, kf.floor_id)
            for node_id, det in assigned:
                self._pending_seen.append(
                    Edge.make(
                        EdgeKind.SEEN_IN,
                        node_id,
                        kf.id,
                        bbox=det.bbox_xyxy,
                        label=det.label,
                        score=round(det.score, 3),
                    )
                )
            self.missing.observed(node_id for node_id, _ in assigned)
            if not (blind_without_instances(self.semantic.segmenter) and frame.instances is None):
                self.missing.check_frame(frame)
            kf.jpeg = encode_keyframe(
                frame.rgb, self.config.store.keyframe_max_side, self.config.store.jpeg_quality
            )
            self._pending_keyframes.append(kf)
            self.progress.objects = len(self.objects)
        self.progress.keyframes_done += 1
        self._since_flush += 1
        self._timings["semantic"] += time.perf_counter() - t0
        self._report()

    # ------------------------------------------------------------- global update
    def global_update(self, reason: str) -> None:
        """Refine rooms, rebuild the hierarchy, persist the diff (single writer)."""
        t0 = time.perf_counter()
        with self._lock:
            self._update_reason = None
            log.info("global update: %s", reason)
            self.geometry.refine()
            self.geometry.apply_to(self.graph, refined=True)
            # floors from heights: keyframes taken on the stairs may carry the floor
            # the camera was leaving
            for tracked in self.objects.objects.values():
                box = tracked.node.bbox
                floor = self.geometry.floor_of_box(box.min[2], box.max[2])
                if floor is not None and floor != tracked.floor_id:
                    tracked.floor_id = tracked.node.floor_id = floor
                    tracked.dirty = True
            merged = self.objects.remove_duplicates()
            for keep, drop in merged:
                self.missing.merged(keep, drop)
            self._seen_index = None
            alias = {drop: keep for keep, drop in merged}
            self.builder.rebuild(self.graph, self.objects, self.geometry.room_at)
            rooms = {n.id for n in self.graph.nodes() if n.id.startswith("room:")}
            # a split room is entered under its geometric id: summarised as a whole too
            for room_id in sorted(rooms | {whole_room_id(r) for r in rooms}):
                inside = [o.id for o in self.objects_in(room_id)]
                self.supervisor.summarised(room_id, inside)
            t1 = time.perf_counter()
            self._timings["update"] += t1 - t0
            self._persist(alias)
            self._timings["persist"] += time.perf_counter() - t1
            if self.observer is not None:
                self.observer.graph(self.graph)
        release_free_memory()  # the update's temporaries are gone: hand their pages back
        self.progress.updates += 1
        self._report()

    def _persist(self, alias: dict[str, str]) -> None:
        keyframes, self._pending_keyframes = self._pending_keyframes, []
        if keyframes:
            self.store.add_keyframes(keyframes)
        for edge in self._pending_seen:
            src = alias.get(edge.src, edge.src)
            if src in self.graph:
                self.graph.add_edge(Edge(edge.kind, src, edge.dst, edge.props))
        self._pending_seen = []
        self.store.write_changes(self.graph)
        self.session.frames = self.progress.frames
        self.session.keyframes = self.progress.keyframes_done
        self.store.upsert_session(self.session)
        save_geometry(self.geometry, self.store.path)
        self._since_flush = 0

    # -------------------------------------------------------------------- finish
    def finish(self, seconds: float) -> BuildSummary:
        """Final update: missing objects, last flush, the session record; ``map.json``
        then records the vocabulary and the map's label space."""
        self.decisions.close()
        missing = self.missing.finish()
        for oid in missing:
            if oid in self.objects.objects:
                self.objects.objects[oid].dirty = True
        self.session.finished = time.time()
        self.session.state = "finished"
        self._updates["final"] += 1
        self.global_update("final update at the end of the session")
        record_session_vocabulary(
            self.store.path, self.store.info, (o.label for o in self.graph.objects())
        )
        stats = self.geometry.stats
        return BuildSummary(
            session_id=self.session.id,
            frames=self.progress.frames,
            keyframes=self.progress.keyframes_done,
            dropped_keyframes=self.geometry.queue.dropped,
            objects=sum(1 for o in self.graph.objects() if o.status is ObjectStatus.ACTIVE),
            rooms=sum(1 for n in self.graph.nodes() if n.id.startswith("room:")),
            floors=sum(1 for n in self.graph.nodes() if n.id.startswith("floor:")),
            areas=sum(1 for n in self.graph.nodes() if n.id.startswith("area:")),
            relations=sum(1 for _ in self.graph.edges(EdgeKind.RELATION)),
            missing=len(missing),
            updates=dict(self._updates),
            seconds=round(seconds, 2),
            geometry_fps=round(stats.frames / self._timings["geometry"], 1)
            if self._timings["geometry"]
            else 0.0,
            semantic_keyframes_per_s=round(
                self.progress.keyframes_done / self._timings["semantic"], 2
            )
            if self._timings["semantic"]
            else 0.0,
            timings_s={k: round(v, 2) for k, v in self._timings.items()},
        )

    # ------------------------------------------------------- model-backed roles
    def _bev_png(self) -> bytes:
        """PNG of the current floor's BEV picture (NodeNotFoundError before any map)."""
        rgb = self.geometry.bev()
        ok, buf = cv2.imencode(".png", cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR))
        if not ok:
            raise RuntimeError("PNG encoding of the BEV picture failed")
        return buf.tobytes()

    def _keyframe_view(self, object_id: str) -> tuple[bytes | None, dict[str, Box]] | None:
        """The keyframe showing ``object_id`` with the most other objects, as JPEG bytes
        and the objects' boxes scaled to that JPEG (for the relation verifier)."""
        if self._seen_index is None:
            index: dict[str, dict[str, tuple[Box, float]]] = {}
            for edge in [*self.graph.edges(EdgeKind.SEEN_IN), *self._pending_seen]:
                box = edge.prop("bbox")
                if box is not None and len(box) == 4:
                    score = float(edge.prop("score", 0.0) or 0.0)
                    index.setdefault(edge.dst, {})[edge.src] = (
                        (int(box[0]), int(box[1]), int(box[2]), int(box[3])),
                        score,
                    )
            self._seen_index = index
        showing = [(kf, seen) for kf, seen in self._seen_index.items() if object_id in seen]
        if not showing:
            return None
        kf_id, seen = max(showing, key=lambda kv: (len(kv[1]), kv[1][object_id][1], kv[0]))
        kf = next((k for k in self._pending_keyframes if k.id == kf_id), None)
        if kf is None:
            try:
                kf = self.store.get_keyframe(kf_id, with_image=True)
            except InheritSGError:
                return None
        if kf.jpeg is None:
            return None
        side = max(kf.width, kf.height)
        scale = min(1.0, self.config.store.keyframe_max_side / side) if side else 1.0
        boxes = {oid: tuple(round(v * scale) for v in b) for oid, (b, _) in seen.items()}
        return kf.jpeg, boxes  # type: ignore[return-value]

    def objects_in(self, room_id: str) -> list[ObjectNode]:
        """Current object nodes of one room (of all its parts when it was split)."""
        with self._lock:
            return [
                o
                for o in self.objects.nodes()
                if o.room_id is not None
                and (o.room_id == room_id or whole_room_id(o.room_id) == room_id)
            ]

    def _raise_worker_error(self) -> None:
        if self._error is not None:
            err, self._error = self._error, None
            if isinstance(err, InheritSGError):
                raise err
            raise RuntimeError(f"semantic stream failed: {err!r}") from err

    def _report(self) -> None:
        if self._progress_cb is not None:
            self._progress_cb(self.progress)


def _check_feature_sizes(store: MapStore, dim: int, image_dim: int, encoder: str) -> None:
    """A map keeps one feature size; a different encoder must not write into it."""
    info = store.info
    if (dim, image_dim) != (info.visual_dim, info.image_feature_dim):
        raise ConfigError(
            f"map {store.path} stores {info.visual_dim}-d object and {info.image_feature_dim}-d "
            f"image features (encoder {info.visual_encoder!r}) but encoder {encoder!r} gives "
            f"{dim}-d and {image_dim}-d; map into a new map created with "
            f"--set store.visual_dim={dim} --set store.image_feature_dim={image_dim}"
        )


def encode_keyframe(rgb: np.ndarray, max_side: int, quality: int) -> bytes:
    """JPEG bytes of a keyframe, downsized so its longer side is at most ``max_side``."""
    h, w = rgb.shape[:2]
    scale = min(1.0, max_side / max(h, w))
    img = (
        rgb
        if scale >= 1.0
        else cv2.resize(rgb, (round(w * scale), round(h * scale)), interpolation=cv2.INTER_AREA)
    )
    ok, buf = cv2.imencode(
        ".jpg", cv2.cvtColor(img, cv2.COLOR_RGB2BGR), [cv2.IMWRITE_JPEG_QUALITY, quality]
    )
    if not ok:
        raise RuntimeError("JPEG encoding failed")
    return buf.tobytes()
