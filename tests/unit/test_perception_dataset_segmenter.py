"""Dataset segmenter: masks and labels from the frame's own instance image."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.model import Frame, Intrinsics, Pose
from inherit_sg.perception.dataset_segmenter import DatasetSegmenter, MaskNoise
from tests.toy_scene import ToyBox, look_at, render_toy_frame, toy_intrinsics


def _frame(instances: np.ndarray, labels: dict[int, str]) -> Frame:
    h, w = instances.shape
    return Frame(
        index=3,
        frame_id="f3",
        timestamp=0.0,
        rgb=np.zeros((h, w, 3), dtype=np.uint8),
        depth=np.ones((h, w), dtype=np.float32),
        pose=Pose.identity(),
        intrinsics=Intrinsics(w, h, 50.0, 50.0, w / 2, h / 2),
        instances=instances,
        instance_labels=labels,
    )


@pytest.fixture
def frame() -> Frame:
    inst = np.zeros((60, 80), dtype=np.uint16)
    inst[5:35, 5:45] = 7  # 1200 px
    inst[40:55, 50:70] = 3  # 300 px
    inst[0:3, 77:80] = 9  # 9 px: too small
    inst[50:60, 0:10] = 4  # 100 px, no label
    return _frame(inst, {7: "Office Chair", 3: "mug", 9: "pen"})


def test_labels_masks_and_order(frame: Frame) -> None:
    dets = DatasetSegmenter(min_pixels=20, erosion_px=0).segment(frame)
    assert [d.label for d in dets] == ["office chair", "mug"]
    chair, mug = dets
    assert chair.mask.shape == (60, 80) and chair.mask.dtype == bool
    assert chair.area == 1200 and chair.bbox_xyxy == (5, 5, 44, 34)
    assert mug.area == 300 and mug.score == 1.0
    assert not any(d.mask[0, 0] for d in dets)  # id 0 ignored


def test_min_fraction_drops_small_masks(frame: Frame) -> None:
    dets = DatasetSegmenter(min_pixels=1, min_fraction=0.1, erosion_px=0).segment(frame)
    assert [d.label for d in dets] == ["office chair"]  # 300 px < 10 % of 4800


def test_erosion_keeps_away_from_boundaries(frame: Frame) -> None:
    det = DatasetSegmenter(min_pixels=20, erosion_px=1).segment(frame)[0]
    assert det.area == 38 * 28
    assert det.bbox_xyxy == (6, 6, 43, 33)


def test_prompts_filter_by_label_words(frame: Frame) -> None:
    seg = DatasetSegmenter(min_pixels=20, erosion_px=0)
    assert [d.label for d in seg.segment(frame, ["chair"])] == ["office chair"]
    assert [d.label for d in seg.segment(frame, ["Mug", "sofa"])] == ["mug"]
    assert seg.segment(frame, ["hair"]) == []  # whole words only
    assert seg.segment(frame, ["table"]) == []


def test_frame_without_instances_gives_nothing() -> None:
    f = _frame(np.zeros((10, 10), np.uint16), {})
    f.instances = None
    assert DatasetSegmenter().segment(f) == []


def test_ignore_labels() -> None:
    inst = np.zeros((40, 40), dtype=np.uint16)
    inst[:20] = 1
    inst[20:] = 2
    dets = DatasetSegmenter(ignore_labels=["Wall"]).segment(_frame(inst, {1: "wall", 2: "bed"}))
    assert [d.label for d in dets] == ["bed"]


def test_noise_is_deterministic_and_perturbs() -> None:
    boxes = [
        ToyBox(f"box{i}", (-1.5 + 0.75 * i, 2.5, 0.3), (0.5, 0.5, 0.6), (60 * i, 100, 200))
        for i in range(5)
    ]
    frame = render_toy_frame(
        boxes, look_at((0, -0.5, 1.3), (0, 2.5, 0.3)), toy_intrinsics(160, 120)
    )
    clean = DatasetSegmenter(erosion_px=0).segment(frame)
    noisy = DatasetSegmenter(erosion_px=0, noise=MaskNoise(drop_rate=0.3, seed=1))
    a, b = noisy.segment(frame), noisy.segment(frame)
    assert [d.label for d in a] == [d.label for d in b]
    assert all(np.array_equal(x.mask, y.mask) for x, y in zip(a, b, strict=True))
    assert len(clean) == 5
    by_label = {d.label: d for d in clean}
    changed = [d for d in a if not np.array_equal(d.mask, by_label[d.label].mask)]
    assert changed  # boundaries were jittered
    for d in a:  # ... but each noisy mask still overlaps its object well
        truth = by_label[d.label].mask
        assert (d.mask & truth).sum() / (d.mask | truth).sum() > 0.6
        assert 0.0 <= d.score <= 1.0
    other_seed = DatasetSegmenter(erosion_px=0, noise=MaskNoise(drop_rate=0.3, seed=2))
    c = other_seed.segment(frame)
    assert [d.label for d in c] != [d.label for d in a] or any(
        not np.array_equal(x.mask, y.mask) for x, y in zip(a, c, strict=False)
    )
