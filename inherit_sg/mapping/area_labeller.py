"""Functional-area labellers (paper §III-B: "an LLM then processes the textual semantics
of these clusters to derive functional labels").

:class:`RuleAreaLabeller` is the offline default (rules of ``areas.toml``);
:class:`LlmAreaLabeller` asks an OpenAI-compatible chat endpoint and falls back to the
rules when the endpoint fails or answers something unusable.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from typing import Any, Protocol

from inherit_sg.errors import EndpointError
from inherit_sg.llm import ChatClient
from inherit_sg.mapping.areas import label_area, summarise_area

log = logging.getLogger(__name__)

SYSTEM_PROMPT = (
    "You name functional areas of indoor scenes for a robot's map. Given the objects that "
    "stand together in one cluster (and the room, when known), answer with a short "
    "functional label (2-4 words, lower case, e.g. 'dining area', 'work area') and one "
    "sentence summarising what the area holds and is used for."
)
SCHEMA: dict[str, Any] = {
    "type": "object",
    "properties": {"label": {"type": "string"}, "summary": {"type": "string"}},
    "required": ["label", "summary"],
    "additionalProperties": False,
}
MAX_LABEL_CHARS = 60
MAX_SUMMARY_CHARS = 300


class AreaLabeller(Protocol):
    """Names a cluster of objects as a functional area."""

    name: str

    def label(self, object_labels: list[str], room_label: str | None) -> tuple[str, str]:
        """(functional label, one-sentence summary) of a cluster."""
        ...


class RuleAreaLabeller:
    """Offline labeller: rule-based label and a listing summary."""

    name = "rules"

    def label(self, object_labels: list[str], room_label: str | None) -> tuple[str, str]:
        """Label by :func:`label_area`, summary by :func:`summarise_area`."""
        label = label_area(object_labels)
        return label, summarise_area(label, object_labels)


def _clean(value: object, limit: int) -> str:
    text = " ".join(str(value).split()).strip("\"'` ") if isinstance(value, str) else ""
    return text if len(text) <= limit else ""


class LlmAreaLabeller:
    """Area labels written by an LLM; the rules answer whenever the model cannot."""

    name = "llm"

    def __init__(self, client: ChatClient, fallback: AreaLabeller | None = None) -> None:
        self.client = client
        self.fallback = fallback or RuleAreaLabeller()
        self.failures = 0
        self._cache: dict[tuple[tuple[str, ...], str | None], tuple[str, str]] = {}

    @staticmethod
    def prompt(object_labels: Sequence[str], room_label: str | None) -> str:
        """The user message for one cluster."""
        listing = ", ".join(sorted(object_labels)) or "nothing"
        where = f" in a {room_label}" if room_label and room_label != "room" else ""
        return f"Objects of one cluster{where}: {listing}. Name the functional area."

    def label(self, object_labels: list[str], room_label: str | None) -> tuple[str, str]:
        """The model's (label, summary), cached per (labels, room); rules on failure."""
        key = (tuple(sorted(object_labels)), room_label)
        if key in self._cache:
            return self._cache[key]
        messages = [
            {"role": "system", "content": SYSTEM_PROMPT},
            {"role": "user", "content": self.prompt(object_labels, room_label)},
        ]
        try:
            data = self.client.chat_json(messages, SCHEMA, "area_label")
            label = _clean(data.get("label"), MAX_LABEL_CHARS).lower()
            summary = _clean(data.get("summary"), MAX_SUMMARY_CHARS)
            if not label or not summary:
                raise EndpointError(f"{self.client.url}: area label answer lacks label/summary")
        except EndpointError as exc:
            self.failures += 1
            log.warning("area labeller falls back to rules: %s", exc)
            return self.fallback.label(object_labels, room_label)  # not cached: retry later
        self._cache[key] = (label, summary)
        return label, summary
