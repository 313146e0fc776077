"""Result types, observation crops and hand-written preprocessing of the perception layer."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.errors import InputError
from inherit_sg.perception.base import (
    ObjectObservation,
    check_masks,
    l2_normalise,
    make_detection,
    mask_bbox,
)
from inherit_sg.perception.preprocess import (
    masked_crop,
    normalise,
    patch_weights,
    resize,
    round_to_multiple,
    square_box,
    to_batch,
)
from tests.toy_scene import ToyBox, look_at, render_toy_frame, toy_intrinsics


def test_mask_bbox_is_inclusive_and_none_for_empty() -> None:
    mask = np.zeros((10, 12), dtype=bool)
    assert mask_bbox(mask) is None
    mask[2:5, 3:9] = True
    assert mask_bbox(mask) == (3, 2, 8, 4)


def test_make_detection_lowercases_and_boxes() -> None:
    mask = np.zeros((8, 8), dtype=np.uint8)
    mask[1:3, 1:4] = 1
    det = make_detection(mask, "  Office Chair ", 0.7)
    assert det is not None
    assert det.label == "office chair"
    assert det.mask.dtype == bool and det.area == 6
    assert det.bbox_xyxy == (1, 1, 3, 2)
    assert make_detection(np.zeros((4, 4), bool), "x", 1.0) is None


def test_observation_from_frame_crops_with_margin() -> None:
    frame = render_toy_frame(
        [ToyBox("chair", (0.0, 2.0, 0.45), (0.5, 0.5, 0.9), (190, 40, 40))],
        look_at((0.0, -0.8, 1.4), (0.0, 2.5, 0.5)),
        toy_intrinsics(80, 60),
    )
    assert frame.instances is not None
    det = make_detection(np.asarray(frame.instances == 1), "chair", 1.0)
    assert det is not None
    obs = ObjectObservation.from_frame(frame, det, (0.5, 0.5, 0.9), room="Kitchen", margin=2)
    x0, y0, x1, y1 = det.bbox_xyxy
    assert obs.rgb.shape[:2] == obs.mask.shape
    assert obs.mask.shape[0] <= y1 - y0 + 1 + 4 and obs.mask.shape[1] <= x1 - x0 + 1 + 4
    assert obs.mask.sum() == det.area  # the whole object is inside the crop
    assert (obs.rgb[obs.mask][:, 0] > obs.rgb[obs.mask][:, 2]).all()  # red pixels


def test_observation_rejects_mismatched_mask() -> None:
    with pytest.raises(InputError, match="mask"):
        ObjectObservation("cup", np.zeros((4, 4, 3), np.uint8), np.zeros((3, 4), bool), (1, 1, 1))
    with pytest.raises(InputError, match="uint8"):
        ObjectObservation("cup", np.zeros((4, 4, 3), np.float32), np.zeros((4, 4), bool), (1, 1, 1))


def test_check_masks_names_bad_mask() -> None:
    with pytest.raises(InputError, match="mask 1"):
        check_masks([np.zeros((4, 4), bool), np.zeros((5, 4), bool)], (4, 4))


def test_l2_normalise_rows_and_zero_safe() -> None:
    x = l2_normalise(np.array([[3.0, 4.0], [0.0, 0.0]]))
    assert x.dtype == np.float32
    np.testing.assert_allclose(x[0], [0.6, 0.8], rtol=1e-6)
    assert not np.isnan(x).any()


def test_normalise_and_batch_layout() -> None:
    img = np.full((4, 6, 3), 255, dtype=np.uint8)
    img[..., 1] = 0
    x = normalise(img, (0.5, 0.5, 0.5), (0.5, 0.5, 0.5))
    assert x.shape == (3, 4, 6) and x.dtype == np.float32
    np.testing.assert_allclose(x[0], 1.0)
    np.testing.assert_allclose(x[1], -1.0)
    b = to_batch([img, img[:2]], 8, 8)
    assert b.shape == (2, 3, 8, 8)


def test_resize_and_rounding() -> None:
    img = np.arange(16 * 20, dtype=np.float32).reshape(16, 20)
    assert resize(img, 8, 10).shape == (8, 10)
    assert resize(img, 32, 40).shape == (32, 40)
    assert round_to_multiple(230, 16) == 224 and round_to_multiple(3, 16) == 16


def test_square_box_stays_inside_image() -> None:
    x0, y0, x1, y1 = square_box((90, 0, 99, 9), (50, 100), margin=0.5)
    assert x1 - x0 == y1 - y0 == 20
    assert x0 >= 0 and x1 <= 100 and y0 >= 0 and y1 <= 50


def test_masked_crop_fills_outside_and_reports_coverage() -> None:
    rgb = np.zeros((40, 40, 3), dtype=np.uint8)
    rgb[10:20, 10:20] = (255, 0, 0)
    mask = np.zeros((40, 40), dtype=bool)
    mask[10:20, 10:20] = True
    crop, coverage = masked_crop(rgb, mask, 32, fill=(0.0, 0.0, 1.0), margin=0.5)
    assert crop.shape == (32, 32, 3) and coverage.shape == (32, 32)
    assert tuple(crop[16, 16]) == (255, 0, 0)
    assert tuple(crop[0, 0]) == (0, 0, 255)  # outside the mask → fill colour
    assert 0.2 < coverage.mean() < 0.3  # 10x10 mask in a 20x20 window
    w = patch_weights(coverage, 8)
    assert w.shape == (16,) and w.max() > 0.9 and w.min() < 0.05
