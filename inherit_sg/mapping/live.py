"""Live mapping sessions: frames pushed one at a time (over HTTP, from a robot) feed the
dual-stream :class:`~inherit_sg.mapping.orchestrator.Mapper`.

A bounded frame queue decouples the producer from the geometric stream, which runs on a
frame thread; keyframes go on to the semantic worker with ``drop`` back-pressure, so
the geometric stream never waits for the semantic side. When the frame queue is full
(the producer is faster than the geometric stream, or the stream waits while a global
update refines the rooms) :meth:`LiveSession.submit` refuses the frame with
:class:`~inherit_sg.errors.IntakeFullError` instead of blocking the caller. Nothing is
written for a refused or invalid frame. :meth:`LiveSession.finish` drains both queues,
runs the final update, persists everything and writes the BEV pictures, as a recorded
build does.
"""

from __future__ import annotations

import logging
import math
import queue
import threading
import time
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import (
    BackPressureError,
    FrameError,
    InheritSGError,
    InputError,
    IntakeFullError,
    MapError,
)
from inherit_sg.mapping.sessions import new_session
from inherit_sg.model import Frame, Intrinsics, Pose
from inherit_sg.perception.base import blind_without_instances
from inherit_sg.store import MapStore

log = logging.getLogger(__name__)

MAPPING, FINISHING, FINISHED, FAILED = "mapping", "finishing", "finished", "failed"
# What one unusable frame raises while it is mapped: it is left out, the session goes on.
_FRAME_FAULTS = (FrameError, ArithmeticError, ValueError)
DEFAULT_FRAME_QUEUE = 8
DEFAULT_FLUSH_EVERY = 20


@dataclass(frozen=True)
class FrameReceipt:
    """What :meth:`LiveSession.submit` accepted: the frame's index in the session and the
    session's counters at that moment (the streams run behind the intake)."""

    frame: int
    keyframes: int
    dropped: int
    objects: int
    queued: int

    def to_dict(self) -> dict[str, int]:
        """JSON-able form."""
        return asdict(self)


