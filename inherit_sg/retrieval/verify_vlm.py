"""VLM verifier: an OpenAI-compatible chat endpoint judges the candidate in its image.

The keyframe is sent as a JPEG data URL with the candidate's pixel box drawn on it (the
paper passes "the image, augmented with the SAM3 bounding box"), together with the
request and what the map knows of the candidate. The answer is a JSON verdict
``{"match": bool, "reason": str}`` (structured output). When the endpoint fails the
offline verifier's verdict is used and the reason says so.
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import EndpointError
from inherit_sg.llm.client import ChatClient, Message
from inherit_sg.perception.vlm_describer import image_data_url
from inherit_sg.retrieval.verify import Box, Evidence, OfflineVerifier, Verdict

SYSTEM_PROMPT = (
    "You check answers of a home robot's object search. The image shows the robot's best "
    "view of a candidate object, outlined with a green box. Decide whether the outlined "
    "object is what the user asked for, including every colour, material, placement and "
    "negation in the request. Answer only with the JSON verdict."
)
VERDICT_SCHEMA: dict[str, Any] = {
    "type": "object",
    "additionalProperties": False,
    "required": ["match", "reason"],
    "properties": {"match": {"type": "boolean"}, "reason": {"type": "string"}},
}


def outlined(image: np.ndarray, box: Box | None) -> np.ndarray:
    """A copy of ``image`` with ``box`` drawn in green (unchanged when None)."""
    import cv2

    out = np.ascontiguousarray(image.copy())
    if box is not None:
        x0, y0, x1, y1 = box
        thick = max(2, round(max(out.shape[:2]) / 200))
        cv2.rectangle(out, (x0, y0), (x1, y1), (0, 255, 0), thick)
    return out


class VlmVerifier:
    """Verdicts from a vision-language model; offline verdict when it fails."""

    name = "vlm"

    def __init__(self, client: ChatClient, max_side: int = 640, quality: int = 85) -> None:
        self.client = client
        self.max_side = max_side
        self.quality = quality
        self.fallback = OfflineVerifier()

    @classmethod
    def from_config(cls, config: Config) -> VlmVerifier:
        """A verifier for the ``[llm]`` endpoint (EndpointError when none is set)."""
        return cls(
            ChatClient.from_config(config.llm),
            config.store.keyframe_max_side,
            config.store.jpeg_quality,
        )

    def messages(self, ev: Evidence, box: Box | None) -> list[dict[str, Any]]:
        """The chat messages sent for one candidate."""
        assert ev.image is not None
        url = image_data_url(outlined(ev.image, box), None, self.max_side, self.quality)
        facts = f"The map calls it a {ev.node.label}"
        if ev.node.description:
            facts += f" ({ev.node.description})"
        text = f"Request: {ev.request!r}\n{facts}.\nIs the outlined object a correct answer?"
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

    def verify(self, ev: Evidence, box: Box | None) -> Verdict:
        """Ask the model; the offline verdict when there is no image or it fails."""
        if ev.image is None:
            return self.fallback.verify(ev, box)
        try:
            data = self.client.chat_json(
                cast(list[Message], self.messages(ev, box)), VERDICT_SCHEMA, "verdict"
            )
        except EndpointError as exc:
            offline = self.fallback.verify(ev, box)
            return Verdict(
                offline.ok, f"VLM failed ({exc.message}); offline: {offline.reason}", box
            )
        match = data.get("match")
        if not isinstance(match, bool):
            offline = self.fallback.verify(ev, box)
            return Verdict(
                offline.ok, f"VLM verdict without 'match'; offline: {offline.reason}", box
            )
        return Verdict(match, f"VLM: {str(data.get('reason', ''))[:200]}", box)
