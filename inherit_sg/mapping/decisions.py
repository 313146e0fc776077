"""Soft-trigger decisions off the frame thread.

The geometric stream must never wait for a model: a supervisor that asks a remote VLM
(it declares ``remote = True``) is consulted on a single background thread, at most one
pending decision per room, and a positive answer schedules the update when it arrives.
Local supervisors (the heuristic) are cheap and decide inline, so recorded builds stay
deterministic.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor

from inherit_sg.mapping.supervisor import Supervisor

log = logging.getLogger(__name__)


class DecisionRunner:
    """Asks ``supervisor`` on room entries; calls ``on_trigger(reason)`` when it says so."""

    def __init__(self, supervisor: Supervisor, on_trigger: Callable[[str], None]) -> None:
        self.supervisor = supervisor
        self.on_trigger = on_trigger
        self.remote = bool(getattr(supervisor, "remote", False))
        self._executor = (
            ThreadPoolExecutor(1, thread_name_prefix="supervisor") if self.remote else None
        )
        self._pending: set[str] = set()
        self._lock = threading.Lock()
        self.decided = 0

    def room_entered(self, room_id: str, object_ids: Iterable[str]) -> None:
        """Decide now (local supervisor) or queue the decision (remote supervisor)."""
        ids = list(object_ids)
        if self._executor is None:
            self._decide(room_id, ids)
            return
        with self._lock:
            if room_id in self._pending:
                return  # an answer for this room is on its way
            self._pending.add(room_id)
        self._executor.submit(self._decide, room_id, ids)

    def _decide(self, room_id: str, ids: list[str]) -> None:
        try:
            trigger, reason = self.supervisor.should_update(room_id, ids)
            self.decided += 1
            if trigger:
                self.on_trigger(reason)
        except Exception:  # a decision must never take the mapping down
            log.exception("soft-trigger decision for %s failed", room_id)
        finally:
            with self._lock:
                self._pending.discard(room_id)

    def pending(self) -> int:
        """Decisions queued or running."""
        with self._lock:
            return len(self._pending)

    def close(self) -> None:
        """Drop queued decisions (the session's final update covers every room)."""
        if self._executor is not None:
            self._executor.shutdown(wait=False, cancel_futures=True)
