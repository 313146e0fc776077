"""Exploration walks: every room, storeys in order, smooth turns, climbing stairs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from inherit_sg.ingest.synthetic.generate import generate_house
from inherit_sg.ingest.synthetic.trajectory import camera_pose


@pytest.fixture(scope="module", params=[(7, 2), (3, 3)])
def walked(request):
    seed, floors = request.param
    house = generate_house(seed, floors)
    return house, house.trajectory()


def _yaw(pose) -> float:
    forward = pose.rotation[:, 2]
    return math.atan2(forward[1], forward[0])


def test_camera_pose_axes():
    pose = camera_pose(1.0, 2.0, 1.4, 0.0, 0.0)
    r = pose.rotation
    assert np.allclose(r[:, 2], [1, 0, 0])  # forward along +x
    assert np.allclose(r[:, 0], [0, -1, 0])  # right
    assert np.allclose(r[:, 1], [0, 0, -1])  # image down is world down
    assert np.allclose(pose.translation, [1.0, 2.0, 1.4])


def test_walk_visits_every_room_and_floor_in_order(walked):
    house, traj = walked
    assert {r.id for r in house.scene.rooms} <= {r for r in traj.rooms if r}
    assert traj.floors == sorted(traj.floors)
    assert set(traj.floors) == set(range(len(house.plan.floors)))
    looks = {traj.rooms[i] for i, a in enumerate(traj.activity) if a == "look"}
    assert {r.id for r in house.scene.rooms} <= looks


def test_frames_rise_on_the_stairs(walked):
    house, traj = walked
    z = np.array([p.translation[2] for p in traj.poses])
    for stairs in house.plan.stairs:
        idx = [
            i
            for i, a in enumerate(traj.activity)
            if a == "stairs" and traj.floors[i] == stairs.from_floor
        ]
        assert len(idx) >= 5
        climb = z[idx[0] - 1 : idx[-1] + 2]
        assert np.all(np.diff(climb) > -0.03)
        assert climb[-1] - climb[0] == pytest.approx(stairs.z1 - stairs.z0, abs=0.05)


def test_motion_is_smooth_and_looks_slightly_down(walked):
    house, traj = walked
    yaws = np.array([_yaw(p) for p in traj.poses])
    steps = np.abs((np.diff(yaws) + np.pi) % (2 * np.pi) - np.pi)
    assert steps.max() < math.radians(37)
    pos = np.array([p.translation for p in traj.poses])
    assert np.linalg.norm(np.diff(pos[:, :2], axis=0), axis=1).max() < 0.75
    pitch = np.degrees(np.arcsin(-np.array([p.rotation[2, 2] for p in traj.poses])))
    glance = np.array([a == "glance" for a in traj.activity])
    assert pitch[~glance].min() > 7 and pitch[~glance].max() < 18
    # one steep look up at the ceiling in every room the walker stops in
    assert glance.sum() >= len(house.scene.rooms) - 1
    assert np.all(pitch[glance] < -55)
    for i, pose in enumerate(traj.poses):
        if traj.activity[i] != "stairs":
            eye = pose.translation[2] - house.plan.floors[traj.floors[i]].z
            assert 1.25 < eye < 1.55


def test_camera_never_inside_furniture(walked):
    house, traj = walked
    floor_z = {f.index: f.z for f in house.scene.floors}
    solid = [  # furniture one could walk into (not flat, not hanging above head height)
        o
        for o in house.scene.objects
        if not o.structural
        and o.bbox_max[2] - o.bbox_min[2] > 0.05
        and o.bbox_min[2] - floor_z[o.floor] < 1.8
    ]
    lo = np.array([o.bbox_min for o in solid])
    hi = np.array([o.bbox_max for o in solid])
    floor = np.array([o.floor for o in solid])
    for i, pose in enumerate(traj.poses):
        c = pose.translation
        inside = np.all((lo[:, :2] < c[:2]) & (c[:2] < hi[:, :2]), axis=1) & (
            floor == traj.floors[i]
        )
        assert not inside.any(), [solid[k].label for k in np.flatnonzero(inside)]


def test_frame_count_and_determinism():
    house = generate_house(7, 2)
    a, b = house.trajectory(), house.trajectory()
    assert 150 <= len(a) <= 1000
    assert all(np.array_equal(p.matrix, q.matrix) for p, q in zip(a.poses, b.poses, strict=True))
    other = house.trajectory(seed=8)
    assert not np.array_equal(other.poses[5].matrix, a.poses[5].matrix)


def test_close_looks_face_walls_and_furniture_up_close(walked):
    """Besides the look-around, the walker steps up to what it saw only from afar: close
    looks come in threes, 30° apart, from spots within the room."""
    house, traj = walked
    plain = house.trajectory(close=False)
    assert len(traj) > len(plain)
    assert traj.activity.count("look") > plain.activity.count("look")
    assert "glance" not in plain.activity
