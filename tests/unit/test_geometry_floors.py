"""Floor tracking with hysteresis, and multi-floor walks through the geometric stream."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.config import GeometryConfig
from inherit_sg.geometry import FloorChanged, GeometricStream
from inherit_sg.geometry.floors import FloorTracker, FloorTransition, estimate_floor_z
from inherit_sg.model import EdgeKind
from tests.unit.geometry_fixtures import EYE, look_around, look_pose, make_frame, two_rooms


def _feed(tracker: FloorTracker, heights: list[float]) -> list[FloorTransition]:
    out = []
    for z in heights:
        t = tracker.update((0.0, 0.0, z), z - EYE)
        if t is not None:
            out.append(t)
    return out


def test_bobbing_camera_stays_on_one_floor() -> None:
    tracker = FloorTracker(GeometryConfig())
    rng = np.random.default_rng(0)
    assert _feed(tracker, list(EYE + rng.normal(0, 0.05, 200))) == []
    assert len(tracker.floors) == 1 and tracker.settled
    assert tracker.current is not None
    assert tracker.current.floor_z == pytest.approx(0.0, abs=0.05)


def test_climb_creates_a_floor_and_descending_re_enters_the_first() -> None:
    tracker = FloorTracker(GeometryConfig())
    up = [EYE] * 5 + list(np.linspace(EYE, EYE + 3.0, 8)) + [EYE + 3.0] * 6
    events = _feed(tracker, up)
    assert len(events) == 1
    first = events[0]
    assert first.created and not first.reordered
    down = list(np.linspace(EYE + 3.0, EYE, 8)) + [EYE] * 6
    events = _feed(tracker, down)
    assert len(events) == 1 and not events[0].created
    assert len(tracker.floors) == 2
    assert [f.level for f in tracker.ordered()] == [0, 1]
    assert tracker.ordered()[1].floor_z == pytest.approx(3.0, abs=0.05)


def test_a_floor_below_reorders_levels() -> None:
    tracker = FloorTracker(GeometryConfig())
    events = _feed(tracker, [EYE + 3.0] * 5 + [EYE] * 6)
    assert len(events) == 1 and events[0].reordered
    low, high = tracker.ordered()
    assert low.floor_z < high.floor_z and (low.level, high.level) == (0, 1)
    assert high.id == "floor:0" and low.id == "floor:1"


def test_floor_height_from_depth_points() -> None:
    rng = np.random.default_rng(1)
    floor = rng.normal(0.0, 0.01, 3000)
    table = rng.normal(0.75, 0.01, 800)
    wall = rng.uniform(0.0, 2.8, 3000)
    z = np.concatenate([floor, table, wall])
    assert estimate_floor_z(z, EYE) == pytest.approx(0.0, abs=0.03)
    assert estimate_floor_z(z[:10], EYE) is None


def test_no_floor_height_from_a_frame_that_sees_only_walls() -> None:
    """A camera tilted up sees walls and ceiling: points spread over many heights and no
    bin holds a surface; that is no estimate, not an error."""
    z = np.linspace(EYE - 2.4, EYE - 0.35, 400)
    assert estimate_floor_z(z, EYE) is None


def _walk(start_z: float, end_z: float) -> list:
    """Look around on one floor, climb/descend, look around on the other."""
    poses = look_around(2.0, 2.0, start_z + EYE)
    for z in np.linspace(start_z + EYE, end_z + EYE, 9)[1:-1]:
        poses.append(look_pose(2.0, 2.0, float(z), 0.0))
    poses += look_around(2.0, 2.0, end_z + EYE)
    return poses


def _run(poses: list) -> tuple[GeometricStream, list]:
    boxes = two_rooms(0.0) + two_rooms(3.0)
    stream = GeometricStream(enqueue_keyframes=False)
    events = []
    for i, pose in enumerate(poses):
        events += stream.process(make_frame(boxes, pose, i))
    return stream, events


def test_two_floor_walk_produces_two_floors_in_order() -> None:
    stream, events = _run(_walk(0.0, 3.0))
    changes = [e for e in events if isinstance(e, FloorChanged)]
    assert len(changes) == 1 and changes[0].created and changes[0].hard
    floors = stream.floors()
    assert [f.level for f in floors] == [0, 1]
    assert floors[0].z_min == pytest.approx(0.0, abs=0.05)
    assert floors[1].z_min == pytest.approx(3.0, abs=0.05)
    assert floors[0].z_max == pytest.approx(floors[1].z_min)
    assert stream.stats.frame_floors[0] == floors[0].id
    assert stream.stats.frame_floors[-1] == floors[1].id
    stairs = [e for e in stream.edges() if e.kind is EdgeKind.STAIRS]
    assert len(stairs) == 1 and (stairs[0].src, stairs[0].dst) == (floors[0].id, floors[1].id)
    assert stairs[0].prop("bottom")[2] < stairs[0].prop("top")[2]
    # Each floor has its own map with free space around the camera.
    assert set(stream.maps) == {floors[0].id, floors[1].id}
    hard = [
        e for e in events if getattr(e, "hard", False) and type(e).__name__ == "KeyframeSelected"
    ]
    assert hard and hard[0].keyframe.floor_id == floors[1].id


def test_walking_down_first_reorders_the_floors() -> None:
    stream, events = _run(_walk(3.0, 0.0))
    change = next(e for e in events if isinstance(e, FloorChanged))
    assert change.reordered
    floors = stream.floors()
    assert floors[0].id == change.to_floor and floors[0].level == 0
    stairs = next(e for e in stream.edges() if e.kind is EdgeKind.STAIRS)
    assert stairs.src == floors[0].id  # STAIRS always point up
