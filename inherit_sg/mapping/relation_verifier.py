"""Relation verifiers (paper §III-C: "the VLM mode analyses annotated RGB images").

The geometric mode (default) keeps every relation the box heuristics of
:mod:`relations` inferred. :class:`VlmRelationVerifier` draws the objects' pixel boxes,
numbered, on a keyframe and asks a vision-language model which of a batch of relations
hold; it keeps those the model confirms. Relations it cannot check (no image, an object
not in the picture, an endpoint failure, a question left unanswered) stay as the
geometry inferred them.
"""

from __future__ import annotations

import base64
import logging
from collections.abc import Mapping
from typing import Any, Protocol, cast

import cv2
import numpy as np

from inherit_sg.errors import EndpointError
from inherit_sg.llm import ChatClient, Message
from inherit_sg.mapping.relations import Relation

log = logging.getLogger(__name__)

Box = tuple[int, int, int, int]
SYSTEM_PROMPT = (
    "You check spatial relations between objects in a photo of an indoor scene. Each "
    "object is outlined by a numbered box. For every question answer whether the relation "
    "holds in the picture."
)
SCHEMA: dict[str, Any] = {
    "type": "object",
    "properties": {
        "answers": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {"index": {"type": "integer"}, "holds": {"type": "boolean"}},
                "required": ["index", "holds"],
                "additionalProperties": False,
            },
        }
    },
    "required": ["answers"],
    "additionalProperties": False,
}
_COLOURS = [(0, 0, 255), (0, 200, 0), (255, 0, 0), (0, 200, 255), (255, 0, 255), (255, 255, 0)]


class RelationVerifier(Protocol):
    """Keeps the relations an image confirms."""

    name: str

    def verify(
        self,
        relations: list[Relation],
        keyframe_jpeg: bytes | None,
        boxes: dict[str, Box],
        labels: Mapping[str, str] | None = None,
    ) -> list[Relation]:
        """The subset of ``relations`` to keep. ``boxes`` maps object ids to their
        inclusive (x0, y0, x1, y1) pixel boxes in the JPEG; ``labels`` names them."""
        ...


class GeometricVerifier:
    """The geometric mode: every inferred relation stands."""

    name = "geometric"

    def verify(
        self,
        relations: list[Relation],
        keyframe_jpeg: bytes | None,
        boxes: dict[str, Box],
        labels: Mapping[str, str] | None = None,
    ) -> list[Relation]:
        """``relations`` unchanged."""
        return list(relations)


def annotate(jpeg: bytes, boxes: Mapping[int, Box], quality: int = 85) -> bytes:
    """The JPEG with each box drawn and tagged with its number."""
    img = cv2.imdecode(np.frombuffer(jpeg, np.uint8), cv2.IMREAD_COLOR)
    if img is None:
        raise EndpointError("keyframe JPEG cannot be decoded for relation verification")
    thick = max(1, round(max(img.shape[:2]) / 240))
    for n, (x0, y0, x1, y1) in boxes.items():
        colour = _COLOURS[(n - 1) % len(_COLOURS)]
        cv2.rectangle(img, (x0, y0), (x1, y1), colour, thick)
        cv2.putText(
            img, str(n), (x0 + 2, max(y0 + 12, 12)), cv2.FONT_HERSHEY_SIMPLEX, 0.45, colour, thick
        )
    ok, buf = cv2.imencode(".jpg", img, [cv2.IMWRITE_JPEG_QUALITY, quality])
    if not ok:
        raise EndpointError("could not encode the annotated keyframe as JPEG")
    return buf.tobytes()


class VlmRelationVerifier:
    """Relations confirmed by a vision-language model on an annotated keyframe."""

    name = "vlm"

    def __init__(self, client: ChatClient, batch_size: int = 16) -> None:
        self.client = client
        self.batch_size = batch_size
        self.failures = 0
        self._verdicts: dict[tuple[str, str, str], bool] = {}

    def verify(
        self,
        relations: list[Relation],
        keyframe_jpeg: bytes | None,
        boxes: dict[str, Box],
        labels: Mapping[str, str] | None = None,
    ) -> list[Relation]:
        """Ask about the relations both of whose objects are boxed in the image (in
        batches); keep those confirmed and every relation that could not be checked."""
        todo = [
            r
            for r in relations
            if (r.src, r.dst, r.predicate) not in self._verdicts
            and r.src in boxes
            and r.dst in boxes
        ]
        if keyframe_jpeg is not None:
            for start in range(0, len(todo), self.batch_size):
                self._ask(todo[start : start + self.batch_size], keyframe_jpeg, boxes, labels or {})
        return [r for r in relations if self._verdicts.get((r.src, r.dst, r.predicate), True)]

    def messages(
        self,
        batch: list[Relation],
        jpeg: bytes,
        boxes: Mapping[str, Box],
        labels: Mapping[str, str],
    ) -> list[dict[str, Any]]:
        """The chat messages asking about ``batch``."""
        numbers: dict[str, int] = {}
        for r in batch:
            for oid in (r.src, r.dst):
                numbers.setdefault(oid, len(numbers) + 1)
        picture = annotate(jpeg, {n: boxes[oid] for oid, n in numbers.items()})
        url = "data:image/jpeg;base64," + base64.b64encode(picture).decode("ascii")

        def name(oid: str) -> str:
            return f"the {labels.get(oid, 'object')} [box {numbers[oid]}]"

        lines = [f"{i}. Is {name(r.src)} {r.predicate} {name(r.dst)}?" for i, r in enumerate(batch)]
        text = "Answer every question by its index.\n" + "\n".join(lines)
        return [
            {"role": "system", "content": SYSTEM_PROMPT},
            {
                "role": "user",
                "content": [
                    {"type": "text", "text": text},
                    {"type": "image_url", "image_url": {"url": url}},
                ],
            },
        ]

    def _ask(
        self,
        batch: list[Relation],
        jpeg: bytes,
        boxes: Mapping[str, Box],
        labels: Mapping[str, str],
    ) -> None:
        try:
            messages = cast(list[Message], self.messages(batch, jpeg, boxes, labels))
            data = self.client.chat_json(messages, SCHEMA, "relation_check")
            answers = data.get("answers")
            if not isinstance(answers, list):
                raise EndpointError(f"{self.client.url}: relation answer has no 'answers' list")
        except EndpointError as exc:
            self.failures += 1
            log.warning("relation verifier keeps %d geometric relations: %s", len(batch), exc)
            return
        for item in answers:
            if not isinstance(item, dict):
                continue
            index, holds = item.get("index"), item.get("holds")
            if isinstance(index, int) and 0 <= index < len(batch) and isinstance(holds, bool):
                r = batch[index]
                self._verdicts[(r.src, r.dst, r.predicate)] = holds
