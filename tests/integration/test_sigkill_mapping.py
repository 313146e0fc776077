"""Twenty SIGKILLs at random moments of mapping, on new maps and on existing ones: every
map reopens for writing, keeps every session that finished before, marks the killed one
interrupted (or finished, when the kill came too late), and holds readable objects.

Two builds run at a time (one per core) so that twenty kills take about a minute."""

from __future__ import annotations

import random
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.store import MapStore
from inherit_sg.store.store_open import CREATE_LEFTOVERS

KILLS = 20
BUILD = "import sys; from inherit_sg.facade import build_map; build_map(sys.argv[1], sys.argv[2])"


@pytest.fixture(scope="module")
def walk(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("sigkill") / "walk"
    write_dataset(generate_house(5, 1, 4), out, width=160, height=120, workers=1, max_frames=24)
    return out


@pytest.fixture(scope="module")
def existing(walk: Path, tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, int]:
    """A healthy one-session map and its object count."""
    map_dir = tmp_path_factory.mktemp("sigkill_base") / "map"
    summary = build_map(walk, map_dir)
    return map_dir, int(summary["objects"])


@dataclass
class Kill:
    map_dir: Path
    had_sessions: int  # finished sessions before the killed build
    after_s: float
    proc: subprocess.Popen[bytes] | None = None


def _start(kill: Kill, walk: Path) -> None:
    kill.proc = subprocess.Popen(
        [sys.executable, "-c", BUILD, str(walk), str(kill.map_dir)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )


def _check(kill: Kill, objects_before: int) -> str:
    """What the killed build left, checked; returns the session state found."""
    if not (kill.map_dir / "map.json").is_file():
        # killed before the map was made (a slow machine can take seconds to create the
        # schema): no map, only what an interrupted create may leave, which the next
        # create clears
        assert kill.had_sessions == 0
        left = {p.name for p in kill.map_dir.iterdir()} if kill.map_dir.exists() else set()
        assert left <= CREATE_LEFTOVERS, left
        if left:
            with MapStore.create(kill.map_dir) as store:
                assert store.sessions() == []
        return "no map yet"
    with MapStore.open(kill.map_dir, write=True) as store:  # the dead writer's lock is stale
        sessions = store.sessions()
        finished = [s for s in sessions if s.state == "finished"]
        assert len(finished) >= kill.had_sessions, [s.state for s in sessions]
        states = {s.state for s in sessions[kill.had_sessions :]}
        assert states <= {"finished", "interrupted"}, states
        objects = list(store.load_graph().objects())
        if kill.had_sessions:
            assert len(objects) >= objects_before * 0.8, (len(objects), objects_before)
        return ",".join(sorted(states)) or "no session yet"


def test_twenty_kills_at_random_moments(
    walk: Path, existing: tuple[Path, int], tmp_path: Path
) -> None:
    base, objects_before = existing
    rng = random.Random(20)
    kills: list[Kill] = []
    for i in range(KILLS):
        target = tmp_path / f"kill{i:02d}"
        had = 0
        if i % 2:  # every other kill lands on an existing map, in its second session
            shutil.copytree(base, target)
            had = 1
        kills.append(Kill(target, had, rng.uniform(1.0, 9.0)))
    outcomes: list[str] = []
    for pair in (kills[i : i + 2] for i in range(0, KILLS, 2)):
        started = time.monotonic()
        for kill in pair:
            _start(kill, walk)
        for kill in sorted(pair, key=lambda k: k.after_s):
            assert kill.proc is not None
            time.sleep(max(0.0, started + kill.after_s - time.monotonic()))
            kill.proc.send_signal(signal.SIGKILL)
            kill.proc.wait(timeout=60)
        outcomes += [_check(kill, objects_before) for kill in pair]
    print("outcomes:", sorted(outcomes))
    assert len(outcomes) == KILLS
    # the random moments cover the run: some kills land mid-session
    assert "interrupted" in outcomes, outcomes
