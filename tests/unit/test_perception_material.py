"""Material from texture: statistics and names on synthetic patches, and the renderer's
material looks they are meant to read."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.ingest.synthetic.render_materials import (
    MATERIAL_CODE,
    material_code,
    pattern,
    specular,
    value_noise,
)
from inherit_sg.model import Frame, Intrinsics, Pose
from inherit_sg.perception.base import Detection
from inherit_sg.perception.colour_names import linear_to_srgb, srgb_to_linear
from inherit_sg.perception.material import (
    classify,
    frame_noise,
    fuse_votes,
    material_name,
    texture_stats,
)

H, W = 48, 64


def _patch(multiplier: np.ndarray, albedo: tuple[int, int, int] = (150, 100, 60)) -> np.ndarray:
    """An sRGB patch of ``albedo`` lit from the left (a smooth gradient), with a step in
    lighting between two faces and the light multiplied by ``multiplier``."""
    shade = np.linspace(0.35, 0.9, W)[None, :] * np.ones((H, 1))
    shade[:, W // 2 :] *= 0.6  # a second face, less lit
    lin = srgb_to_linear(np.asarray(albedo)) * (shade * multiplier)[..., None]
    return np.round(linear_to_srgb(lin)).astype(np.uint8)


def _plane_points() -> np.ndarray:
    """World points of a vertical 0.64 × 0.48 m face at 1 cm per pixel."""
    ys, xs = np.mgrid[0:H, 0:W]
    return np.stack([xs * 0.01, np.full(xs.shape, 2.0), 1.0 - ys * 0.01], axis=-1).reshape(-1, 3)


def _rendered(material: str) -> np.ndarray:
    codes = np.full(H * W, material_code(material), dtype=np.uint8)
    mult = pattern(codes, _plane_points().astype(np.float32), np.ones(H * W, np.float32))
    return _patch(mult.reshape(H, W))


MASK = np.ones((H, W), dtype=bool)


@pytest.mark.parametrize(
    ("material", "expected"),
    [
        ("wood", "wood"),
        ("fabric", "fabric"),
        ("stone", "stone"),
        ("plastic", "plastic"),
        ("metal", "unknown"),
        ("ceramic", "unknown"),
        ("glass", "unknown"),
    ],
)
def test_rendered_materials_are_read_back(material: str, expected: str) -> None:
    assert material_name(_rendered(material), MASK) == expected
    assert material_name(*_in_frame(_rendered(material), 0.0)) == expected


def test_statistics_separate_grain_weave_and_smooth_faces() -> None:
    wood = texture_stats(_rendered("wood"), MASK)
    fabric = texture_stats(_rendered("fabric"), MASK)
    smooth = texture_stats(_patch(np.ones((H, W))), MASK)
    assert wood is not None and fabric is not None and smooth is not None
    assert wood.periodic < -0.3 < fabric.periodic
    assert fabric.fine > 0.5 > wood.fine
    # the lighting gradient and the step between the faces leave no texture
    assert smooth.contrast < 0.01 and classify(smooth) == "unknown"


def test_mask_limits_the_pixels_and_tiny_masks_say_nothing() -> None:
    img = _rendered("fabric")
    img[:, : W // 2] = _rendered("wood")[:, : W // 2]
    right = np.zeros((H, W), dtype=bool)
    right[:, W // 2 + 2 :] = True
    # (noise 0: a frame that is half wood grain is no place to measure sensor noise,
    # frame_noise would take the grain for noise and make the fabric unreadable)
    assert material_name(img, right, noise=0.0) == "fabric"
    assert material_name(img, right) == "unknown"
    tiny = np.zeros((H, W), dtype=bool)
    tiny[10:15, 10:15] = True
    assert texture_stats(img, tiny) is None and material_name(img, tiny) == "unknown"
    assert texture_stats(img, np.zeros((H, W), dtype=bool)) is None


def test_render_material_codes_patterns_and_specular() -> None:
    assert material_code("Wood") == MATERIAL_CODE["wood"] and material_code("unobtainium") == 0
    pts = _plane_points().astype(np.float32)
    generic = np.full(len(pts), 0.97, np.float32)
    assert np.array_equal(pattern(np.zeros(len(pts), np.uint8), pts, generic), generic)
    noise = value_noise(pts, 100.0)
    assert (
        noise.min() >= -1.0
        and noise.max() <= 1.0
        and np.array_equal(noise, value_noise(pts, 100.0))
    )
    # a mirror-like configuration: the light straight behind the camera
    n = np.array([[0.0, -1.0, 0.0]] * 2, np.float32)
    view = np.array([[0.0, 1.0, 0.0]] * 2, np.float32)
    light = np.array([[0.0, -1.0, 0.0]] * 2, np.float32)
    codes = np.array([MATERIAL_CODE["metal"], MATERIAL_CODE["wood"]], np.uint8)
    spec = specular(codes, n, view, light)
    assert spec[0] > 0.4 and spec[1] == 0.0


def test_votes_fuse_textured_majorities_and_need_agreeing_views_for_plastic() -> None:
    assert fuse_votes({"wood": 3, "fabric": 1}) == "wood"
    assert fuse_votes({"wood": 2, "fabric": 2}) is None
    # grain seen from afar reads as a faint texture: one textured view outweighs it
    assert fuse_votes({"wood": 1, "plastic": 5}) == "wood"
    assert fuse_votes({"plastic": 2}) == "plastic"
    assert fuse_votes({"plastic": 1}) is None
    assert fuse_votes({}) is None


def _in_frame(patch: np.ndarray, noise: float, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """``patch`` in the middle of a 3× larger frame of smooth wall, with Gaussian sensor
    noise of ``noise`` grey levels over everything; returns the frame and the mask."""
    frame = np.zeros((3 * H, 3 * W, 3))
    frame[:] = _patch(np.ones((H, W)))[H // 2, W // 4]
    frame[H : 2 * H, W : 2 * W] = patch
    mask = np.zeros(frame.shape[:2], dtype=bool)
    mask[H : 2 * H, W : 2 * W] = True
    noisy = frame + np.random.default_rng(seed).normal(0.0, noise, frame.shape)
    return np.clip(np.round(noisy), 0, 255).astype(np.uint8), mask


def test_sensor_noise_is_not_read_as_texture() -> None:
    clean, mask = _in_frame(_patch(np.ones((H, W))), 0.0)
    assert frame_noise(clean) == 0.0
    smooth, _ = _in_frame(_patch(np.ones((H, W))), 2.0)
    assert frame_noise(smooth, exclude=mask) > 0.02
    stats = texture_stats(smooth, mask)
    assert stats is not None and classify(stats) != "unknown"  # noise alone looks textured
    assert material_name(smooth, mask) == "unknown"  # the frame's noise floor explains it
    for sigma in (0.5, 2.0, 5.0):
        assert material_name(_in_frame(_patch(np.ones((H, W))), sigma)[0], mask) == "unknown"
        assert material_name(_in_frame(_rendered("fabric"), sigma)[0], mask) == "fabric"
        assert material_name(_in_frame(_rendered("wood"), sigma)[0], mask) == "wood"
    # a faint moulding texture is read in a clean frame only
    assert material_name(_in_frame(_rendered("plastic"), 0.0)[0], mask) == "plastic"
    assert material_name(_in_frame(_rendered("plastic"), 1.0)[0], mask) == "unknown"


class _OneBox:
    """A segmenter that finds one box in the middle of every frame."""

    name = "one box"

    def segment(self, frame: Frame, prompts: object = None) -> list[Detection]:
        mask = np.zeros(frame.rgb.shape[:2], dtype=bool)
        mask[12:36, 16:48] = True
        return [Detection(mask, "box", 1.0, (16, 12, 47, 35))]


def test_the_semantic_stream_samples_the_noise_floor_on_a_share_of_keyframes() -> None:
    from inherit_sg.config import Config
    from inherit_sg.mapping.object_map import ObjectMap
    from inherit_sg.mapping.semantic import NOISE_EVERY, LabelSimilarity, SemanticStream
    from inherit_sg.perception.registry import create_describer, create_visual_encoder
    from tests.unit.retrieval_fixtures import HashEmbedder

    cfg = Config()
    stream = SemanticStream(
        _OneBox(),
        create_visual_encoder(cfg),
        create_describer(cfg),
        ObjectMap(LabelSimilarity(HashEmbedder())),
    )
    clean, _ = _in_frame(_patch(np.ones((H, W))), 0.0)
    noisy, _ = _in_frame(_patch(np.ones((H, W))), 3.0)
    frames = [noisy] * 3 + [clean] * (2 * NOISE_EVERY)
    floors = []
    for rgb in frames:
        frame = _frame(rgb)
        stream.integrate(frame, stream.perceive(frame), "floor:0")
        floors.append(stream.noise_floor)
    assert len(stream.noise_samples) == 3  # keyframes 0, NOISE_EVERY and 2 · NOISE_EVERY
    assert floors[0] > 0.02 and floors[-1] == 0.0  # the median follows the camera


def _frame(rgb: np.ndarray) -> Frame:
    h, w = rgb.shape[:2]
    return Frame(
        index=0,
        frame_id="f",
        timestamp=0.0,
        rgb=rgb,
        depth=np.ones((h, w), dtype=np.float32),
        pose=Pose.identity(),
        intrinsics=Intrinsics(fx=100.0, fy=100.0, cx=w / 2, cy=h / 2, width=w, height=h),
    )


@pytest.mark.parametrize("material", ["wood", "fabric", "stone", "plastic"])
def test_a_large_mask_is_read_in_a_window_with_the_same_result(
    material: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A mask far larger than MAX_SIDE is read in a window around its middle: fewer
    pixels, the same material as reading all of it."""
    from inherit_sg.perception import material as mat

    big = np.tile(_rendered(material), (8, 6, 1))  # 384 × 384 pixels
    mask = np.zeros(big.shape[:2], dtype=bool)
    mask[20:370, 30:380] = True
    windowed = texture_stats(big, mask)
    assert windowed is not None and windowed.pixels <= mat.MAX_SIDE**2
    monkeypatch.setattr(mat, "MAX_SIDE", 10_000)
    whole = texture_stats(big, mask)
    assert whole is not None and whole.pixels > 4 * windowed.pixels
    assert classify(windowed) == classify(whole) == material_name(big, mask, noise=0.0)
