"""Offline describer: a template sentence from what was measured — the colour named
from the masked pixels, the size from the 3D extent, the room from the map — and the
fallback wrapper that lets a model-backed describer degrade to it.

Example: ``"a red chair, about 0.5 × 0.5 × 0.9 m, medium-sized, in the kitchen"``.
"""

from __future__ import annotations

import logging
import math
import threading
import time

import cv2
import numpy as np

from inherit_sg.errors import ModelUnavailableError
from inherit_sg.perception.base import Describer, ObjectObservation
from inherit_sg.perception.colour_names import colour_name
from inherit_sg.wording import with_article

log = logging.getLogger(__name__)

SMALL_MAX_SIDE = 0.5
SMALL_MAX_VOLUME = 0.03
LARGE_MIN_SIDE = 1.5
LARGE_MIN_VOLUME = 0.5


def size_class(extent: tuple[float, float, float]) -> str:
    """ "small", "medium" or "large" from the longest side and the volume (metres)."""
    longest = max(extent)
    volume = math.prod(max(0.0, e) for e in extent)
    if longest >= LARGE_MIN_SIDE or volume >= LARGE_MIN_VOLUME:
        return "large"
    if longest < SMALL_MAX_SIDE and volume < SMALL_MAX_VOLUME:
        return "small"
    return "medium"


# The label of a thing no model has named (the classical segmenter's masks).
UNNAMED = "object"


def shape_word(extent: tuple[float, float, float], round_footprint: bool = False) -> str:
    """How a thing looks, from its extent (x, y, z up, metres) and whether its footprint is
    round (:func:`is_round_footprint`): "flat" (a low slab: a rug, a tray), "tall" (a
    column: a lamp, a cabinet), "round" (a bin, a round table, a stool), "long" (a bench, a
    shelf) or "box-like"; "" for an extent that says nothing."""
    if not all(math.isfinite(v) and v > 0 for v in extent):
        return ""
    low, high = sorted(extent[:2])
    height = extent[2]
    if height < 0.35 * high and height < 0.3:
        return "flat"
    if height > 1.8 * high and height > 0.6:
        return "tall"
    if round_footprint:
        return "round"
    if high > 2.5 * low:
        return "long"
    return "box-like"


# A disc fills π/4 ≈ 0.785 of its bounding rectangle (a half disc, the visible front of a
# cylinder, fills the same share of its own); a rectangle fills 1, a triangle 0.5.
ROUND_FILL = (0.70, 0.88)
ROUND_MAX_ASPECT = 2.1  # the visible half of a cylinder is a half disc, 2:1
ROUND_MIN_CORNERS = 5


def is_round_footprint(points: np.ndarray) -> bool:
    """Whether the floor-plan outline of world ``points`` (N, 3) is round: its convex hull
    fills a disc's share of its smallest bounding rectangle, is at most about twice as long
    as wide (a half disc, seen from one side), and has no few sharp corners (its outline
    simplified at 3 % of the perimeter keeps at least :data:`ROUND_MIN_CORNERS` vertices,
    where a box keeps four and an L-shaped view three)."""
    xy = np.ascontiguousarray(np.asarray(points, dtype=np.float32).reshape(-1, 3)[:, :2])
    if len(xy) < 12 or not np.isfinite(xy).all():
        return False
    hull = cv2.convexHull(xy)
    (_, _), (w, h), _ = cv2.minAreaRect(hull)
    if min(w, h) <= 1e-3 or max(w, h) / min(w, h) > ROUND_MAX_ASPECT:
        return False
    fill = float(cv2.contourArea(hull)) / float(w * h)
    if not ROUND_FILL[0] <= fill <= ROUND_FILL[1]:
        return False
    outline = cv2.approxPolyDP(hull, 0.03 * cv2.arcLength(hull, True), True)
    return len(outline) >= ROUND_MIN_CORNERS


def _dims(extent: tuple[float, float, float]) -> str:
    def fmt(v: float) -> str:
        return f"{v:.2f}".rstrip("0").rstrip(".") if v < 0.1 else f"{v:.1f}"

    return " × ".join(fmt(max(0.0, v)) for v in extent)


# How a measured material reads before a noun ("wooden table", "stone vase").
_MATERIAL_ADJECTIVES = {"wood": "wooden", "wool": "woollen"}


def _adjective(material: str | None) -> str:
    if not material or material == "unknown":
        return ""
    return _MATERIAL_ADJECTIVES.get(material, material)


class TemplateDescriber:
    """Deterministic description from measured colour, size and room context."""

    def __init__(self) -> None:
        self.name = "offline"

    def describe(self, obs: ObjectObservation) -> str:
        """E.g. "a red chair, about 0.5 × 0.5 × 0.9 m, medium-sized, in the kitchen"."""
        return template_description(
            obs.label,
            colour_name(obs.rgb, obs.mask),
            obs.extent,
            obs.room,
            round_footprint=obs.round_footprint,
        )


def template_description(
    label: str,
    colour: str,
    extent: tuple[float, float, float],
    room: str | None = None,
    *,
    material: str | None = None,
    round_footprint: bool = False,
) -> str:
    """The offline sentence from a label, a colour name ("unknown" to omit it), the 3D
    extent in metres, the room label, a measured material (None to omit it) and whether the
    footprint is round (shape words are given to unnamed things only); also
    used to refresh descriptions when fused observations change an object's size, room
    or material, e.g. "a brown wooden table, about 1.2 × 0.8 × 0.75 m, ..."."""
    label = label.strip().lower() or UNNAMED
    # an unnamed thing is told apart by how it looks: "a tall white object"
    shape = shape_word(extent, round_footprint) if label == UNNAMED else ""
    words = [w for w in (shape, colour if colour != "unknown" else "", _adjective(material)) if w]
    noun = " ".join([*words, label])
    parts = [with_article(noun)]
    if all(math.isfinite(v) for v in extent) and max(extent) > 0:
        parts.append(f"about {_dims(extent)} m")
        parts.append(f"{size_class(extent)}-sized")
    text = ", ".join(parts)
    if room:
        text += f", in the {room.strip().lower()}"
    return text


class FallbackDescriber:
    """Ask ``primary``; when it is unavailable (endpoint down, timeout, garbage) use
    ``fallback`` and skip ``primary`` for ``cooldown_s`` so a dead endpoint does not cost
    one timeout per object."""

    def __init__(self, primary: Describer, fallback: Describer, cooldown_s: float = 30.0) -> None:
        self.primary = primary
        self.fallback = fallback
        self.cooldown_s = cooldown_s
        self.name = f"{primary.name}|{fallback.name}"
        self.failures = 0
        self._skip_until = 0.0
        self._lock = threading.Lock()

    def describe(self, obs: ObjectObservation) -> str:
        """Primary's description, or the fallback's when the primary fails."""
        with self._lock:
            skip = time.monotonic() < self._skip_until
        if not skip:
            try:
                return self.primary.describe(obs)
            except ModelUnavailableError as exc:
                log.warning(
                    "describer %s failed, using %s: %s", self.primary.name, self.fallback.name, exc
                )
                with self._lock:
                    self.failures += 1
                    self._skip_until = time.monotonic() + self.cooldown_s
        return self.fallback.describe(obs)
