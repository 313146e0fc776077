"""Offline template describer and the fallback wrapper."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.errors import EndpointError, InputError
from inherit_sg.perception.base import ObjectObservation
from inherit_sg.perception.colour_names import linear_to_srgb, srgb_to_linear
from inherit_sg.perception.describer import (
    FallbackDescriber,
    TemplateDescriber,
    is_round_footprint,
    shape_word,
    size_class,
    template_description,
)


def _obs(
    albedo: tuple[int, int, int],
    label: str = "chair",
    extent: tuple[float, float, float] = (0.5, 0.5, 0.9),
    room: str | None = "Kitchen",
) -> ObjectObservation:
    """A crop whose object pixels are ``albedo`` under a vertical light gradient, on a
    background of a different colour that the mask excludes."""
    shade = np.linspace(0.4, 1.0, 24)[:, None, None]
    obj = linear_to_srgb(srgb_to_linear(np.asarray(albedo)) * shade * np.ones((1, 20, 1)))
    rgb = np.zeros((24, 28, 3), dtype=np.uint8)
    rgb[:] = (40, 160, 60)  # green background
    mask = np.zeros((24, 28), dtype=bool)
    mask[:, 4:24] = True
    rgb[:, 4:24] = np.clip(obj + 0.5, 0, 255).astype(np.uint8)
    return ObjectObservation(label, rgb, mask, extent, room)


def test_template_names_measured_colour_size_and_room() -> None:
    text = TemplateDescriber().describe(_obs((190, 40, 40)))
    assert text == "a red chair, about 0.5 × 0.5 × 0.9 m, medium-sized, in the kitchen"


def test_colour_comes_from_pixels_not_label() -> None:
    d = TemplateDescriber()
    assert d.describe(_obs((45, 80, 185), label="Red Chair")).startswith("a blue red chair")
    assert d.describe(_obs((225, 120, 35), label="armchair")).startswith("an orange armchair")


def test_without_room_or_extent() -> None:
    d = TemplateDescriber()
    assert d.describe(_obs((235, 235, 230), room=None)).endswith("medium-sized")
    text = d.describe(_obs((235, 235, 230), extent=(0.0, 0.0, 0.0), room=None))
    assert text == "a white chair"


def test_small_dimensions_keep_two_decimals() -> None:
    text = TemplateDescriber().describe(_obs((45, 80, 185), "mug", (0.08, 0.08, 0.11)))
    assert "about 0.08 × 0.08 × 0.1 m" in text and "small-sized" in text


@pytest.mark.parametrize(
    ("extent", "expected"),
    [
        ((0.1, 0.1, 0.11), "small"),
        ((0.25, 0.25, 0.45), "small"),
        ((0.5, 0.5, 0.9), "medium"),
        ((0.45, 0.4, 0.55), "medium"),
        ((2.0, 0.9, 0.85), "large"),
        ((0.4, 0.4, 1.6), "large"),
        ((0.85, 0.85, 0.9), "large"),
    ],
)
def test_size_class(extent: tuple[float, float, float], expected: str) -> None:
    assert size_class(extent) == expected


class _Flaky:
    name = "flaky"

    def __init__(self, fail: bool) -> None:
        self.fail = fail
        self.calls = 0

    def describe(self, obs: ObjectObservation) -> str:
        self.calls += 1
        if self.fail:
            raise EndpointError("endpoint http://x is down")
        return "a model-written description"


def test_fallback_uses_primary_when_it_works() -> None:
    primary = _Flaky(fail=False)
    fb = FallbackDescriber(primary, TemplateDescriber())
    assert fb.describe(_obs((190, 40, 40))) == "a model-written description"
    assert fb.failures == 0 and fb.name == "flaky|offline"


def test_fallback_switches_and_cools_down() -> None:
    primary = _Flaky(fail=True)
    fb = FallbackDescriber(primary, TemplateDescriber(), cooldown_s=60.0)
    first = fb.describe(_obs((190, 40, 40)))
    second = fb.describe(_obs((45, 80, 185)))
    assert first.startswith("a red chair") and second.startswith("a blue chair")
    assert primary.calls == 1 and fb.failures == 1  # no second timeout while cooling down
    fb.cooldown_s = 0.0
    fb._skip_until = 0.0
    primary.fail = False
    assert fb.describe(_obs((190, 40, 40))) == "a model-written description"


def test_fallback_does_not_hide_bad_input() -> None:
    class Strict:
        name = "strict"

        def describe(self, obs: ObjectObservation) -> str:
            raise InputError("bad crop")

    with pytest.raises(InputError):
        FallbackDescriber(Strict(), TemplateDescriber()).describe(_obs((190, 40, 40)))


def test_measured_material_is_named_before_the_noun() -> None:
    text = template_description("table", "brown", (1.2, 0.8, 0.75), "kitchen", material="wood")
    assert text.startswith("a brown wooden table, about 1.2 × 0.8 × 0.8 m")
    assert template_description("vase", "unknown", (0.1, 0.1, 0.3), material="stone").startswith(
        "a stone vase"
    )
    assert template_description("armchair", "unknown", (0.8, 0.8, 0.9)).startswith("an armchair")


def test_an_unnamed_thing_is_described_by_its_shape() -> None:
    assert shape_word((0.4, 0.4, 1.6)) == "tall"
    assert shape_word((1.2, 0.8, 0.05)) == "flat"
    assert shape_word((0.4, 1.8, 0.5)) == "long"
    assert shape_word((0.4, 0.3, 0.3)) == "box-like"
    assert shape_word((0.0, 0.3, 0.3)) == "" and shape_word((float("nan"), 1, 1)) == ""
    text = template_description("object", "white", (0.4, 0.4, 1.6), "office")
    assert text.startswith("a tall white object, about 0.4 × 0.4 × 1.6 m")
    # a named thing is told by its name; its shape is left out
    assert template_description("lamp", "white", (0.4, 0.4, 1.6)).startswith("a white lamp")


def _rotated(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return points @ np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]).T


def _box_faces(w: float, d: float, faces: tuple[str, ...], rng: np.random.Generator) -> np.ndarray:
    t = rng.uniform(0, 1, (300, 2))
    sides = {
        "front": np.c_[t[:, 0] * w, np.zeros(300), t[:, 1]],
        "side": np.c_[np.zeros(300), t[:, 0] * d, t[:, 1]],
        "top": np.c_[t[:, 0] * w, t[:, 1] * d, np.ones(300)],
    }
    return np.vstack([sides[f] for f in faces])


def test_a_round_footprint_is_told_from_a_box_seen_from_any_side() -> None:
    rng = np.random.default_rng(3)
    angle = rng.uniform(0, 2 * np.pi, 400)
    bin_wall = np.c_[0.2 * np.cos(angle), 0.2 * np.sin(angle), rng.uniform(0, 0.6, 400)]
    assert is_round_footprint(bin_wall)
    front_half = bin_wall[np.sin(angle) >= 0]  # one view sees half of the cylinder
    assert is_round_footprint(front_half)
    for turn in np.linspace(0, 1.5, 7):
        for faces in (("front",), ("front", "side"), ("front", "side", "top")):
            box = _box_faces(0.5, 0.4, faces, rng)
            assert not is_round_footprint(_rotated(box, turn)), (turn, faces)
    assert not is_round_footprint(np.zeros((5, 3)))  # too few points say nothing
    assert shape_word((0.4, 0.4, 0.5), round_footprint=True) == "round"
    assert shape_word((0.3, 0.3, 1.2), round_footprint=True) == "tall"  # a pole stays tall
    text = template_description("object", "red", (0.4, 0.4, 0.5), round_footprint=True)
    assert text.startswith("a round red object")
