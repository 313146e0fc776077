"""Back-projection, association, fusion and duplicate removal of object observations."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from inherit_sg.mapping.association import AssociationParams, associate
from inherit_sg.mapping.backproject import (
    Observation,
    backproject_mask,
    observe,
    robust_box,
    voxel_downsample,
)
from inherit_sg.mapping.object_map import ObjectMap, pieces_of_one
from inherit_sg.model import BBox3D, Frame, Intrinsics, Pose

K = Intrinsics(160, 120, 100.0, 100.0, 79.5, 59.5, 1000.0)


def _frame(depth: np.ndarray, pose: Pose | None = None, name: str = "f0", t: float = 0.0) -> Frame:
    return Frame(
        0,
        name,
        t,
        np.zeros((120, 160, 3), np.uint8),
        depth.astype(np.float32),
        pose or Pose.identity(),
        K,
    )


def _wall_with_box() -> tuple[Frame, np.ndarray]:
    depth = np.full((120, 160), 4.0)
    mask = np.zeros((120, 160), bool)
    mask[40:80, 60:100] = True
    depth[mask] = 2.0
    return _frame(depth), mask


def test_backprojection_lands_on_the_surface() -> None:
    frame, mask = _wall_with_box()
    pts = backproject_mask(frame, mask)
    assert pts is not None
    assert np.allclose(pts[:, 2], 2.0, atol=1e-6)
    # pixel columns 62..97 after erosion -> x = (u - cx)/fx * z
    assert pts[:, 0].min() == pytest.approx((62 - 79.5) / 100 * 2.0, abs=0.05)


def test_mask_edges_and_outliers_do_not_inflate_the_box() -> None:
    frame, mask = _wall_with_box()
    bleed = mask.copy()
    bleed[40:80, 100:103] = True  # border pixels that see the far wall
    depth = frame.depth.copy()
    depth[50, 70] = 0.0  # a hole
    depth[60, 80] = 7.5  # a stray far reading
    obs = observe(_frame(depth), bleed, "box")
    assert obs is not None
    assert obs.bbox.max[2] < 2.1 and obs.bbox.min[2] > 1.9


def test_too_few_valid_pixels_gives_no_observation() -> None:
    _, mask = _wall_with_box()
    assert observe(_frame(np.zeros((120, 160))), mask, "box") is None


def _whole_frame_points(frame: Frame, mask: np.ndarray) -> np.ndarray | None:
    """Back-projection worked on the whole frame, as a reference for the cropped one."""
    import cv2

    m = mask.astype(np.uint8)
    eroded = cv2.erode(m, np.ones((5, 5), np.uint8))
    m = eroded if int(eroded.sum()) >= 20 else m
    rows, cols = np.nonzero((m > 0) & (frame.depth > 0.1) & (frame.depth < 8.0))
    if len(rows) < 20:
        return None
    z = frame.depth[rows, cols].astype(np.float64)
    med = np.median(z)
    mad = np.median(np.abs(z - med)) * 1.4826 + 0.02
    keep = np.abs(z - med) <= 3.0 * mad + 0.05 * med
    rows, cols, z = rows[keep], cols[keep], z[keep]
    if len(z) < 20:
        return None
    cam = np.stack([(cols - K.cx) / K.fx * z, (rows - K.cy) / K.fy * z, z], axis=1)
    return voxel_downsample(frame.pose.transform_points(cam), 0.03)


def test_backprojection_on_the_mask_box_equals_the_whole_frame() -> None:
    """Masks touching the image border, thin ones and scattered ones: working on the
    mask's box gives exactly the points and pixel count of working on the whole frame."""
    rng = np.random.default_rng(3)
    depth = rng.uniform(0.5, 6.0, (120, 160))
    depth[rng.random((120, 160)) < 0.05] = 0.0  # holes
    c, s_ = np.cos(0.7), np.sin(0.7)
    pose = Pose.from_matrix([[c, -s_, 0, 1.0], [s_, c, 0, -2.0], [0, 0, 1, 0.5], [0, 0, 0, 1]])
    frame = _frame(depth, pose)
    masks = []
    for y0, y1, x0, x1 in [
        (0, 30, 0, 40),
        (90, 120, 130, 160),
        (10, 13, 20, 140),
        (0, 120, 0, 160),
    ]:
        m = np.zeros((120, 160), bool)
        m[y0:y1, x0:x1] = True
        masks.append(m)
    masks.append(rng.random((120, 160)) < 0.3)  # scattered pixels: erosion empties it
    masks.append(np.zeros((120, 160), bool))
    for mask in masks:
        got, want = backproject_mask(frame, mask), _whole_frame_points(frame, mask)
        assert (got is None) == (want is None)
        if got is not None:
            assert np.array_equal(got, want)
            obs = observe(frame, mask, "thing")
            assert obs is not None and obs.pixel_count == int(mask.sum())


