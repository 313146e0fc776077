"""Colour naming from pixels: robust to shading, separates black/grey/white."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from inherit_sg.perception.colour_names import (
    COLOUR_NAMES,
    colour_name,
    colour_name_in_frame,
    exposure_gain,
    linear_to_lab,
    linear_to_srgb,
    name_rgb,
    rank_colours,
    representative_colour,
    srgb_to_linear,
)

ALBEDOS = {
    "red": (190, 40, 40),
    "orange": (225, 120, 35),
    "yellow": (225, 200, 50),
    "green": (50, 140, 60),
    "blue": (45, 80, 185),
    "purple": (120, 60, 160),
    "pink": (230, 140, 170),
    "brown": (120, 75, 40),
    "black": (30, 30, 30),
    "white": (235, 235, 230),
    "grey": (128, 128, 128),
    "beige": (215, 195, 160),
}


def shaded_patch(
    albedo: tuple[int, int, int], darkest: float, noise: float = 3.0, seed: int = 0
) -> np.ndarray:
    """A 30×40 patch of ``albedo`` lit by a left-to-right brightness gradient (linear
    light from ``darkest`` to 1) plus sensor noise."""
    rng = np.random.default_rng(seed)
    shade = np.linspace(darkest, 1.0, 40)[None, :, None]
    lin = srgb_to_linear(np.asarray(albedo)) * shade * np.ones((30, 1, 1))
    img = linear_to_srgb(lin) + rng.normal(0.0, noise, (30, 40, 3))
    return np.clip(img + 0.5, 0, 255).astype(np.uint8)


def test_lab_of_reference_colours() -> None:
    lab = linear_to_lab(srgb_to_linear(np.array([[255, 255, 255], [0, 0, 0], [255, 0, 0]])))
    np.testing.assert_allclose(lab[0], [100, 0, 0], atol=0.5)
    np.testing.assert_allclose(lab[1], [0, 0, 0], atol=0.5)
    assert lab[2, 1] > 70 and lab[2, 2] > 50  # red: strongly +a, +b
    rgb = np.array([12.0, 128.0, 250.0])
    np.testing.assert_allclose(linear_to_srgb(srgb_to_linear(rgb)), rgb, atol=1e-6)


@pytest.mark.parametrize("name", sorted(ALBEDOS))
@pytest.mark.parametrize("darkest", [1.0, 0.5, 0.3])
def test_palette_colours_keep_their_name_under_shading(name: str, darkest: float) -> None:
    assert colour_name(shaded_patch(ALBEDOS[name], darkest)) == name


def test_red_patch_with_strong_gradient_is_red() -> None:
    patch = shaded_patch((200, 30, 30), darkest=0.15)
    assert colour_name(patch) == "red"
    # the dark end alone is still red, not brown or black
    assert colour_name(patch[:, :15]) == "red"


def test_dark_grey_versus_black_and_white_versus_grey() -> None:
    assert colour_name(shaded_patch((70, 70, 72), 0.6)) == "grey"
    assert colour_name(shaded_patch((22, 22, 22), 0.6)) == "black"
    assert colour_name(shaded_patch((245, 245, 245), 0.6)) == "white"
    assert colour_name(shaded_patch((165, 165, 165), 0.6)) == "grey"


def test_black_metal_with_a_broad_sheen_stays_black() -> None:
    # black albedo lit evenly, plus a white specular lobe over most of the surface
    xs = np.linspace(-1.0, 1.0, 40)
    sheen = 0.12 * np.clip(1.0 - np.abs(xs) * 1.6, 0.0, None) ** 2
    lin = srgb_to_linear(np.array([25, 25, 25]))[None, None, :] * np.ones((30, 40, 1))
    lin = lin + sheen[None, :, None]
    patch = np.round(linear_to_srgb(lin)).astype(np.uint8)
    assert colour_name(patch) == "black"
    # a dark grey surface lit unevenly stays grey: its lower quartile is not dark
    assert colour_name(shaded_patch((80, 80, 82), 0.3)) == "grey"


def test_only_masked_pixels_count() -> None:
    img = np.zeros((20, 20, 3), dtype=np.uint8)
    img[:, :10] = (45, 80, 185)
    img[:, 10:] = (225, 200, 50)
    mask = np.zeros((20, 20), dtype=bool)
    mask[:, 12:] = True
    assert colour_name(img, mask) == "yellow"
    assert colour_name(img, ~mask) == "blue"
    assert colour_name(img, np.zeros((20, 20), dtype=bool)) == "unknown"
    assert representative_colour(img, np.zeros((20, 20), dtype=bool)) is None


def test_majority_colour_wins_over_small_dark_parts() -> None:
    img = shaded_patch((190, 40, 40), 0.5)
    img[24:, :] = (15, 15, 15)  # black legs under a red seat
    assert colour_name(img) == "red"


def test_rank_colours_covers_palette_best_first() -> None:
    ranked = rank_colours((50, 140, 60))
    assert ranked[0][0] == "green"
    assert sorted(n for n, _ in ranked) == sorted(COLOUR_NAMES)
    assert all(a[1] <= b[1] for a, b in itertools.pairwise(ranked))
    assert name_rgb((30, 45, 115)) == "blue"  # navy
    assert name_rgb((250, 180, 200)) == "pink"


def test_exposure_correction_keeps_white_white_in_a_dim_frame() -> None:
    frame = np.zeros((40, 60, 3), dtype=np.uint8)
    dim = 0.3  # the room light reaches this share of full brightness
    wall = srgb_to_linear(np.array([232, 226, 212])) * dim
    frame[:] = np.round(linear_to_srgb(wall)).astype(np.uint8)
    mask = np.zeros((40, 60), dtype=bool)
    mask[10:30, 20:40] = True
    white = srgb_to_linear(np.array([240, 240, 236])) * dim * 0.8
    frame[mask] = np.round(linear_to_srgb(white)).astype(np.uint8)
    assert colour_name(frame, mask) == "grey"  # the pixels alone look grey
    assert exposure_gain(frame, mask) > 1.5
    assert colour_name_in_frame(frame, mask) == "white"
    grey = srgb_to_linear(np.array([110, 110, 110])) * dim * 0.8
    frame[mask] = np.round(linear_to_srgb(grey)).astype(np.uint8)
    assert colour_name_in_frame(frame, mask) in ("grey", "black")
    # a frame without other pixels gives no exposure reference
    assert exposure_gain(frame, np.ones((40, 60), dtype=bool)) == 1.0
