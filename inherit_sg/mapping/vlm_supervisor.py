"""VLM soft-trigger supervisor (paper §III-C): on entering a room, a vision-language
model looks at the current BEV picture and decides whether the map's summary of the
room is stale. Any failure (no picture yet, endpoint down, unusable answer) falls back
to the :class:`HeuristicSupervisor`, which is kept informed of every summary."""

from __future__ import annotations

import base64
import logging
from collections.abc import Callable, Iterable
from typing import Any, cast

from inherit_sg.errors import EndpointError, InheritSGError
from inherit_sg.llm import ChatClient, Message
from inherit_sg.mapping.supervisor import HeuristicSupervisor

log = logging.getLogger(__name__)

SYSTEM_PROMPT = (
    "You supervise a robot's semantic map. The picture is the bird's-eye view of the "
    "current floor: coloured regions are rooms with their names, dots are objects, marks "
    "are where the map was last updated. Decide whether the summary of the named room "
    "is stale and the map should be updated now."
)
SCHEMA: dict[str, Any] = {
    "type": "object",
    "properties": {"update": {"type": "boolean"}, "reason": {"type": "string"}},
    "required": ["update", "reason"],
    "additionalProperties": False,
}
MAX_REASON_CHARS = 200


class VlmSupervisor:
    """Soft trigger decided by a VLM on the BEV picture; heuristic on failure.

    ``remote``: the mapper asks it off the frame thread (see :mod:`~inherit_sg.mapping.decisions`).
    """

    remote = True

    def __init__(
        self,
        client: ChatClient,
        bev_png: Callable[[], bytes],
        fallback: HeuristicSupervisor | None = None,
    ) -> None:
        self.client = client
        self.bev_png = bev_png
        self.fallback = fallback or HeuristicSupervisor()
        self.failures = 0
        self._summarised: dict[str, frozenset[str]] = {}
        self._decided: dict[tuple[str, frozenset[str]], tuple[bool, str]] = {}

    def question(self, room_id: str, now: frozenset[str]) -> str:
        """The text of the request for ``room_id`` holding ``now``."""
        if room_id not in self._summarised:
            state = "The map has no summary of it yet."
        else:
            before = self._summarised[room_id]
            state = (
                f"Its summary covers {len(before)} objects; it now holds {len(now)}, "
                f"{len(now - before)} of them new and {len(before - now)} gone."
            )
        return f"The robot just entered {room_id}. {state} Is the room's summary stale?"

    def messages(self, room_id: str, now: frozenset[str], png: bytes) -> list[dict[str, Any]]:
        """The chat messages sent for one decision."""
        url = "data:image/png;base64," + base64.b64encode(png).decode("ascii")
        return [
            {"role": "system", "content": SYSTEM_PROMPT},
            {
                "role": "user",
                "content": [
                    {"type": "text", "text": self.question(room_id, now)},
                    {"type": "image_url", "image_url": {"url": url}},
                ],
            },
        ]

    def should_update(self, room_id: str, object_ids: Iterable[str]) -> tuple[bool, str]:
        """(trigger?, reason) from the model; one request per room and object set."""
        now = frozenset(object_ids)
        key = (room_id, now)
        if key in self._decided:
            return self._decided[key]
        try:
            png = self.bev_png()
            messages = cast(list[Message], self.messages(room_id, now, png))
            data = self.client.chat_json(messages, SCHEMA, "soft_trigger")
            update, reason = data.get("update"), data.get("reason")
            if not isinstance(update, bool):
                raise EndpointError(f"{self.client.url}: soft-trigger answer has no boolean")
        except (InheritSGError, ValueError) as exc:
            self.failures += 1
            log.warning("supervisor falls back to the heuristic: %s", exc)
            return self.fallback.should_update(room_id, now)
        text = " ".join(str(reason or "").split())[:MAX_REASON_CHARS] or "no reason given"
        decision = (update, f"VLM on {room_id}: {text}")
        self._decided[key] = decision
        return decision

    def summarised(self, room_id: str, object_ids: Iterable[str]) -> None:
        """Record the summary's object set (here and in the fallback)."""
        now = frozenset(object_ids)
        self._summarised[room_id] = now
        self._decided = {k: v for k, v in self._decided.items() if k[0] != room_id}
        self.fallback.summarised(room_id, now)