def test_voxel_downsample_and_robust_box() -> None:
    pts = np.random.default_rng(0).uniform(0, 1, (5000, 3))
    down = voxel_downsample(pts, 0.1)
    assert 900 <= len(down) <= 1000
    box = robust_box(np.vstack([pts, [[50.0, 50.0, 50.0]]]))
    assert box.max[0] < 1.01


def _obs(
    label: str,
    centre: tuple[float, float, float],
    size: float = 0.5,
    feat: np.ndarray | None = None,
    kf: str = "k",
) -> Observation:
    c = np.asarray(centre, float)
    rng = np.random.default_rng(abs(hash((label, centre))) % 2**32)
    pts = c + rng.uniform(-size / 2, size / 2, (200, 3))
    return Observation(label, pts, robust_box(pts, 0, 100), c, 500, 0.2, 1.0, feat, kf, 0.0)


def _unit(v: list[float]) -> np.ndarray:
    a = np.asarray(v, dtype=np.float32)
    return a / np.linalg.norm(a)


def _same_label(a: str, b: str) -> float:
    return 1.0 if a == b else 0.0


def test_two_chairs_seen_together_stay_two() -> None:
    omap = ObjectMap(_same_label)
    omap.integrate([_obs("chair", (0, 0, 0.45)), _obs("chair", (0.7, 0, 0.45))], "floor:0")
    assert len(omap) == 2
    # a second view of both, slightly shifted, fuses into the same two nodes
    res = omap.integrate(
        [_obs("chair", (0.72, 0.02, 0.45)), _obs("chair", (0.03, 0, 0.45))], "floor:0"
    )
    assert len(omap) == 2 and not res.created
    assert {m.node_id for m in res.matched} == set(omap.objects)


def test_a_new_chair_beside_a_known_one_is_a_new_node() -> None:
    omap = ObjectMap(_same_label)
    omap.integrate([_obs("chair", (0, 0, 0.45))], "floor:0")
    res = omap.integrate([_obs("chair", (0.9, 0.0, 0.45))], "floor:0")
    assert len(res.created) == 1 and len(omap) == 2


def test_stage_one_matches_on_overlap_and_appearance_across_labels() -> None:
    f = _unit([1, 0, 0, 0])
    omap = ObjectMap(_same_label)
    omap.integrate([_obs("sofa", (0, 0, 0.4), 1.0, f)], "floor:0")
    res = omap.integrate([_obs("couch", (0.05, 0, 0.4), 1.0, f)], "floor:0")
    assert res.matched and res.matched[0].stage == 1
    node = next(iter(omap.objects.values()))
    assert node.label_votes == Counter({"sofa": 1, "couch": 1})


def test_new_label_matches_by_text_similarity_only_when_close() -> None:
    def sim(a: str, b: str) -> float:
        return 0.9 if {a, b} == {"sofa", "couch"} else 0.0

    omap = ObjectMap(sim)
    omap.integrate([_obs("sofa", (0, 0, 0.4), 1.0)], "floor:0")
    assert not omap.integrate([_obs("couch", (3.0, 0, 0.4), 1.0)], "floor:0").matched
    assert omap.integrate([_obs("couch", (0.1, 0, 0.4), 1.0)], "floor:0").matched


