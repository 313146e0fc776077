"""Soft-trigger decisions: local supervisors decide inline, remote ones off the frame
thread with at most one pending decision per room."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterable

from inherit_sg.mapping.decisions import DecisionRunner
from inherit_sg.mapping.supervisor import HeuristicSupervisor


class SlowRemote:
    """A supervisor whose answers wait for ``release`` (a model that takes its time)."""

    remote = True

    def __init__(self) -> None:
        self.release = threading.Event()
        self.asked: list[str] = []

    def should_update(self, room_id: str, object_ids: Iterable[str]) -> tuple[bool, str]:
        self.asked.append(room_id)
        assert self.release.wait(10)
        return room_id != "room:2", f"model on {room_id}"

    def summarised(self, room_id: str, object_ids: Iterable[str]) -> None:
        pass


def _wait(cond: object, timeout: float = 10.0) -> None:
    deadline = time.monotonic() + timeout
    while not cond() and time.monotonic() < deadline:  # type: ignore[operator]
        time.sleep(0.01)


def test_local_supervisor_decides_inline() -> None:
    reasons: list[str] = []
    runner = DecisionRunner(HeuristicSupervisor(), reasons.append)
    runner.room_entered("room:1", ["object:1"])
    assert not runner.remote and runner.pending() == 0
    assert reasons == ["entered room:1, which has no summary yet"]


def test_remote_supervisor_never_blocks_the_caller() -> None:
    sup = SlowRemote()
    reasons: list[str] = []
    runner = DecisionRunner(sup, reasons.append)
    start = time.perf_counter()
    for _ in range(5):
        runner.room_entered("room:1", ["object:1"])  # deduplicated while pending
    runner.room_entered("room:2", [])
    assert time.perf_counter() - start < 0.5
    assert runner.pending() == 2 and reasons == []
    sup.release.set()
    _wait(lambda: runner.pending() == 0)
    assert sup.asked == ["room:1", "room:2"]
    assert reasons == ["model on room:1"]  # room:2 answered "no update"
    runner.close()


def test_failing_decision_is_contained() -> None:
    class Broken(SlowRemote):
        def should_update(self, room_id: str, object_ids: Iterable[str]) -> tuple[bool, str]:
            raise RuntimeError("endpoint exploded")

    runner = DecisionRunner(Broken(), lambda r: None)
    runner.room_entered("room:1", [])
    _wait(lambda: runner.pending() == 0)
    assert runner.pending() == 0 and runner.decided == 0
    runner.close()
