"""VLM describer: asks an OpenAI-compatible chat endpoint (GPT-4o, vLLM, Ollama) to
describe an object from its image crop.

The crop is sent as a base64 JPEG data URL in an ``image_url`` content part, with the
background outside the mask darkened so the model knows which object is meant (the
context stays visible). The measured size and the room go along as text. Failures of the
endpoint raise :class:`EndpointError`; wrap this describer in
:class:`~inherit_sg.perception.describer.FallbackDescriber` to degrade to the offline
template.
"""

from __future__ import annotations

import base64
from typing import Any, cast

import cv2
import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import EndpointError
from inherit_sg.llm import ChatClient, Message
from inherit_sg.perception.base import ObjectObservation
from inherit_sg.perception.preprocess import resize

SYSTEM_PROMPT = (
    "You describe objects that a home robot has seen, for its map. Answer with one short "
    "sentence naming the object's colour, material and notable parts. No preamble."
)
MAX_CHARS = 300


def image_data_url(
    rgb: np.ndarray, mask: np.ndarray | None = None, max_side: int = 384, quality: int = 85
) -> str:
    """JPEG data URL of an (H, W, 3) uint8 RGB crop, downsized to ``max_side``; pixels
    outside ``mask`` are darkened to a third."""
    img = rgb
    if mask is not None:
        img = np.where(mask[..., None], rgb, rgb // 3).astype(np.uint8)
    h, w = img.shape[:2]
    scale = min(1.0, max_side / max(h, w))
    if scale < 1.0:
        img = resize(img, max(1, round(h * scale)), max(1, round(w * scale)))
    ok, buf = cv2.imencode(".jpg", img[..., ::-1], [cv2.IMWRITE_JPEG_QUALITY, int(quality)])
    if not ok:
        raise EndpointError("could not encode the object crop as JPEG")
    return "data:image/jpeg;base64," + base64.b64encode(buf.tobytes()).decode("ascii")


def _question(obs: ObjectObservation) -> str:
    x, y, z = (max(0.0, v) for v in obs.extent)
    text = f"Describe the {obs.label.strip().lower() or 'object'} in this picture."
    if max(x, y, z) > 0:
        text += f" Measured size: about {x:.2f} × {y:.2f} × {z:.2f} m."
    if obs.room:
        text += f" It is in the {obs.room.strip().lower()}."
    return text


def clean_answer(text: str, where: str) -> str:
    """First non-empty line of a model answer, without quotes, at most ``MAX_CHARS``."""
    for line in text.strip().splitlines():
        line = line.strip().strip("\"'`").strip()
        if line:
            return line if len(line) <= MAX_CHARS else line[: MAX_CHARS - 1].rstrip() + "…"
    raise EndpointError(f"{where} answered an empty description")


class VlmDescriber:
    """Object descriptions from a vision-language model behind a chat endpoint."""

    def __init__(self, client: ChatClient, max_side: int = 384, jpeg_quality: int = 85) -> None:
        self.name = "vlm"
        self.client = client
        self._max_side = max_side
        self._quality = jpeg_quality

    @classmethod
    def from_config(cls, config: Config) -> VlmDescriber:
        """A describer for the ``[llm]`` endpoint (EndpointError when none is set)."""
        client = ChatClient.from_config(config.llm)
        return cls(client, config.perception.describer_max_side, config.store.jpeg_quality)

    def messages(self, obs: ObjectObservation) -> list[dict[str, Any]]:
        """The chat messages sent for ``obs``."""
        url = image_data_url(obs.rgb, obs.mask, self._max_side, self._quality)
        return [
            {"role": "system", "content": SYSTEM_PROMPT},
            {
                "role": "user",
                "content": [
                    {"type": "text", "text": _question(obs)},
                    {"type": "image_url", "image_url": {"url": url}},
                ],
            },
        ]

    def describe(self, obs: ObjectObservation) -> str:
        """One-sentence description written by the model."""
        # Content parts are forwarded verbatim as JSON by the client.
        answer = self.client.chat(cast(list[Message], self.messages(obs)))
        return clean_answer(answer, self.client.url)
