"""Keyframe gating and the bounded keyframe queue to the semantic stream (paper §III-B).

A frame becomes a keyframe when its global image feature's cosine similarity to the
last keyframe drops below a threshold (appearance gate), or when the camera moved or
turned enough since the last keyframe (pose gate), or when forced (floor change).

Back-pressure policy of :class:`KeyframeQueue`: the geometric stream never blocks.
When the queue is full, the oldest *non-hard* keyframe is dropped (the count is kept);
hard keyframes (floor changes) are dropped only when every queued item is hard.
"""

from __future__ import annotations

import math
import threading
from collections import deque
from dataclasses import dataclass

import numpy as np

from inherit_sg.geometry.image_feature import cosine
from inherit_sg.model import Frame, Keyframe, Pose


@dataclass(frozen=True)
class GateDecision:
    """Outcome of the gate for one frame."""

    selected: bool
    reason: str  # "first", "appearance", "pose", "forced" or "" when not selected
    similarity: float


class KeyframeGate:
    """Appearance + pose keyframe gate."""

    def __init__(
        self,
        similarity: float = 0.9,
        translation: float = 1.0,
        rotation_deg: float = 30.0,
        min_gap: int = 2,
    ) -> None:
        self.similarity = similarity
        self.translation = translation
        self.rotation = math.radians(rotation_deg)
        self.min_gap = min_gap
        self._feature: np.ndarray | None = None
        self._pose: np.ndarray | None = None
        self._index = -(10**9)

    def check(
        self, index: int, feature: np.ndarray, pose: Pose, force: bool = False
    ) -> GateDecision:
        """Decide on one frame; a selected frame becomes the new reference."""
        m = pose.matrix
        if self._feature is None or self._pose is None:
            return self._accept(index, feature, m, "first", 0.0)
        sim = cosine(feature, self._feature)
        if force:
            return self._accept(index, feature, m, "forced", sim)
        if index - self._index < self.min_gap:
            return GateDecision(False, "", sim)
        if sim < self.similarity:
            return self._accept(index, feature, m, "appearance", sim)
        moved = float(np.linalg.norm(m[:3, 3] - self._pose[:3, 3]))
        rel = self._pose[:3, :3].T @ m[:3, :3]
        turned = math.acos(max(-1.0, min(1.0, (float(np.trace(rel)) - 1.0) / 2.0)))
        if moved > self.translation or turned > self.rotation:
            return self._accept(index, feature, m, "pose", sim)
        return GateDecision(False, "", sim)

    def _accept(
        self, index: int, feature: np.ndarray, m: np.ndarray, reason: str, sim: float
    ) -> GateDecision:
        self._feature, self._pose, self._index = feature, m, index
        return GateDecision(True, reason, sim)


@dataclass(frozen=True)
class PendingKeyframe:
    """A keyframe waiting for the semantic stream, with the frame it came from."""

    keyframe: Keyframe
    frame: Frame
    hard: bool = False
    reason: str = ""


class KeyframeQueue:
    """Thread-safe bounded queue; ``put`` never blocks (see the module docstring)."""

    def __init__(self, capacity: int = 64) -> None:
        if capacity < 1:
            raise ValueError("keyframe queue capacity must be at least 1")
        self.capacity = capacity
        self._items: deque[PendingKeyframe] = deque()
        self._cond = threading.Condition()
        self._closed = False
        self.dropped = 0
        self.dropped_hard = 0

    def __len__(self) -> int:
        with self._cond:
            return len(self._items)

    def put(self, item: PendingKeyframe) -> PendingKeyframe | None:
        """Enqueue; returns the keyframe dropped to make room, if any."""
        with self._cond:
            if self._closed:
                raise RuntimeError("keyframe queue is closed")
            dropped = None
            if len(self._items) >= self.capacity:
                victim = next((i for i in self._items if not i.hard), self._items[0])
                self._items.remove(victim)
                dropped = victim
                self.dropped += 1
                self.dropped_hard += int(victim.hard)
            self._items.append(item)
            self._cond.notify_all()
            return dropped

    def get(self, timeout: float | None = None) -> PendingKeyframe | None:
        """Oldest pending keyframe; None on timeout or when closed and drained."""
        with self._cond:
            if not self._cond.wait_for(lambda: self._items or self._closed, timeout):
                return None
            item = self._items.popleft() if self._items else None
            self._cond.notify_all()  # a producer may wait for room (:meth:`wait_below`)
            return item

    def wait_below(self, size: int, timeout: float | None = None) -> bool:
        """Block until fewer than ``size`` keyframes are pending or the queue is closed
        (the back-pressure of recorded datasets); False when ``timeout`` passed first."""
        with self._cond:
            return self._cond.wait_for(lambda: len(self._items) < size or self._closed, timeout)

    def drain(self) -> list[PendingKeyframe]:
        """Take every pending keyframe at once (oldest first)."""
        with self._cond:
            out = list(self._items)
            self._items.clear()
            self._cond.notify_all()
            return out

    def close(self) -> None:
        """No more puts; wakes waiting consumers."""
        with self._cond:
            self._closed = True
            self._cond.notify_all()

    @property
    def closed(self) -> bool:
        """Whether :meth:`close` was called."""
        return self._closed
