"""Soft-trigger supervisor (paper §III-C): on entering a room, decide whether the map's
summary of it is stale. The offline heuristic triggers for a room never summarised, or
one whose set of objects changed by at least ``min_change`` (Jaccard distance) since its
last summary. A VLM supervisor that reads the BEV picture can replace it (same
interface)."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Protocol


class Supervisor(Protocol):
    """Decides whether entering ``room_id`` calls for a global update."""

    def should_update(self, room_id: str, object_ids: Iterable[str]) -> tuple[bool, str]:
        """(trigger?, reason)."""
        ...

    def summarised(self, room_id: str, object_ids: Iterable[str]) -> None:
        """Record the object set a fresh summary of ``room_id`` covers."""
        ...


@dataclass
class HeuristicSupervisor:
    """Offline soft trigger: new rooms and rooms whose contents changed enough."""

    min_change: float = 0.3
    _seen: dict[str, frozenset[str]] = field(default_factory=dict)

    def should_update(self, room_id: str, object_ids: Iterable[str]) -> tuple[bool, str]:
        """Trigger for unsummarised rooms and changed object sets."""
        now = frozenset(object_ids)
        if room_id not in self._seen:
            return True, f"entered {room_id}, which has no summary yet"
        before = self._seen[room_id]
        union = before | now
        change = 1.0 - len(before & now) / len(union) if union else 0.0
        if change >= self.min_change:
            return True, f"{room_id} changed: {change:.0%} of its objects differ from its summary"
        return False, f"{room_id} summary is current ({change:.0%} change)"

    def summarised(self, room_id: str, object_ids: Iterable[str]) -> None:
        """Remember what the summary covered."""
        self._seen[room_id] = frozenset(object_ids)
