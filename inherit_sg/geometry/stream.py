"""The geometric stream (paper §III-B): consumes frames one by one and keeps floors,
per-floor BEV occupancy, rooms, doors and keyframe gating up to date.

Per frame: back-project a strided depth image, track the floor from the camera height,
ray-cast the band scan into the current floor's grid (skipped while on stairs), run the
keyframe gate and queue keyframes for the semantic stream, re-segment rooms every
``segment_every`` frames, and notice when the camera enters another room.
"""

from __future__ import annotations

import functools
import math
import threading
from collections import deque
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, TypeVar, cast

import numpy as np

from inherit_sg.config import Config, GeometryConfig
from inherit_sg.errors import NodeNotFoundError
from inherit_sg.geometry.bev import render_bev, write_png
from inherit_sg.geometry.events import (
    FloorChanged,
    GeometryEvent,
    KeyframeDropped,
    KeyframeSelected,
    RoomEntered,
    RoomsUpdated,
)
from inherit_sg.geometry.export import apply_to_graph, floor_nodes, geometry_edges, room_nodes
from inherit_sg.geometry.floor_map import Door, FloorMap
from inherit_sg.geometry.floors import (
    FloorState,
    FloorTracker,
    FloorTransition,
    estimate_floor_z,
)
from inherit_sg.geometry.gating import KeyframeGate, KeyframeQueue, PendingKeyframe
from inherit_sg.geometry.image_feature import global_image_feature
from inherit_sg.geometry.occupancy import LogOddsParams
from inherit_sg.geometry.raycast import band_scan, world_points
from inherit_sg.geometry.records import (
    IdCounter,
    RoomTracker,
    StairsRecord,
    StreamStats,
    room_node_id,
)
from inherit_sg.geometry.refine import RefineParams
from inherit_sg.geometry.rooms import SegmentParams
from inherit_sg.geometry.viewpoint import best_views, grid_views, horizontal_fov
from inherit_sg.model import Edge, FloorNode, Frame, Keyframe, Pose, RoomNode, SceneGraph

_F = TypeVar("_F", bound=Callable[..., Any])


def _locked(method: _F) -> _F:
    """Run a method under the stream's lock (the semantic worker calls in too)."""

    @functools.wraps(method)
    def wrapper(self: GeometricStream, *args: Any, **kwargs: Any) -> Any:
        with self.lock:
            return method(self, *args, **kwargs)

    return cast(_F, wrapper)


# An object whose middle lies this far below a floor's estimated surface still stands on
# it (depth noise on thin things such as rugs); it is less than a floor slab is thick.
FLOOR_BAND_M = 0.1
# An object reaching this far below its floor's surface rises from the floor below
# (stairs); less is depth noise at the foot of things standing on the floor.
RISES_FROM_M = 0.3


def _floor_index(floors: list[FloorState], z: float) -> int:
    """Index in ``floors`` (lowest first) of the highest floor whose surface lies at most
    :data:`FLOOR_BAND_M` above ``z``; the lowest when none does."""
    below = [k for k, f in enumerate(floors) if f.floor_z - FLOOR_BAND_M <= z]
    return below[-1] if below else 0


