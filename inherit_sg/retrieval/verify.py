"""Visual verification of the top candidates on their best keyframe (paper §III-D).

Two roles, as in the paper: a *segmenter* prompted with the target label must find the
object in the candidate's best view, then a *verifier* confirms the instruction.

- Segmenter: with SAM3 configured (``perception.segmenter = "sam3"``) it runs on the
  keyframe JPEG; the offline default uses the detection the mapping recorded on the
  SEEN_IN edge of that keyframe (its label must be compatible with the target, its
  pixel box gives the crop).
- Verifier: offline, the crop's pixels are checked against requested colours
  (:func:`inherit_sg.perception.colour_names.colour_name`) and the spatial, room and
  floor constraints against the graph (the terms the scorer computed); the VLM adapter
  (:mod:`inherit_sg.retrieval.verify_vlm`) asks an OpenAI-compatible endpoint.

A candidate without a keyframe cannot be checked visually: its verdict is ``None``
(unverified), which the engine accepts; ``False`` makes it fall back to the next one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from inherit_sg.errors import InheritSGError
from inherit_sg.model import Frame, Intrinsics, Keyframe, ObjectNode, Pose
from inherit_sg.perception.base import Segmenter
from inherit_sg.perception.colour_names import colour_name, colour_name_in_frame
from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    FunctionConstraint,
    LabelConstraint,
)
from inherit_sg.retrieval.graph_checks import PROXIMITY_NOTE
from inherit_sg.retrieval.plan import NodeSpec
from inherit_sg.retrieval.score_table import is_hint
from inherit_sg.retrieval.scoring import Scored

# Share of the box kept (centred) when naming a crop's colour: borders show background.
COLOUR_CROP = 0.5
Box = tuple[int, int, int, int]


@dataclass
class Verdict:
    """Outcome for one candidate: True (confirmed), False (rejected), None (unverified)."""

    ok: bool | None
    reason: str
    box: Box | None = None


@dataclass
class Evidence:
    """What verification looks at for one candidate."""

    node: ObjectNode
    spec: NodeSpec
    scored: Scored
    request: str
    keyframe: Keyframe | None = None
    detection: dict[str, Any] = field(default_factory=dict)
    image: np.ndarray | None = None  # RGB of the keyframe JPEG

    def wanted_labels(self) -> set[str]:
        """Map labels that count as the target (positive label/function matches)."""
        out: set[str] = set()
        for con in self.spec.constraints:
            if isinstance(con, LabelConstraint | FunctionConstraint) and not con.negated:
                out |= set(self.spec.matches.get(con.id, {}))
        return out


class Verifier(Protocol):
    """Confirms (or rejects) a grounded candidate against the request."""

    name: str

    def verify(self, ev: Evidence, box: Box | None) -> Verdict:
        """The verdict for ``ev`` with the object at ``box`` in ``ev.image``."""
        ...


def decode_jpeg(data: bytes) -> np.ndarray | None:
    """RGB uint8 image of JPEG bytes (None when they do not decode)."""
    import cv2

    buf = np.frombuffer(data, dtype=np.uint8)
    img = cv2.imdecode(buf, cv2.IMREAD_COLOR)
    # cvtColor: a tenth of the time of a strided channel flip (0.3 against 2.7 ms)
    return None if img is None else cv2.cvtColor(img, cv2.COLOR_BGR2RGB)


def recorded_box(ev: Evidence) -> Box | None:
    """The SEEN_IN pixel box scaled to the decoded image (None when absent or bad)."""
    raw = ev.detection.get("bbox")
    if ev.image is None or not isinstance(raw, list | tuple) or len(raw) != 4:
        return None
    h, w = ev.image.shape[:2]
    kf = ev.keyframe
    sx = w / kf.width if kf is not None and kf.width else 1.0
    sy = h / kf.height if kf is not None and kf.height else 1.0
    x0, y0, x1, y1 = (float(v) for v in raw)
    box = (int(x0 * sx), int(y0 * sy), int(x1 * sx), int(y1 * sy))
    x0i, y0i = max(0, box[0]), max(0, box[1])
    x1i, y1i = min(w - 1, box[2]), min(h - 1, box[3])
    return (x0i, y0i, x1i, y1i) if x1i > x0i and y1i > y0i else None


def _central_bounds(box: Box, keep: float) -> Box:
    x0, y0, x1, y1 = box
    dx, dy = (x1 - x0) * (1 - keep) / 2, (y1 - y0) * (1 - keep) / 2
    xa, ya = int(x0 + dx), int(y0 + dy)
    return xa, ya, max(xa + 1, int(x1 - dx)), max(ya + 1, int(y1 - dy))


def central_crop(image: np.ndarray, box: Box, keep: float = COLOUR_CROP) -> np.ndarray:
    """The centred ``keep`` share of ``box`` (at least one pixel)."""
    xa, ya, xb, yb = _central_bounds(box, keep)
    return image[ya : yb + 1, xa : xb + 1]


def crop_colour(image: np.ndarray, box: Box) -> str:
    """Colour name of the central crop of ``box``, exposure-corrected by the rest of the
    image as at mapping time (:func:`colour_name_in_frame`)."""
    xa, ya, xb, yb = _central_bounds(box, COLOUR_CROP)
    mask = np.zeros(image.shape[:2], dtype=bool)
    mask[ya : yb + 1, xa : xb + 1] = True
    return colour_name(image, mask) if mask.all() else colour_name_in_frame(image, mask)


# A candidate whose label / function match is weaker than this is not what was asked for.
NAMED_MIN = 0.5
# Attributes the map measures over many views (why texts of attribute_sim): a candidate
# whose measured value differs from the one asked for is not what was asked for.
MEASURED_ATTRIBUTES = ("colour is ", "material is ")


def graph_failures(ev: Evidence) -> list[str]:
    """Positive spatial / room / area / floor constraints the graph does not support
    (a relation credited only for standing near the landmark is not supported; hints
    are not checked), negated
    ones it does, a colour or material the map measured otherwise, and a thing that is
    not what was asked for (its label or function match below :data:`NAMED_MIN`)."""
    out: list[str] = []
    if ev.spec.levels is not None and not ev.scored.h_floor:
        out.append("not on the requested floor")
    named = [t for t in ev.scored.terms.values() if t.kind in ("label", "function")]
    positive = [t for t in named if t.polarity > 0]
    if positive and max(t.sim for t in positive) < NAMED_MIN:
        best = max(positive, key=lambda t: t.sim)
        out.append(f"{best.cid} ({best.kind}) barely matches: {best.why}")
    for term in ev.scored.terms.values():
        if term.kind == "attribute" and term.polarity > 0 and term.sim <= 0.0:
            if term.why.startswith(MEASURED_ATTRIBUTES):  # "colour is white", asked brown
                out.append(f"{term.cid} (attribute) contradicted by the map: {term.why}")
            continue
        if term.kind not in ("relation", "room", "area"):
            continue
        if is_hint(term.kind, term.polarity, term.weight):
            continue  # a hint (near where the speaker stands) is no requirement
        unsupported = term.sim <= 0.0 or term.why.startswith(PROXIMITY_NOTE)
        if term.polarity > 0 and unsupported:
            out.append(f"{term.cid} ({term.kind}) not found in the graph")
        elif term.polarity < 0 and term.sim >= 0.5:
            out.append(f"{term.cid} (negated {term.kind}) holds: {term.why}")
    return out


class OfflineVerifier:
    """Colour from the crop's pixels, geometry from the graph."""

    name = "offline"

    def verify(self, ev: Evidence, box: Box | None) -> Verdict:
        """Reject on a constraint the graph fails, or a colour the crop contradicts
        unless the map measured just that colour over all the views of the object (one
        crop is a noisier reading of the same pixels)."""
        failures = graph_failures(ev)
        if ev.image is not None and box is not None:
            seen = crop_colour(ev.image, box)
            for con in ev.spec.constraints:
                if not (isinstance(con, AttributeConstraint) and con.key == "colour"):
                    continue
                if seen == "unknown" or _map_agrees(ev, con):
                    continue
                if (seen == con.value) == con.negated:
                    failures.append(
                        f"{con.id}: the crop looks {seen}, asked {describe_colour(con)}"
                    )
        if failures:
            return Verdict(False, "; ".join(failures), box)
        return Verdict(True, "pixels and graph agree with the request", box)


