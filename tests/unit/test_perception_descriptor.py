"""Offline visual descriptor: shape of the output, normalisation, discrimination."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.errors import InputError
from inherit_sg.model import Frame
from inherit_sg.perception.descriptor import NATIVE_DIM, DescriptorEncoder
from tests.toy_scene import ToyBox, look_at, render_toy_frame, toy_intrinsics

BOXES = [
    ToyBox("chair", (-0.8, 2.0, 0.45), (0.5, 0.5, 0.9), (190, 40, 40), yaw=0.3, pattern=0.15),
    ToyBox("cabinet", (0.8, 2.5, 0.6), (0.9, 0.45, 1.2), (45, 80, 185)),
    ToyBox("cube", (0.0, 1.5, 0.2), (0.4, 0.4, 0.4), (225, 200, 50), pattern=0.2),
    ToyBox("bin", (-1.8, 3.0, 0.5), (0.6, 0.6, 1.0), (235, 235, 230)),
    ToyBox("crate", (1.3, 1.2, 0.3), (0.6, 0.4, 0.6), (50, 140, 60), pattern=0.1),
]
VIEWS = [
    look_at((0.0, -0.8, 1.4), (0.0, 2.5, 0.5)),
    look_at((-1.5, -0.5, 1.6), (0.0, 2.2, 0.5)),
    look_at((1.2, -0.3, 1.2), (-0.3, 2.5, 0.4)),
]


@pytest.fixture(scope="module")
def frames() -> list[Frame]:
    return [
        render_toy_frame(BOXES, v, toy_intrinsics(240, 180), rgb_noise=2.0, seed=i)
        for i, v in enumerate(VIEWS)
    ]


def _masks(frame: Frame) -> list[np.ndarray]:
    assert frame.instances is not None
    return [frame.instances == i + 1 for i in range(len(BOXES))]


def test_output_shape_dtype_and_norm(frames: list[Frame]) -> None:
    enc = DescriptorEncoder()
    feats = enc.encode(frames[0].rgb, _masks(frames[0]))
    assert feats.shape == (len(BOXES), NATIVE_DIM) and feats.dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(feats, axis=1), 1.0, rtol=1e-5)
    g = enc.encode_image(frames[0].rgb)
    assert g.shape == (NATIVE_DIM,) and g.dtype == np.float32
    assert np.linalg.norm(g) == pytest.approx(1.0, rel=1e-5)
    assert enc.encode(frames[0].rgb, []).shape == (0, NATIVE_DIM)


def test_same_object_across_views_beats_different_colours(frames: list[Frame]) -> None:
    enc = DescriptorEncoder()
    feats = [enc.encode(f.rgb, _masks(f)) for f in frames]
    for a in range(len(frames)):
        for b in range(a + 1, len(frames)):
            sim = feats[a] @ feats[b].T
            for i in range(len(BOXES)):
                others = np.delete(sim[i], i)
                assert sim[i, i] > 0.75, (a, b, BOXES[i].label)
                assert sim[i, i] > others.max() + 0.2, (a, b, BOXES[i].label)


def test_same_colour_different_shape_is_less_similar_than_same_object() -> None:
    boxes = [
        ToyBox("tall", (-0.7, 2.2, 0.6), (0.4, 0.4, 1.2), (190, 40, 40)),
        ToyBox("flat", (0.8, 2.2, 0.15), (1.0, 0.6, 0.3), (190, 40, 40), pattern=0.2),
    ]
    enc = DescriptorEncoder()
    f1, f2 = (render_toy_frame(boxes, v, toy_intrinsics(240, 180)) for v in VIEWS[:2])
    a = enc.encode(f1.rgb, _masks_of(f1, 2))
    b = enc.encode(f2.rgb, _masks_of(f2, 2))
    sim = a @ b.T
    assert sim[0, 0] > sim[0, 1] and sim[1, 1] > sim[1, 0]


def _masks_of(frame: Frame, n: int) -> list[np.ndarray]:
    assert frame.instances is not None
    return [frame.instances == i + 1 for i in range(n)]


def test_other_dimensions_preserve_similarity(frames: list[Frame]) -> None:
    native = DescriptorEncoder()
    big = DescriptorEncoder(dim=384, image_dim=512)
    small = DescriptorEncoder(dim=64)
    masks = _masks(frames[0])
    n = native.encode(frames[0].rgb, masks)
    bigf = big.encode(frames[0].rgb, masks)
    assert bigf.shape == (len(BOXES), 384) and big.encode_image(frames[0].rgb).shape == (512,)
    np.testing.assert_allclose(bigf @ bigf.T, n @ n.T, atol=1e-4)  # isometry
    s = small.encode(frames[0].rgb, masks)
    assert s.shape == (len(BOXES), 64)
    np.testing.assert_allclose(np.linalg.norm(s, axis=1), 1.0, rtol=1e-5)


def test_global_descriptor_tells_views_apart(frames: list[Frame]) -> None:
    enc = DescriptorEncoder()
    g = np.stack([enc.encode_image(f.rgb) for f in frames])
    again = enc.encode_image(
        render_toy_frame(BOXES, VIEWS[0], toy_intrinsics(240, 180), rgb_noise=2.0, seed=9).rgb
    )
    same = float(g[0] @ again)
    assert same > 0.99
    assert same > float(g[0] @ g[1]) and same > float(g[0] @ g[2])


def test_deterministic_and_rejects_bad_input(frames: list[Frame]) -> None:
    enc = DescriptorEncoder()
    masks = _masks(frames[0])
    np.testing.assert_array_equal(
        enc.encode(frames[0].rgb, masks), enc.encode(frames[0].rgb, masks)
    )
    with pytest.raises(InputError, match="empty"):
        enc.encode(frames[0].rgb, [np.zeros(frames[0].depth.shape, dtype=bool)])
    with pytest.raises(InputError, match="shape"):
        enc.encode(frames[0].rgb, [np.ones((3, 3), dtype=bool)])
    with pytest.raises(InputError, match="uint8"):
        enc.encode_image(frames[0].rgb.astype(np.float32))


def test_large_masks_are_subsampled_consistently(frames: list[Frame]) -> None:
    full = DescriptorEncoder(max_pixels=10**9).encode(frames[0].rgb, _masks(frames[0]))
    sub = DescriptorEncoder(max_pixels=500).encode(frames[0].rgb, _masks(frames[0]))
    assert np.min(np.sum(full * sub, axis=1)) > 0.95