class GeometricStream:
    """Fast half of the dual-stream construction (floors, rooms, doors, keyframes).

    ``config``: the whole :class:`Config` or its geometry section. Keyframes go to
    ``queue`` (a new bounded one by default) unless ``enqueue_keyframes`` is False.
    ``image_feature`` maps an RGB image to the global vector the keyframe gate compares
    (default: the offline descriptor of size ``store.image_feature_dim``; a DINOv3
    adapter can be passed instead). ``first_room_id`` / ``first_floor_id`` start the id
    counters (a later session appending to a map passes numbers not used yet).

    Public methods hold ``lock``, so a semantic worker may call :meth:`add_door`,
    :meth:`refine`, :meth:`rooms` or :meth:`apply_to` between two frames safely.
    """

    def __init__(
        self,
        config: Config | GeometryConfig | None = None,
        *,
        session_id: str = "",
        image_feature_dim: int | None = None,
        queue: KeyframeQueue | None = None,
        enqueue_keyframes: bool = True,
        image_feature: Callable[[np.ndarray], np.ndarray] | None = None,
        first_room_id: int = 1,
        first_floor_id: int = 0,
    ) -> None:
        self.lock = threading.RLock()
        full = config if isinstance(config, Config) else None
        cfg = config if isinstance(config, GeometryConfig) else (full or Config()).geometry
        self.cfg = cfg
        self.session_id = session_id
        self.feature_dim = image_feature_dim or (full or Config()).store.image_feature_dim
        self.queue = queue or KeyframeQueue(cfg.queue_capacity)
        self.enqueue_keyframes = enqueue_keyframes
        dim = self.feature_dim
        self.image_feature = image_feature or (lambda rgb: global_image_feature(rgb, dim))
        self.tracker = FloorTracker(cfg, first_floor_id)
        self.gate = KeyframeGate(
            cfg.keyframe_similarity,
            cfg.keyframe_translation,
            cfg.keyframe_rotation_deg,
            cfg.keyframe_min_gap,
        )
        self.maps: dict[str, FloorMap] = {}
        self.keyframes: list[Keyframe] = []
        self.stairs: list[StairsRecord] = []
        self.update_points: list[tuple[str, float, float, float]] = []  # floor, x, y, t
        self.best_view: dict[int, str] = {}
        self.stats = StreamStats()
        self.segment_params = SegmentParams.from_config(cfg)
        self.refine_params = RefineParams.from_config(cfg)
        self._logodds = LogOddsParams(
            cfg.logodds_hit,
            cfg.logodds_miss,
            cfg.logodds_min,
            cfg.logodds_max,
            cfg.occupied_threshold,
            cfg.free_threshold,
        )
        self._room_ids = IdCounter(first_room_id)
        self._since_segment = 0
        self._room = RoomTracker(self.cfg.room_enter_frames)
        self._time = 0.0
        self._views: list[tuple[str, str, Pose, float]] = []  # floor, keyframe id, pose, hfov
        self.published_rooms: set[str] = set()  # room ids last written by apply_to
        # Frames seen while between floors: (frame position, points, camera, floor height).
        self._pending: deque[tuple[int, np.ndarray, np.ndarray, float | None]] = deque(
            maxlen=cfg.floor_stable_frames
        )

    # ------------------------------------------------------------------ frames
    def floor_map(self, floor_id: str) -> FloorMap:
        """The map of one floor (created on first use)."""
        fmap = self.maps.get(floor_id)
        if fmap is None:
            cfg = self.cfg
            fmap = FloorMap(
                cfg.cell_size,
                self._logodds,
                cfg.grid_margin,
                cfg.room_hysteresis,
                self._room_ids,
                cfg.door_needs_lintel,
            )
            self.maps[floor_id] = fmap
        return fmap

    @_locked
    def process(self, frame: Frame) -> list[GeometryEvent]:
        """Consume one frame; returns the events it caused (in order)."""
        cfg = self.cfg
        self._time = frame.timestamp
        cam = frame.pose.translation
        stride = max(1, round(cfg.depth_stride * frame.intrinsics.width / 640))
        pts = world_points(frame, stride, cfg.max_range * 1.5)
        floor_est = estimate_floor_z(pts[:, 2], float(cam[2]))
        position = (float(cam[0]), float(cam[1]), float(cam[2]))
        trans = self.tracker.update(position, floor_est)
        events: list[GeometryEvent] = []
        if trans is not None:
            events += self._floor_changed(frame, trans)
        floor = self.tracker.current
        assert floor is not None
        fmap = self.floor_map(floor.id)
        if self.tracker.settled:
            self._pending.clear()
            self._integrate(fmap, floor, pts, cam)
            self._since_segment += 1
        else:
            self._pending.append((self.stats.frames, pts, cam, floor_est))
        self.stats.frames += 1
        self.stats.frame_floors.append(floor.id)
        events += self._gate(frame, floor.id, hard=trans is not None)
        if self._since_segment >= cfg.segment_every:
            events += self.segment(floor.id, frame.index)
        if self.tracker.settled:
            events += self._track_room(frame, fmap, floor.id)
        return events

    def _integrate(
        self, fmap: FloorMap, floor: FloorState, pts: np.ndarray, cam: np.ndarray
    ) -> None:
        cfg = self.cfg
        scan = band_scan(
            pts,
            cam,
            floor.floor_z,
            (cfg.band_min, cfg.band_max),
            cfg.max_range,
            cfg.angle_res_deg,
            (cfg.lintel_min, cfg.lintel_max),
        )
        fmap.integrate(scan, cfg.depth_sigma_1m)
        fmap.trajectory.append((float(cam[0]), float(cam[1])))
        self.stats.integrated += 1

    def _catch_up(self, floor: FloorState) -> None:
        """After a floor switch, the steady frames that confirmed it belong to the new
        floor: assign and integrate them there."""
        fmap = self.floor_map(floor.id)
        for pos, pts, cam, est in self._pending:
            if abs(float(cam[2]) - floor.camera_z) > self.cfg.floor_settle_tol:
                continue
            if est is not None:
                floor.estimates.append(est)
            self.stats.frame_floors[pos] = floor.id
            self._integrate(fmap, floor, pts, cam)
        self._pending.clear()

    def _floor_changed(self, frame: Frame, trans: FloorTransition) -> list[GeometryEvent]:
        events = self.segment(trans.from_id, frame.index)
        self._catch_up(self.tracker.floors[trans.to_id])
        if not any({s.from_floor, s.to_floor} == {trans.from_id, trans.to_id} for s in self.stairs):
            self.stairs.append(StairsRecord(trans.from_id, trans.to_id, trans.start, trans.end))
        self._room = RoomTracker(self.cfg.room_enter_frames)
        events.append(
            FloorChanged(
                frame.index,
                frame.timestamp,
                trans.from_id,
                trans.to_id,
                trans.created,
                trans.reordered,
                trans.start,
                trans.end,
            )
        )
        return events

    def _gate(self, frame: Frame, floor_id: str, hard: bool) -> list[GeometryEvent]:
        feature = self.image_feature(frame.rgb)
        decision = self.gate.check(frame.index, feature, frame.pose, force=hard)
        if not decision.selected:
            return []
        kf_id = f"kf:{self.session_id}:{frame.index}" if self.session_id else f"kf:{frame.index}"
        kf = Keyframe(
            id=kf_id,
            session_id=self.session_id,
            timestamp=frame.timestamp,
            pose=frame.pose,
            floor_id=floor_id,
            frame_index=frame.index,
            global_feature=feature,
            width=frame.intrinsics.width,
            height=frame.intrinsics.height,
        )
        self.keyframes.append(kf)
        self._views.append((floor_id, kf_id, frame.pose, horizontal_fov(frame.intrinsics)))
        self.stats.keyframes += 1
        events: list[GeometryEvent] = [
            KeyframeSelected(
                frame.index, frame.timestamp, kf, decision.reason, hard, decision.similarity
            )
        ]
        if self.enqueue_keyframes:
            dropped = self.queue.put(PendingKeyframe(kf, frame, hard, decision.reason))
            if dropped is not None:
                self.stats.dropped_keyframes += 1
                events.append(
                    KeyframeDropped(frame.index, frame.timestamp, dropped.keyframe.id, dropped.hard)
                )
        return events

    def _track_room(self, frame: Frame, fmap: FloorMap, floor_id: str) -> list[GeometryEvent]:
        before = self._room.current
        entered = self._room.observe(fmap.room_at(*fmap.trajectory[-1]))
        if entered is None:
            return []
        previous = room_node_id(before) if before else None
        return [
            RoomEntered(frame.index, frame.timestamp, floor_id, room_node_id(entered), previous)
        ]

    # ------------------------------------------------------------------- rooms
    @_locked
    def segment(self, floor_id: str | None = None, frame_index: int = -1) -> list[GeometryEvent]:
        """Re-segment the rooms of one floor (default: the current one) now."""
        fid = floor_id or self.current_floor_id
        if fid is None or fid not in self.maps:
            return []
        self._since_segment = 0
        added, removed = self.maps[fid].segment(self.segment_params)
        self.stats.segmentations += 1
        if not added and not removed:
            return []
        ids = tuple(room_node_id(r) for r in self.maps[fid].rooms.room_ids())
        return [
            RoomsUpdated(
                frame_index,
                self._time,
                fid,
                ids,
                tuple(room_node_id(r) for r in sorted(added)),
                tuple(room_node_id(r) for r in sorted(removed)),
            )
        ]

    @_locked
    def refine(self, floor_id: str | None = None) -> list[RoomNode]:
        """Global room-mask refinement (update event) of one floor or all floors, then
        best viewpoints of the refined rooms; records an update point for the BEV.
        Returns the refined room nodes."""
        fids = [floor_id] if floor_id else list(self.maps)
        for fid in fids:
            fmap = self.maps.get(fid)
            if fmap is None or fmap.grid.empty:
                continue
            fmap.segment(self.segment_params)
            ids = fmap.refine(self.refine_params)
            self._assign_views(fid, fmap, ids)
            self.stats.refinements += 1
        cur = self.current_floor_id
        if cur is not None and cur in self.maps and self.maps[cur].trajectory:
            x, y = self.maps[cur].trajectory[-1]
            self.update_points.append((cur, x, y, self._time))
        return room_nodes(self, floor_id, refined=True)

    def _assign_views(self, fid: str, fmap: FloorMap, ids: np.ndarray) -> None:
        g = fmap.grid
        shots = [(key, pose, hfov) for floor, key, pose, hfov in self._views if floor == fid]
        views = grid_views(shots, (g.origin_x, g.origin_y), g.resolution)
        rng = self.cfg.max_range / g.resolution
        for room, (key, _) in best_views(
            ids, ~g.free_mask(), views, rng, self.cfg.viewpoint_rays
        ).items():
            self.best_view[room] = key

    # ---------------------------------------------------------------- queries
    @property
    def current_floor_id(self) -> str | None:
        """Id of the floor the camera is on."""
        return self.tracker.current.id if self.tracker.current else None

    @property
    def current_room_id(self) -> str | None:
        """Id of the room the camera was last seen entering."""
        return room_node_id(self._room.current) if self._room.current else None

    @_locked
    def room_at(self, x: float, y: float, floor_id: str | None = None) -> str | None:
        """Room id at a world point on a floor (default: the current floor)."""
        fid = floor_id or self.current_floor_id
        if fid is None or fid not in self.maps:
            return None
        rid = self.maps[fid].room_at(x, y)
        return room_node_id(rid) if rid else None

    def floor_of_height(self, z: float) -> str | None:
        """The floor whose height band contains world height ``z`` (an object's middle):
        the highest floor whose surface lies at most :data:`FLOOR_BAND_M` above ``z``.

        An object's middle, not its bottom: a light hung from a ceiling sits a slab's
        thickness below the next floor's surface, its middle lower still, while even a rug
        on that floor has its middle at or above the surface."""
        floors = self.tracker.ordered()
        return floors[_floor_index(floors, z)].id if floors else None

    def floor_of_box(self, z_min: float, z_max: float) -> str | None:
        """The floor of an object spanning world heights ``z_min``–``z_max``: the floor of
        its middle (:meth:`floor_of_height`), or the one below when the object reaches
        more than :data:`RISES_FROM_M` below that floor's surface (the top of a flight of
        stairs, seen from the upper floor, rises from the lower one)."""
        floors = self.tracker.ordered()
        if not floors:
            return None
        k = _floor_index(floors, (z_min + z_max) / 2)
        if k > 0 and z_min < floors[k].floor_z - RISES_FROM_M:
            k -= 1
        return floors[k].id

    @_locked
    def add_door(self, x: float, y: float, z: float, width: float = 0.9) -> None:
        """Register a door seen by the semantic stream; it separates rooms from the next
        segmentation on."""
        fid = self.floor_of_height(z)
        if fid is None:
            return
        doors = self.floor_map(fid).semantic_doors
        if all(math.hypot(x - dx, y - dy) > max(width, w) / 2 for dx, dy, w in doors):
            doors.append((x, y, width))

    @_locked
    def doors(self, floor_id: str | None = None) -> list[tuple[str, Door]]:
        """``(floor id, door)`` for one floor or all floors."""
        fids = [floor_id] if floor_id else list(self.maps)
        return [(fid, d) for fid in fids if fid in self.maps for d in self.maps[fid].doors()]

    @_locked
    def bev(
        self,
        floor_id: str | None = None,
        refined: bool = False,
        labels: Mapping[str, str] | None = None,
    ) -> np.ndarray:
        """BEV picture (RGB) of one floor (default: the current one). ``labels`` maps room
        ids to the text drawn on them (default: the ids)."""
        fid = floor_id or self.current_floor_id
        if fid is None or fid not in self.maps or self.maps[fid].grid.empty:
            raise NodeNotFoundError(f"no BEV map for floor {fid!r}: it has no observations yet")
        points = [(x, y, t) for f, x, y, t in self.update_points if f == fid]
        names = {}
        for room in self.maps[fid].masks(refined):
            rid = room_node_id(room)
            names[room] = (labels or {}).get(rid, rid)
        scene = self.maps[fid].bev_scene(refined, names, points, self._time)
        return render_bev(scene, self.cfg.bev_scale)

    def save_bev(
        self,
        path: str | Path,
        floor_id: str | None = None,
        refined: bool = False,
        labels: Mapping[str, str] | None = None,
    ) -> Path:
        """Write :meth:`bev` as a PNG file; returns the path."""
        return write_png(self.bev(floor_id, refined, labels), path)

    # ------------------------------------------------------------ scene graph
    @_locked
    def floors(self) -> list[FloorNode]:
        """Floor nodes, lowest first."""
        return floor_nodes(self)

    @_locked
    def rooms(self, floor_id: str | None = None, refined: bool = False) -> list[RoomNode]:
        """Room nodes of one floor or all floors (refined masks after :meth:`refine`)."""
        return room_nodes(self, floor_id, refined)

    @_locked
    def edges(self, refined: bool = False) -> list[Edge]:
        """HAS_ROOM, CONNECTS and STAIRS edges."""
        return geometry_edges(self, refined)

    @_locked
    def apply_to(self, graph: SceneGraph, refined: bool = True) -> None:
        """Update the floor and room layers of ``graph`` in place."""
        apply_to_graph(self, graph, refined)
