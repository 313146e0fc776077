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


def shape_word(extent: tuple[float, float, float]) -> str:
    """How a box looks, from its extent (x, y, z up, metres): "flat" (a low slab: a rug, a
    tray), "tall" (a column: a lamp, a cabinet), "long" (a bench, a shelf) or "box-like";
    "" for an extent that says nothing."""
    if not all(math.isfinite(v) and v > 0 for v in extent):
        return ""
    low, high = sorted(extent[:2])
    height = extent[2]
    if height < 0.35 * high and height < 0.3:
        return "flat"
    if height > 1.8 * high and height > 0.6:
        return "tall"
    if high > 2.5 * low:
        return "long"
    return "box-like"


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
        return template_description(obs.label, colour_name(obs.rgb, obs.mask), obs.extent, obs.room)


def template_description(
    label: str,
    colour: str,
    extent: tuple[float, float, float],
    room: str | None = None,
    *,
    material: str | None = None,
) -> str:
    """The offline sentence from a label, a colour name ("unknown" to omit it), the 3D
    extent in metres, the room label and a measured material (None to omit it); also
    used to refresh descriptions when fused observations change an object's size, room
    or material, e.g. "a brown wooden table, about 1.2 × 0.8 × 0.75 m, ..."."""
    label = label.strip().lower() or UNNAMED
    # an unnamed thing is told apart by how it looks: "a tall white object"
    shape = shape_word(extent) if label == UNNAMED else ""
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
