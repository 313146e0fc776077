"""Build one map job all or nothing: into a temporary sibling of the final directory,
renamed into place only when every session finished.

A new map is built in ``ROOT/.NAME.RUN.partial`` and renamed to ``ROOT/NAME``. An existing
map is copied there under its writer lock (so no other writer changes it meanwhile),
extended, and swapped in: the old directory is renamed aside, the new one into place,
and the old one removed. A killed attempt leaves only its ``.partial`` folder, which the
next attempt (same run id) and the driver remove. This module needs no Ray.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import time
from pathlib import Path
from typing import Any

from inherit_sg.config import Config
from inherit_sg.errors import MapError
from inherit_sg.scale.manifest import MapJob

# A test hook: JSON {"map": NAME, "after_frames": N, "times": K, "marks": DIR} makes the
# task building NAME kill its own worker process (SIGKILL) after N frames, on its first
# K attempts (counted by files in DIR). Read in the worker; never set in production.
FAULT_VARIABLE = "ISG_SCALE_TEST_FAULT"  # not INHERIT_SG_*: those are config entries
PARTIAL_SUFFIX = ".partial"
# Written into a finished map before it is renamed into place: which build-many run made
# it and its summary, so that a retry after a kill between the rename and the task's
# return reports the map instead of mapping its sessions a second time.
RECORD_FILE = "build-many.json"


def partial_dir(root: Path, name: str, run_id: str) -> Path:
    """Where run ``run_id`` builds map ``name`` before renaming it into place."""
    return root / f".{name}.{run_id}{PARTIAL_SUFFIX}"


def _fault_hook(name: str) -> Any:
    """The progress callback that kills this worker when the fault hook asks, else None."""

    raw = os.environ.get(FAULT_VARIABLE)
    if not raw:
        return None
    spec = json.loads(raw)
    if spec.get("map") != name:
        return None
    marks = Path(spec["marks"])
    marks.mkdir(parents=True, exist_ok=True)
    done = len(list(marks.glob(f"{name}.*")))
    if done >= int(spec.get("times", 1)):
        return None
    after = int(spec.get("after_frames", 5))

    def progress(p: Any) -> None:
        if p.frames >= after:
            (marks / f"{name}.{done}").write_text(str(os.getpid()))
            os.kill(os.getpid(), signal.SIGKILL)

    return progress


def build_job(
    job: MapJob, root: str | Path, run_id: str, config: Config | None = None
) -> dict[str, Any]:
    """Build ``job`` under ``root`` all or nothing; its summary (sessions, frames, objects,
    rooms, seconds, host, pid), mapped with ``config`` (default: this process's
    configuration). Raises what :func:`inherit_sg.facade.build_map` raises,
    leaving no ``.partial`` folder behind unless the process itself is killed."""
    from inherit_sg.config import load_config
    from inherit_sg.facade import build_map
    from inherit_sg.store.lock import WriterLock
    from inherit_sg.store.mapdir import LOCK_FILE

    started = time.perf_counter()
    base = Path(root)
    final = base / job.name
    earlier = _finished_by(final, run_id)
    if earlier is not None:
        return earlier
    clean_up(base, job.name, run_id)  # what a killed attempt of this run left
    work = partial_dir(base, job.name, run_id)
    lock: WriterLock | None = None
    if (final / "map.json").is_file():
        lock = WriterLock(final / LOCK_FILE, final)
        lock.acquire()
    elif final.exists():
        raise MapError(f"{final} exists and is not a map: remove it or pick another name")
    try:
        if lock is not None:
            shutil.copytree(final, work, ignore=shutil.ignore_patterns(LOCK_FILE))
        cfg = config or load_config()
        hook = _fault_hook(job.name)
        summaries = [
            build_map(
                s.dataset,
                work,
                fmt=s.format,
                session_name=s.session,
                config=cfg,
                max_frames=s.max_frames,
                progress=hook,
            )
            for s in job.sessions
        ]
        record = _record(job, final, summaries, started)
        (work / RECORD_FILE).write_text(
            json.dumps({"run_id": run_id, "record": record}), encoding="utf-8"
        )
        _put_in_place(work, final, run_id, replace=lock is not None)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    finally:
        if lock is not None:
            lock.release()
    if lock is not None:
        shutil.rmtree(_aside(final, run_id), ignore_errors=True)
    return record


def clean_up(root: Path, name: str, run_id: str) -> None:
    """Undo what a killed attempt of run ``run_id`` left for map ``name``: its partial
    folder goes; an existing map it had renamed aside goes back in place (or, when the
    new map made it into place, away)."""
    shutil.rmtree(partial_dir(root, name, run_id), ignore_errors=True)
    final = root / name
    aside = _aside(final, run_id)
    if aside.exists():
        if final.exists():
            shutil.rmtree(aside, ignore_errors=True)
        else:
            os.rename(aside, final)


def _finished_by(final: Path, run_id: str) -> dict[str, Any] | None:
    """The record of ``final`` when run ``run_id`` already put it in place, else None."""
    try:
        doc = json.loads((final / RECORD_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return doc.get("record") if doc.get("run_id") == run_id else None


def _record(
    job: MapJob, final: Path, summaries: list[dict[str, Any]], started: float
) -> dict[str, Any]:
    """The summary row of a built map."""
    last = summaries[-1]
    return {
        "map": job.name,
        "path": str(final),
        "status": "built",
        "sessions": [s["session_id"] for s in summaries],
        "frames": sum(int(s["frames"]) for s in summaries),
        "keyframes": sum(int(s["keyframes"]) for s in summaries),
        **{k: last[k] for k in ("floors", "rooms", "areas", "objects", "relations")},
        "seconds": round(time.perf_counter() - started, 2),
        "host": socket.gethostname(),
        "pid": os.getpid(),
    }


def _aside(final: Path, run_id: str) -> Path:
    return final.parent / f".{final.name}.{run_id}.old"


def _put_in_place(work: Path, final: Path, run_id: str, *, replace: bool) -> None:
    """Rename the finished ``work`` folder to ``final`` (same file system: atomic); an
    existing map is first renamed aside, and put back when the second rename fails."""
    if not replace:
        os.rename(work, final)
        return
    aside = _aside(final, run_id)
    os.rename(final, aside)
    try:
        os.rename(work, final)
    except OSError:
        os.rename(aside, final)
        raise
