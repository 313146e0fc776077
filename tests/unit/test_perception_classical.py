"""Classical depth + colour segmenter on rendered boxes in a room and on real Replica."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.model import Frame, Intrinsics, Pose
from inherit_sg.perception.classical_segmenter import (
    ClassicalSegmenter,
    chroma_edges,
    depth_edges,
)
from inherit_sg.perception.planes import backproject, structural_planes
from tests.toy_scene import ToyBox, look_at, render_toy_frame, toy_intrinsics

BOXES = [
    ToyBox("chair", (-1.0, 2.0, 0.45), (0.5, 0.5, 0.9), (190, 40, 40), yaw=0.3, pattern=0.1),
    ToyBox("cabinet", (0.8, 2.5, 0.6), (0.9, 0.45, 1.2), (45, 80, 185)),
    ToyBox("box", (0.0, 1.5, 0.2), (0.4, 0.4, 0.4), (225, 200, 50), pattern=0.2),
    # touches the yellow box at the same depth: only colour separates them
    ToyBox("crate", (0.35, 1.5, 0.15), (0.3, 0.4, 0.3), (50, 140, 60)),
]


@pytest.fixture(scope="module")
def frame() -> Frame:
    return render_toy_frame(
        BOXES,
        look_at((0.0, -0.8, 1.4), (0.0, 2.5, 0.5)),
        toy_intrinsics(320, 240),
        rgb_noise=2.0,
        depth_noise=0.002,
    )


def _iou(a: np.ndarray, b: np.ndarray) -> float:
    return float((a & b).sum() / max(1, (a | b).sum()))


def test_boxes_in_front_of_a_wall_become_one_mask_each(frame: Frame) -> None:
    dets = ClassicalSegmenter().segment(frame)
    assert frame.instances is not None
    assert len(dets) == len(BOXES)
    matched = set()
    for det in dets:
        assert det.label == "object" and 0.0 <= det.score <= 1.0
        ids, counts = np.unique(frame.instances[det.mask], return_counts=True)
        best = int(ids[counts.argmax()])
        assert best != 0, "a mask landed on the floor or a wall"
        assert counts.max() / counts.sum() > 0.97  # pure
        assert _iou(det.mask, frame.instances == best) > 0.8
        matched.add(best)
    assert matched == {1, 2, 3, 4}
    assert all(d.score > 0.8 for d in dets)  # every box stands out in depth


def test_structural_planes_cover_floor_and_walls_not_boxes(frame: Frame) -> None:
    assert frame.instances is not None
    structure = structural_planes(backproject(frame.depth, frame.intrinsics), frame.depth > 0)
    room = frame.instances == 0
    assert structure[room].mean() > 0.9
    assert structure[~room].mean() < 0.1


def test_without_colour_touching_boxes_merge(frame: Frame) -> None:
    dets = ClassicalSegmenter(use_colour=False).segment(frame)
    assert len(dets) == len(BOXES) - 1


def test_edges_detect_depth_jumps_and_chroma_not_shading() -> None:
    depth = np.full((20, 20), 2.0, dtype=np.float32)
    depth[:, 10:] = 3.0
    edges = depth_edges(depth)
    assert edges[:, 9:11].all() and not edges[:, :8].any() and not edges[:, 12:].any()
    ramp = np.linspace(60, 250, 40).astype(np.uint8)
    shaded = np.stack([ramp, ramp // 4, ramp // 4], axis=-1)[None].repeat(40, axis=0)
    assert chroma_edges(shaded).mean() < 0.01  # a shaded red surface has no colour edge
    two = np.zeros((40, 40, 3), dtype=np.uint8)
    two[:, :20] = (190, 40, 40)
    two[:, 20:] = (45, 80, 185)
    assert chroma_edges(two)[:, 19:21].all()


def test_prompts_other_than_generic_give_nothing(frame: Frame) -> None:
    seg = ClassicalSegmenter()
    assert seg.segment(frame, ["chair"]) == []
    assert len(seg.segment(frame, ["object"])) == len(BOXES)


def test_real_replica_frame_gives_plausible_masks(real_data: Path) -> None:
    root = real_data / "replica_office0"
    rgb = cv2.imread(str(root / "results" / "frame000000.jpg"))
    depth_raw = cv2.imread(str(root / "results" / "depth000000.png"), cv2.IMREAD_UNCHANGED)
    if rgb is None or depth_raw is None:
        pytest.skip("replica frames unreadable")
    h, w = depth_raw.shape
    k = Intrinsics(w, h, 600.0, 600.0, 599.5, 339.5, 6553.5)
    frame = Frame(
        0, "0", 0.0, np.ascontiguousarray(rgb[..., ::-1]), depth_raw / np.float32(6553.5),
        Pose.identity(), k,
    )  # fmt: skip
    dets = ClassicalSegmenter().segment(frame.validate())
    assert 3 <= len(dets) <= 60
    union = np.zeros((h, w), dtype=bool)
    for det in dets:
        assert not (union & det.mask).any()  # masks are disjoint
        union |= det.mask
        assert det.area < 0.5 * h * w
    # walls and floor were rejected: the masks do not cover the whole view
    assert 0.05 < union.mean() < 0.8