def _map_agrees(ev: Evidence, con: AttributeConstraint) -> bool:
    """Whether the map's measured value fully supports ``con`` for the candidate."""
    term = ev.scored.terms.get(con.id)
    return term is not None and term.sim >= 1.0 and not con.negated


def describe_colour(con: AttributeConstraint) -> str:
    """'red' or 'not red'."""
    return f"{'not ' if con.negated else ''}{con.value}"


def frame_from_image(image: np.ndarray, frame_id: str) -> Frame:
    """A pose-less frame around a keyframe image (for segmenters that need only RGB)."""
    h, w = image.shape[:2]
    intr = Intrinsics(width=w, height=h, fx=float(w), fy=float(w), cx=w / 2, cy=h / 2)
    eye = Pose(tuple(float(v) for v in np.eye(4).ravel()))
    depth = np.zeros((h, w), dtype=np.float32)
    return Frame(0, frame_id, 0.0, image, depth, eye, intr)


def ground(
    ev: Evidence, segmenter: Segmenter | None, prompts: Sequence[str]
) -> tuple[bool | None, str, Box | None]:
    """Find the target in the keyframe: (found?, why, pixel box)."""
    if ev.keyframe is None:
        return None, "no keyframe to verify against", None
    if segmenter is not None and ev.image is not None:
        try:
            found = segmenter.segment(frame_from_image(ev.image, ev.keyframe.id), list(prompts))
        except InheritSGError as exc:
            return None, f"segmenter failed ({exc.message})", recorded_box(ev)
        if not found:
            return False, f"{segmenter.name} found no {'/'.join(prompts)} in {ev.keyframe.id}", None
        best = max(found, key=lambda d: d.score)
        return True, f"{segmenter.name} found {best.label} ({best.score:.2f})", best.bbox_xyxy
    label = str(ev.detection.get("label", "")).strip().lower()
    if not ev.detection:
        return None, f"no detection recorded for {ev.node.id} in {ev.keyframe.id}", None
    wanted = ev.wanted_labels()
    if wanted and label and label not in wanted and label != ev.node.label:
        return False, f"{ev.keyframe.id} shows a {label}, not a {'/'.join(sorted(wanted))}", None
    return True, f"{ev.keyframe.id} shows a {label or ev.node.label}", recorded_box(ev)


def skip_grounding(ev: Evidence) -> tuple[bool | None, str, Box | None]:
    """No segmenter step (``retrieval.verify_segmenter`` off): the target label is not
    looked for; the verifier gets the keyframe with the box recorded at mapping time."""
    if ev.keyframe is None:
        return None, "no keyframe to verify against", None
    return True, f"grounding skipped on {ev.keyframe.id}", recorded_box(ev)
