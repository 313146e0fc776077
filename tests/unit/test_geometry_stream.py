"""The geometric stream on a rendered two-room walk: rooms, doors, events, scene graph,
best viewpoints and the BEV picture."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from inherit_sg.config import Config, GeometryConfig
from inherit_sg.errors import NodeNotFoundError
from inherit_sg.geometry import (
    GeometricStream,
    KeyframeSelected,
    RoomEntered,
    RoomsUpdated,
)
from inherit_sg.geometry.events import GeometryEvent
from inherit_sg.model import EdgeKind, FloorNode, NodeId, RoomNode, SceneGraph
from tests.unit.geometry_fixtures import look_pose, make_frame, two_room_walk, two_rooms


@pytest.fixture(scope="module")
def walk() -> tuple[GeometricStream, list[GeometryEvent]]:
    boxes = two_rooms()
    stream = GeometricStream(session_id="s1")
    events: list[GeometryEvent] = []
    for i, pose in enumerate(two_room_walk()):
        events += stream.process(make_frame(boxes, pose, i))
    stream.segment()
    return stream, events


def test_two_rooms_with_a_door_between_them(walk: tuple[GeometricStream, list]) -> None:
    stream, _ = walk
    rooms = stream.rooms()
    assert len(rooms) == 2
    a = next(r for r in rooms if r.position[0] < 4.0)
    b = next(r for r in rooms if r.position[0] > 4.0)
    assert a.position[:2] == pytest.approx((2.0, 2.0), abs=0.2)
    assert b.position[:2] == pytest.approx((6.0, 2.0), abs=0.2)
    assert a.mask is not None and 13.0 < a.mask.area_m2 <= 16.0
    assert a.mask.contains_xy(1.0, 3.0) and not a.mask.contains_xy(6.0, 2.0)
    assert stream.room_at(6.5, 1.0) == b.id and stream.room_at(1.0, 1.0) == a.id
    connects = [e for e in stream.edges() if e.kind is EdgeKind.CONNECTS]
    assert len(connects) == 1
    door = connects[0].prop("door")
    assert door[0] == pytest.approx(4.0, abs=0.15) and door[1] == pytest.approx(1.95, abs=0.3)
    assert 0.6 < connects[0].prop("width") < 1.2
    has_room = {e.dst for e in stream.edges() if e.kind is EdgeKind.HAS_ROOM}
    assert has_room == {a.id, b.id}


def test_events_and_keyframe_queue(walk: tuple[GeometricStream, list]) -> None:
    stream, events = walk
    kfs = [e for e in events if isinstance(e, KeyframeSelected)]
    assert kfs and kfs[0].reason == "first"
    assert len(stream.queue) == len(kfs) == stream.stats.keyframes
    assert all(e.keyframe.floor_id == "floor:0" for e in kfs)
    assert kfs[0].keyframe.id.startswith("kf:s1:")
    pending = stream.queue.get(timeout=0)
    assert pending is not None and pending.frame.index == kfs[0].frame_index
    assert any(isinstance(e, RoomsUpdated) and e.added for e in events)
    entered = [e for e in events if isinstance(e, RoomEntered)]
    assert entered and entered[-1].room_id == stream.room_at(6.0, 2.0)
    assert stream.current_room_id == entered[-1].room_id


def test_refine_keeps_rooms_disjoint_and_picks_views(walk: tuple[GeometricStream, list]) -> None:
    stream, _ = walk
    stream.refine()
    rooms = stream.rooms(refined=True)
    assert len(rooms) == 2
    masks = []
    for r in rooms:
        assert r.mask is not None
        m = np.zeros((200, 200), dtype=bool)
        r0 = round((r.mask.origin_y + 1.0) / 0.05)
        c0 = round((r.mask.origin_x + 1.0) / 0.05)
        h, w = r.mask.cells.shape
        m[r0 : r0 + h, c0 : c0 + w] = r.mask.cells
        masks.append(m)
        assert r.best_view is not None
        kf = next(k for k in stream.keyframes if k.id == r.best_view)
        assert r.mask.contains_xy(*kf.pose.translation[:2])  # seen from inside the room
    assert not (masks[0] & masks[1]).any()
    assert stream.update_points and stream.update_points[-1][0] == "floor:0"


def test_semantic_door_separates_an_open_arch() -> None:
    boxes = two_rooms(door=(0.5, 3.5))  # a 3 m wide opening: one room by geometry
    poses = two_room_walk()
    stream = GeometricStream(enqueue_keyframes=False)
    for i, pose in enumerate(poses):
        stream.process(make_frame(boxes, pose, i))
    stream.segment()
    assert len(stream.rooms()) == 1
    stream.add_door(4.0, 2.0, 0.0, width=3.0)
    stream.segment()
    stream.segment()  # hysteresis: two votes
    rooms = stream.rooms()
    assert len(rooms) == 2
    (fid, door), *_ = stream.doors()
    assert door.source == "semantic" and door.rooms is not None
    assert fid == "floor:0"
    connects = [e for e in stream.edges() if e.kind is EdgeKind.CONNECTS]
    assert len(connects) == 1 and connects[0].prop("source") == "semantic"


def test_apply_to_graph_keeps_semantic_fields(walk: tuple[GeometricStream, list]) -> None:
    stream, _ = walk
    graph = SceneGraph()
    stream.apply_to(graph, refined=False)
    floors = [n for n in graph.nodes() if isinstance(n, FloorNode)]
    rooms = [n for n in graph.nodes() if isinstance(n, RoomNode)]
    assert len(floors) == 1 and len(rooms) == 2
    assert {graph.parent(r.id) for r in rooms} == {"floor:0"}
    rooms[0].label, rooms[0].summary = "kitchen", "a kitchen"
    graph.flush_changes()
    stream.apply_to(graph, refined=False)
    again = graph.get(rooms[0].id)
    assert isinstance(again, RoomNode) and again.label == "kitchen" and again.summary
    assert not graph.changes.new_nodes
    assert len(list(graph.edges(EdgeKind.CONNECTS))) == 1
    stream.published_rooms.add("room:999")
    graph.add_or_update(RoomNode(id="room:999", label="gone"))
    stream.apply_to(graph, refined=False)
    assert "room:999" not in graph


def test_bev_picture_shows_the_rooms(walk: tuple[GeometricStream, list], tmp_path: Path) -> None:
    stream, _ = walk
    path = stream.save_bev(tmp_path / "bev.png")
    img = np.asarray(Image.open(path).convert("RGB"))
    g = stream.maps["floor:0"].grid
    scale = stream.cfg.bev_scale

    def pixel(x: float, y: float) -> np.ndarray:
        col = int((x - g.origin_x) / g.resolution * scale)
        row = int((g.shape[0] - (y - g.origin_y) / g.resolution) * scale)
        return img[row, col].astype(int)

    a, b = pixel(1.0, 3.2), pixel(7.0, 3.2)
    assert np.abs(a - b).sum() > 60  # each room has its own colour
    assert np.abs(a - 255).sum() > 30 and np.abs(b - 255).sum() > 30  # tinted, not plain
    wall = pixel(0.08, 3.2)
    assert wall.max() < 100
    with pytest.raises(NodeNotFoundError, match="floor:9"):
        stream.save_bev(tmp_path / "x.png", floor_id="floor:9")
    named = stream.bev(labels={stream.rooms()[0].id: "kitchen"})
    assert named.shape == img.shape and not np.array_equal(named, img)


def test_stream_config_sources() -> None:
    cfg = Config()
    cfg.store.image_feature_dim = 128
    assert GeometricStream(cfg).feature_dim == 128
    assert GeometricStream(GeometryConfig(cell_size=0.1)).cfg.cell_size == 0.1
    calls: list[tuple[int, ...]] = []

    def feature(rgb: np.ndarray) -> np.ndarray:
        calls.append(rgb.shape)
        return np.ones(8, dtype=np.float32)

    stream = GeometricStream(enqueue_keyframes=False, image_feature=feature)
    frame = make_frame(two_rooms(), look_pose(2, 2, 1.4, 0.0), 0)
    events = stream.process(frame)
    assert len(stream.queue) == 0 and isinstance(events[0], KeyframeSelected)
    feat = events[0].keyframe.global_feature
    assert calls == [(120, 160, 3)] and feat is not None and feat.shape == (8,)


def test_id_offsets_and_calls_from_a_worker_thread() -> None:
    import threading

    boxes = two_rooms()
    frames = [make_frame(boxes, p, i) for i, p in enumerate(two_room_walk())]
    stream = GeometricStream(enqueue_keyframes=False, first_room_id=40, first_floor_id=3)
    errors: list[BaseException] = []
    done = threading.Event()

    def worker() -> None:
        try:
            while not done.is_set():
                stream.rooms()
                stream.edges()
                stream.add_door(9.0, 9.0, 0.0)
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    t = threading.Thread(target=worker)
    t.start()
    for frame in frames:
        stream.process(frame)
    done.set()
    t.join(timeout=10)
    assert not errors
    assert [f.id for f in stream.floors()] == ["floor:3"]
    assert {r.id for r in stream.refine()} == {"room:40", "room:41"}


def test_an_object_belongs_to_the_floor_its_middle_stands_on() -> None:
    """A light hung from the ground floor's ceiling, just below the upper floor's
    surface, stays on the ground floor; a rug on the upper floor, with its middle a little
    below that floor's estimated surface, is on the upper floor."""
    from inherit_sg.geometry.floors import FloorState
    from inherit_sg.geometry.stream import FLOOR_BAND_M, RISES_FROM_M

    stream = GeometricStream(enqueue_keyframes=False)
    ground = FloorState(NodeId("floor:0"), camera_z=1.4, level=0)
    upper = FloorState(NodeId("floor:1"), camera_z=4.4, level=1)
    ground.estimates.append(0.0)
    upper.estimates.append(3.0)
    stream.tracker.floors = {ground.id: ground, upper.id: upper}
    ceiling_light_middle = 2.8 - 0.07
    assert stream.floor_of_height(ceiling_light_middle) == "floor:0"
    assert stream.floor_of_height(3.0 - FLOOR_BAND_M / 2) == "floor:1"
    assert stream.floor_of_height(0.5) == "floor:0"
    assert stream.floor_of_height(-0.2) == "floor:0"  # below every floor: the lowest
    # the top of a flight of stairs seen from the upper floor rises from the ground floor
    assert stream.floor_of_box(2.2, 3.6) == "floor:0"
    # a chair upstairs whose foot the depth noise pulls a little below the floor
    assert stream.floor_of_box(3.0 - RISES_FROM_M / 2, 3.9) == "floor:1"
    assert stream.floor_of_box(2.7, 2.84) == "floor:0"  # a ceiling light downstairs