def test_open_vocabulary_needs_strict_visual_similarity() -> None:
    a, b = _unit([1, 0.05, 0, 0]), _unit([0.2, 1, 0, 0])
    candidates_map = ObjectMap(_same_label)
    candidates_map.integrate([_obs("object", (0, 0, 0.3), 0.4, a)], "floor:0")
    tracked = list(candidates_map.objects.values())
    params = AssociationParams()
    assert not associate([_obs("object", (0.1, 0, 0.3), 0.4, b)], tracked, params, _same_label)
    assert associate([_obs("object", (0.1, 0, 0.3), 0.4, a)], tracked, params, _same_label)


def test_floors_are_kept_apart() -> None:
    omap = ObjectMap(_same_label)
    omap.integrate([_obs("chair", (0, 0, 0.45))], "floor:0")
    res = omap.integrate([_obs("chair", (0, 0, 0.45))], "floor:1")
    assert res.created


def test_fusion_grows_the_box_and_keeps_the_most_central_view() -> None:
    omap = ObjectMap(_same_label)
    left = _obs("sofa", (0, 0, 0.4), 0.8, kf="k1")
    left.centre_offset = 0.6
    omap.integrate([left], "floor:0")
    right = _obs("sofa", (0.5, 0, 0.4), 0.8, kf="k2")
    right.centre_offset = 0.1
    omap.integrate([right], "floor:0")
    (obj,) = omap.objects.values()
    assert obj.node.observation_count == 2
    assert obj.node.bbox.max[0] > 0.8 and obj.node.bbox.min[0] < -0.3
    assert obj.node.best_keyframe == "k2" and obj.node.keyframe_ids == ["k1", "k2"]


def test_duplicates_are_merged() -> None:
    omap = ObjectMap(_same_label)
    omap.integrate([_obs("table", (0, 0, 0.4), 1.0)], "floor:0")
    node = next(iter(omap.objects.values()))
    # force a split: a second node overlapping the first
    omap.integrate([_obs("table", (5, 5, 0.4), 1.0)], "floor:0")
    second = next(o for o in omap.objects.values() if o is not node)
    second.points = node.points + 0.1
    second.node.bbox = BBox3D(
        tuple(np.asarray(node.node.bbox.min) + 0.1), tuple(np.asarray(node.node.bbox.max) + 0.1)
    )
    merged = omap.remove_duplicates()
    assert merged == [(node.id, second.id)] or merged == [(second.id, node.id)]
    assert len(omap) == 1 and omap.removed


def test_overlapping_pieces_of_one_staircase_are_one_object() -> None:
    # a staircase seen a flight at a time: same width and height, overlapping lengthwise
    lower = BBox3D((4.68, 1.70, 0.10), (5.66, 5.05, 2.69))
    upper = BBox3D((4.68, 4.40, 0.10), (5.66, 5.80, 3.07))
    assert lower.intersection_volume(upper) / upper.volume < 0.5  # the plain rule misses it
    assert pieces_of_one(lower, upper)
    # two chairs side by side whose boxes just touch stay two chairs
    chair = BBox3D((0.0, 0.0, 0.0), (0.45, 0.45, 0.9))
    neighbour = BBox3D((0.43, 0.0, 0.0), (0.88, 0.45, 0.9))
    assert not pieces_of_one(chair, neighbour)
    # boxes matching in one axis only (an L of counters) stay apart
    run_a = BBox3D((0.0, 0.0, 0.0), (3.0, 0.6, 0.9))
    run_b = BBox3D((2.4, 0.0, 0.0), (3.0, 2.5, 0.9))
    assert not pieces_of_one(run_a, run_b)
