"""The perception noise model: clean is identity, noisy rates, per-frame ids."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.ingest.synthetic.noise import (
    CONFUSIONS,
    LEVELS,
    PoseDrift,
    degrade_depth,
    degrade_instances,
    noise_config,
    renumber,
)
from inherit_sg.ingest.synthetic.trajectory import camera_pose
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

LABELS = ("chair", "sofa", "table", "mug", "cabinet", "lamp", "bed", "book")


def _tiles(n_side: int = 20, size: int = 12) -> tuple[np.ndarray, dict[int, str]]:
    """A grid of touching square instances with labels."""
    img = np.zeros((n_side * size, n_side * size), dtype=np.uint16)
    labels = {}
    for i in range(n_side):
        for j in range(n_side):
            k = i * n_side + j + 1
            img[i * size : (i + 1) * size, j * size : (j + 1) * size] = k
            labels[k] = LABELS[k % len(LABELS)]
    return img, labels


def test_clean_is_identity():
    img, labels = _tiles()
    ids, out = degrade_instances(img, labels, LEVELS["clean"], np.random.default_rng(0))
    assert np.array_equal(ids, img) and out == labels
    depth = np.full((10, 10), 2.5, dtype=np.float32)
    assert np.array_equal(degrade_depth(depth, LEVELS["clean"], np.random.default_rng(0)), depth)
    pose = camera_pose(1, 2, 1.4, 0.3, 0.2)
    assert PoseDrift(LEVELS["clean"], np.random.default_rng(0)).apply(pose) == pose


def test_noisy_rates_roughly_as_documented():
    config = noise_config("noisy")
    img, labels = _tiles()
    n = len(labels)
    dropped = split = merged = synonyms = confused = 0
    runs = 10
    for seed in range(runs):
        ids, out = degrade_instances(img, labels, config, np.random.default_rng(seed))
        kept = set(np.unique(ids)) - {0}
        assert kept == set(out)
        originals = {k for k in labels if (ids == k).any()}
        dropped += sum(1 for k in labels if not (ids[img == k] != 0).any())
        split += sum(1 for k in kept if k > n)
        merged += sum(1 for k in labels if (ids[img == k] != 0).all() and k not in originals)
        for k in originals:
            truth, seen = labels[k], out[k]
            if seen != truth:
                if seen in OBJECT_KINDS[truth].synonyms:
                    synonyms += 1
                elif seen in CONFUSIONS.get(truth, ()):
                    confused += 1
    total = n * runs
    assert 0.07 < dropped / total < 0.13
    assert 0.03 < split / total < 0.07
    assert 0.02 < merged / total < 0.07
    assert synonyms > 0.05 * total  # 15 % draws, some kinds have no other word
    assert 0.02 < confused / total < 0.08


def test_depth_noise_grows_with_depth_and_drops_pixels():
    config = noise_config("noisy")
    rng = np.random.default_rng(1)
    near = degrade_depth(np.full((200, 200), 1.0, dtype=np.float32), config, rng)
    far = degrade_depth(np.full((200, 200), 3.0, dtype=np.float32), config, rng)
    assert near[near > 0].std() == pytest.approx(0.01, rel=0.15)
    assert far[far > 0].std() == pytest.approx(0.09, rel=0.15)
    assert 0.002 < (near == 0).mean() < 0.01
    zero = degrade_depth(np.zeros((50, 50), dtype=np.float32), config, rng)
    assert not zero.any()


def test_renumber_hides_global_ids():
    img = np.zeros((40, 40), dtype=np.uint16)
    img[:20, :20], img[20:, :20], img[:, 20:] = 101, 7, 3000
    labels = {101: "sofa", 7: "mug", 3000: "lamp"}
    out, out_labels = renumber(img, labels, np.random.default_rng(4))
    assert out.dtype == np.uint16
    assert set(out_labels) == {1, 2, 3} == set(np.unique(out))
    for k, label in labels.items():
        new = np.unique(out[img == k])
        assert len(new) == 1 and out_labels[int(new[0])] == label
    assert np.array_equal(out == 0, img == 0)
    perms = {
        tuple(renumber(img, labels, np.random.default_rng(s))[0][[0, 30, 0], [0, 0, 30]])
        for s in range(12)
    }
    assert len(perms) > 1


def test_pose_drift_is_small_and_accumulates():
    drift = PoseDrift(noise_config("noisy"), np.random.default_rng(0))
    pose = camera_pose(1, 2, 1.4, 0.3, 0.2)
    offsets = [np.linalg.norm(drift.apply(pose).translation - pose.translation) for _ in range(400)]
    assert offsets[0] < 0.02
    assert 0.005 < offsets[-1] < 0.3


def test_unknown_level_is_rejected():
    with pytest.raises(ValueError, match="noise level"):
        noise_config("extreme")