class LiveSession:
    """One mapping session fed frame by frame into an open, writable map store."""

    def __init__(
        self,
        store: MapStore,
        config: Config,
        *,
        name: str | None = None,
        frame_queue: int = DEFAULT_FRAME_QUEUE,
        flush_every: int = DEFAULT_FLUSH_EVERY,
    ) -> None:
        from inherit_sg.mapping.orchestrator import Mapper

        if frame_queue < 1 or flush_every < 1:
            raise InputError("frame_queue and flush_every must be at least 1")
        if not store.writable:
            raise MapError(f"map {store.path} is open read-only; a live session needs write=True")
        self.store = store
        self.session = new_session(
            store, name, dataset="live", default_prefix="live", taken=MapError
        )
        self.name = self.session.name
        self.mapper = Mapper(
            store, config, self.session, backpressure="drop", flush_every=flush_every
        )
        store.upsert_session(self.session)
        self.intrinsics: Intrinsics | None = None
        self.state = MAPPING
        self.error: str | None = None
        self.summary: dict[str, Any] | None = None
        self._received = 0
        self._blind = 0  # frames the configured segmenter cannot look at
        self._rejected: list[str] = []  # frames the mapper could not use, and why
        self._frame_s = 0.0
        self._frames: queue.Queue[Frame] = queue.Queue(maxsize=frame_queue)
        self._lock = threading.Lock()  # state, intake counters and the frame queue
        self._failure: BaseException | None = None
        self._started = time.perf_counter()
        self._thread = threading.Thread(target=self._consume, name="live-frames", daemon=True)
        self.mapper.start()
        self._thread.start()

    @property
    def id(self) -> str:
        """The session id stored in the map (``session:N``)."""
        return self.session.id

    # ------------------------------------------------------------------ intake
    def submit(
        self,
        rgb: np.ndarray,
        depth: np.ndarray,
        pose: Pose,
        *,
        intrinsics: Intrinsics | None = None,
        timestamp: float | None = None,
        instances: np.ndarray | None = None,
        instance_labels: dict[int, str] | None = None,
    ) -> FrameReceipt:
        """Queue one frame for the streams. ``depth`` is float metres, or raw uint16 units
        (as in depth PNGs) divided here by the intrinsics' ``depth_scale``;
        ``intrinsics`` is required on the first frame and, when given later, must match;
        ``timestamp`` is seconds since the session started (default: now).

        FrameError for a malformed frame, IntakeFullError when the frame queue is full,
        BackPressureError while the session finishes, MapError once it has finished."""
        intr = self._intrinsics_for(intrinsics)
        if np.issubdtype(depth.dtype, np.integer):
            depth = depth.astype(np.float32) / np.float32(intr.depth_scale)
        with self._lock:
            self._check_open()
            index = self._received
            stamp = time.time() - self.session.started if timestamp is None else timestamp
            if not math.isfinite(stamp) or stamp < 0:
                raise FrameError(f"frame {index}: timestamp must be a finite number >= 0")
            frame = Frame(
                index=index,
                frame_id=f"live-{index:06d}",
                timestamp=float(stamp),
                rgb=rgb,
                depth=depth,
                pose=pose,
                intrinsics=intr,
                instances=None if instances is None else instances.astype(np.uint16, copy=False),
                instance_labels=dict(instance_labels or {}),
            ).validate()
            try:
                self._frames.put_nowait(frame)
            except queue.Full:
                raise IntakeFullError(
                    f"live session {self.id}: {self._frames.maxsize} frames are waiting for "
                    "the geometric stream; retry later",
                    self._retry_after(),
                ) from None
            if self.intrinsics is None:
                self.intrinsics = intr
            self._received += 1
            segmenter = self.mapper.semantic.segmenter
            if (
                instances is None
                and blind_without_instances(segmenter)
                and not getattr(segmenter, "falls_back", False)
            ):
                self._blind += 1
            return FrameReceipt(index, *self._counters(), self._frames.qsize())

    def _intrinsics_for(self, given: Intrinsics | None) -> Intrinsics:
        current = self.intrinsics
        if given is None:
            if current is None:
                raise FrameError(f"live session {self.id}: the first frame needs intrinsics")
            return current
        if current is not None and given != current:
            raise FrameError(
                f"live session {self.id}: intrinsics differ from the session's "
                f"({current.to_dict()}); start a new session for another camera"
            )
        return given

    def _check_open(self) -> None:
        if self.state == FINISHING:
            raise BackPressureError(f"live session {self.id} is finishing", self._retry_after())
        if self.state == FINISHED:
            raise MapError(f"live session {self.id} has finished; start a new session")
        self._poll_worker()
        if self.state == FAILED:
            raise InheritSGError(f"live session {self.id} failed: {self.error}")

    def _poll_worker(self) -> None:
        try:
            self.mapper.check()
        except BaseException as exc:
            self._fail(exc)

    def _fail(self, exc: BaseException, *, force: bool = False) -> None:
        """Record the first failure; the session stops taking frames."""
        log.error("live session %s failed: %s", self.id, exc)
        self._failure = self._failure or exc
        self.error = self.error or (exc.message if isinstance(exc, InheritSGError) else repr(exc))
        if force or self.state == MAPPING:
            self.state = FAILED

    def _retry_after(self) -> float:
        done = max(1, self.mapper.progress.frames)
        return max(1.0, (self._frames.qsize() + 1) * self._frame_s / done)

    def _counters(self) -> tuple[int, int, int]:
        progress = self.mapper.progress
        return progress.keyframes, self.mapper.geometry.queue.dropped, progress.objects

    # ------------------------------------------------------------- frame thread
    def _consume(self) -> None:
        while True:
            try:
                frame = self._frames.get(timeout=0.05)
            except queue.Empty:
                if self.state != MAPPING:
                    return
                continue
            try:
                t0 = time.perf_counter()
                self.mapper.process_frame(frame)
                self._frame_s += time.perf_counter() - t0
            except _FRAME_FAULTS as exc:
                # one frame the mapper cannot use (a pose far from the walk, numbers that
                # overflow) is left out; the frames accepted before and after it count
                log.warning("live session %s: frame %s left out: %s", self.id, frame.index, exc)
                with self._lock:
                    self._rejected.append(f"frame {frame.index}: {exc}")
            except BaseException as exc:
                with self._lock:
                    self._fail(exc)
                return

    def _record_failed(self) -> None:
        """Mark the session record failed (best effort: the store may be what failed)."""
        self.session.state = "failed"
        try:
            self.store.upsert_session(self.session)
        except Exception as exc:  # the failure is reported already; this is a footnote
            log.warning("live session %s: could not record the failure: %s", self.id, exc)

    # ------------------------------------------------------------------ status
    @property
    def ended(self) -> bool:
        """Whether the session finished or failed (it takes no more frames)."""
        return self.state in (FINISHED, FAILED)

    def status(self) -> dict[str, Any]:
        """Counters of the session (JSON-able)."""
        with self._lock:
            if self.state == MAPPING:
                self._poll_worker()
            keyframes, dropped, objects = self._counters()
            progress = self.mapper.progress
            return {
                "session_id": self.id,
                "name": self.name,
                "state": self.state,
                "frames_received": self._received,
                "frames_processed": progress.frames,
                "frames_rejected": len(self._rejected),
                "frames_queued": self._frames.qsize(),
                "keyframes": keyframes,
                "keyframes_done": progress.keyframes_done,
                "keyframes_pending": len(self.mapper.geometry.queue),
                "dropped": dropped,
                "objects": objects,
                "updates": progress.updates,
                "error": self.error,
                "warnings": self._warnings(),
                "summary": self.summary,
            }

    def _warnings(self) -> list[str]:
        out = []
        if self._blind:
            out.append(
                f"{self._blind} frames came without instance masks, which the 'dataset' "
                "segmenter needs: they add geometry but no objects (send instances + "
                "instance_labels, or configure perception.segmenter = 'sam3' or 'classical')"
            )
        unmasked = self.mapper.semantic.unmasked_frames
        if unmasked:
            from inherit_sg.perception.auto_segmenter import UNNAMED_WARNING

            out.append(f"{unmasked} keyframes came without instance masks: {UNNAMED_WARNING}")
        if self._rejected:
            out.append(
                f"{len(self._rejected)} frames were left out because the mapper could not "
                f"use them (last: {self._rejected[-1]})"
            )
        return out

    # ------------------------------------------------------------------ finish
    def finish(self) -> dict[str, Any]:
        """Stop intake, drain the queues, run the final update, persist the session and
        write ``<map>/bev/floor_<level>.png``; the mapping summary. A failed session is
        finished as far as it can be and its error raised."""
        from inherit_sg.mapping.bev_pictures import write_bev_pictures

        with self._lock:
            if self.state == FINISHED and self.summary is not None:
                return self.summary
            if self.state == FINISHING:
                raise BackPressureError(f"live session {self.id} is finishing", 2.0)
            failed = self.state == FAILED
            self.state = FINISHING
        try:
            self._thread.join()
            self.mapper.drain()
            if failed or self._failure is not None:
                raise self._failure or InheritSGError(f"live session {self.id} failed")
            summary = self.mapper.finish(time.perf_counter() - self._started).to_dict()
            pictures = write_bev_pictures(self.mapper, self.store.path)
        except BaseException as exc:
            with self._lock:
                self._fail(exc, force=True)
            self._record_failed()
            if isinstance(exc, InheritSGError):
                raise
            raise InheritSGError(f"live session {self.id} failed: {self.error}") from exc
        summary["map"] = str(self.store.path)
        summary["bev"] = [str(p) for p in pictures]
        with self._lock:
            self.summary = summary
            self.state = FINISHED
        return summary
