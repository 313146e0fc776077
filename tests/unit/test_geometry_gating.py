"""Global image feature, keyframe gate and the bounded keyframe queue."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from inherit_sg.geometry.gating import KeyframeGate, KeyframeQueue, PendingKeyframe
from inherit_sg.geometry.image_feature import cosine, global_image_feature
from inherit_sg.model import Keyframe, Pose
from tests.unit.geometry_fixtures import look_pose, make_frame, palette, two_rooms


def _image(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    img = np.zeros((120, 160, 3), dtype=np.uint8)
    for _ in range(6):
        r, c = rng.integers(0, 100), rng.integers(0, 140)
        img[r : r + rng.integers(10, 60), c : c + rng.integers(10, 80)] = rng.integers(0, 255, 3)
    return img


@pytest.mark.parametrize("dim", [256, 128, 512])
def test_feature_size_and_norm(dim: int) -> None:
    f = global_image_feature(_image(0), dim)
    assert f.shape == (dim,) and f.dtype == np.float32
    assert np.linalg.norm(f) == pytest.approx(1.0, abs=1e-5)


def test_feature_similarity_tracks_appearance() -> None:
    a, b = _image(1), _image(2)
    fa, fb = global_image_feature(a), global_image_feature(b)
    assert cosine(fa, global_image_feature(a.copy())) == pytest.approx(1.0)
    shifted = np.roll(a, 3, axis=1)
    assert cosine(fa, global_image_feature(shifted)) > 0.95
    assert cosine(fa, fb) < 0.9


def test_gate_fires_on_a_scene_change_and_not_on_a_still_camera() -> None:
    boxes = two_rooms()
    pose = look_pose(2.0, 2.0, 1.4, 0.0)
    gate = KeyframeGate(similarity=0.9, translation=1.0, rotation_deg=30.0, min_gap=0)
    still = make_frame(boxes, pose, 0)
    feat = global_image_feature(still.rgb)
    decisions = [gate.check(i, feat, pose) for i in range(10)]
    assert decisions[0].selected and decisions[0].reason == "first"
    assert not any(d.selected for d in decisions[1:])
    other = make_frame(boxes, pose, 10, colours=palette(len(boxes), seed=7))
    changed = gate.check(10, global_image_feature(other.rgb), pose)
    assert changed.selected and changed.reason == "appearance" and changed.similarity < 0.9
    moved = look_pose(3.5, 2.0, 1.4, 0.0)
    d = gate.check(11, global_image_feature(other.rgb), moved)
    assert d.selected and d.reason == "pose"
    turned = look_pose(3.5, 2.0, 1.4, 0.9)
    assert gate.check(12, global_image_feature(other.rgb), turned).reason == "pose"
    assert gate.check(13, global_image_feature(other.rgb), turned, force=True).reason == "forced"


def test_gate_respects_the_minimum_gap() -> None:
    gate = KeyframeGate(similarity=0.99, min_gap=3)
    pose = Pose.identity()
    assert gate.check(0, global_image_feature(_image(1)), pose).selected
    assert not gate.check(1, global_image_feature(_image(2)), pose).selected
    assert gate.check(3, global_image_feature(_image(3)), pose).selected


def _pending(i: int, hard: bool = False) -> PendingKeyframe:
    kf = Keyframe(id=f"kf:{i}", session_id="", timestamp=float(i), pose=Pose.identity())
    frame = make_frame(two_rooms(), look_pose(2, 2, 1.4, 0.0), i)
    return PendingKeyframe(kf, frame, hard)


def test_queue_drops_the_oldest_soft_keyframe_when_full() -> None:
    q = KeyframeQueue(3)
    items = [_pending(0, hard=True), _pending(1), _pending(2)]
    for it in items:
        assert q.put(it) is None
    dropped = q.put(_pending(3))
    assert dropped is not None and dropped.keyframe.id == "kf:1"
    assert q.dropped == 1 and len(q) == 3
    assert [p.keyframe.id for p in q.drain()] == ["kf:0", "kf:2", "kf:3"]
    full_of_hard = KeyframeQueue(1)
    full_of_hard.put(_pending(5, hard=True))
    assert full_of_hard.put(_pending(6, hard=True)).keyframe.id == "kf:5"  # type: ignore[union-attr]
    assert full_of_hard.dropped_hard == 1


def test_queue_hands_keyframes_to_a_consumer_thread() -> None:
    q = KeyframeQueue(8)
    got: list[str] = []

    def consume() -> None:
        while (item := q.get(timeout=5.0)) is not None:
            got.append(item.keyframe.id)

    worker = threading.Thread(target=consume)
    worker.start()
    for i in range(5):
        q.put(_pending(i))
    q.close()
    worker.join(timeout=10.0)
    assert got == [f"kf:{i}" for i in range(5)]
    assert q.get(timeout=0.01) is None
    with pytest.raises(RuntimeError):
        q.put(_pending(9))
    with pytest.raises(ValueError):
        KeyframeQueue(0)


def test_a_producer_waits_for_room_until_the_consumer_takes_a_keyframe() -> None:
    q = KeyframeQueue(2)
    q.put(_pending(0))
    q.put(_pending(1))
    assert q.wait_below(2, timeout=0.01) is False  # full: no room
    taken: list[str] = []

    def consume_one() -> None:
        item = q.get(timeout=5.0)
        assert item is not None
        taken.append(item.keyframe.id)

    worker = threading.Timer(0.05, consume_one)
    worker.start()
    assert q.wait_below(2, timeout=5.0) is True  # woken by the consumer's get
    worker.join()
    assert taken == ["kf:0"] and len(q) == 1
    q.close()
    assert q.wait_below(0, timeout=0.01) is True  # a closed queue never blocks
