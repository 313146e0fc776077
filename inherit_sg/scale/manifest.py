"""The ``map build-many`` manifest: a JSONL file, one map per line.

Each line is a JSON object::

    {"dataset": "walks/house-a", "format": "auto", "map": "house-a", "session": "monday"}
    {"map": "house-b", "sessions": [{"dataset": "walks/b-mon"}, {"dataset": "walks/b-tue",
     "format": "isg", "session": "tuesday", "max_frames": 200}]}

``dataset`` (or ``sessions``, a list of ``{dataset, format?, session?, max_frames?}``
run in order) is required; ``format`` defaults to ``auto``; ``map`` (the map directory's
name under the output root) defaults to the first dataset's folder name. Relative
dataset paths are read against the manifest's folder. Blank lines and lines starting
with ``#`` are skipped. Every problem names its line.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from inherit_sg.errors import InputError
from inherit_sg.ingest.readers import formats

MAP_KEYS = frozenset({"dataset", "format", "map", "session", "max_frames", "sessions"})
SESSION_KEYS = frozenset({"dataset", "format", "session", "max_frames"})
NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{0,127}$")


class ManifestError(InputError):
    """A build-many manifest line is malformed."""

    code = "bad_manifest"


@dataclass(frozen=True)
class SessionJob:
    """One mapping session: a dataset mapped into the map as a new session."""

    dataset: str
    format: str = "auto"
    session: str | None = None
    max_frames: int | None = None


@dataclass(frozen=True)
class MapJob:
    """One map to build (one Ray task): its name under the root and its sessions."""

    name: str
    sessions: tuple[SessionJob, ...]
    line: int = 0


def _session(raw: Any, base: Path, where: str, keys: frozenset[str]) -> SessionJob:
    if not isinstance(raw, dict):
        raise ManifestError(f"{where}: expected a JSON object, got {type(raw).__name__}")
    unknown = sorted(set(raw) - keys)
    if unknown:
        raise ManifestError(f"{where}: unknown field(s) {', '.join(unknown)}")
    dataset = raw.get("dataset")
    if not isinstance(dataset, str) or not dataset.strip():
        raise ManifestError(f"{where}: 'dataset' must be a non-empty path string")
    path = Path(dataset).expanduser()
    path = path if path.is_absolute() else base / path
    if not path.exists():
        raise ManifestError(f"{where}: dataset {path} does not exist")
    fmt = raw.get("format", "auto")
    known = ("auto", *formats())  # every registered reader
    if fmt not in known:
        raise ManifestError(f"{where}: format {fmt!r} is not one of {', '.join(known)}")
    session = raw.get("session")
    if session is not None and (not isinstance(session, str) or not session.strip()):
        raise ManifestError(f"{where}: 'session' must be a non-empty string")
    max_frames = raw.get("max_frames")
    if max_frames is not None and (
        isinstance(max_frames, bool) or not isinstance(max_frames, int) or max_frames < 1
    ):
        raise ManifestError(f"{where}: 'max_frames' must be a positive integer")
    return SessionJob(str(path), fmt, session, max_frames)


def parse_line(raw: Any, base: Path, line: int) -> MapJob:
    """One manifest line (already JSON-decoded) as a :class:`MapJob`."""
    where = f"line {line}"
    if not isinstance(raw, dict):
        raise ManifestError(f"{where}: expected a JSON object, got {type(raw).__name__}")
    unknown = sorted(set(raw) - MAP_KEYS)
    if unknown:
        raise ManifestError(f"{where}: unknown field(s) {', '.join(unknown)}")
    if "sessions" in raw:
        if "dataset" in raw or "session" in raw or "max_frames" in raw:
            raise ManifestError(
                f"{where}: give either 'dataset' (one session) or 'sessions', not both"
            )
        items = raw["sessions"]
        if not isinstance(items, list) or not items:
            raise ManifestError(f"{where}: 'sessions' must be a non-empty list")
        fmt = raw.get("format", "auto")
        sessions = tuple(
            _session(
                {"format": fmt, **item} if isinstance(item, dict) else item,
                base,
                f"{where}, session {i + 1}",
                SESSION_KEYS,
            )
            for i, item in enumerate(items)
        )
    else:
        single = {k: v for k, v in raw.items() if k != "map"}
        sessions = (_session(single, base, where, SESSION_KEYS),)
    name = raw.get("map", Path(sessions[0].dataset).name)
    if not isinstance(name, str) or not NAME.match(name):
        raise ManifestError(
            f"{where}: map name {name!r} must be 1-128 letters, digits, '.', '_' or '-' "
            "and start with a letter or digit"
        )
    return MapJob(name, sessions, line)


def read_manifest(path: str | Path) -> list[MapJob]:
    """Every map job of the manifest at ``path``, in file order; raises
    :class:`ManifestError` naming the line of the first problem."""
    src = Path(path)
    try:
        text = src.read_text(encoding="utf-8")
    except OSError as exc:
        raise ManifestError(f"cannot read manifest {src}: {exc.strerror or exc}") from None
    jobs: list[MapJob] = []
    seen: dict[str, int] = {}
    for number, content in enumerate(text.splitlines(), start=1):
        stripped = content.strip()
        if not stripped or stripped.startswith("#"):
            continue
        try:
            raw = json.loads(stripped)
        except json.JSONDecodeError as exc:
            raise ManifestError(f"line {number}: not valid JSON ({exc.msg})") from None
        job = parse_line(raw, src.parent, number)
        if job.name in seen:
            raise ManifestError(
                f"line {number}: map {job.name!r} is already built by line {seen[job.name]} "
                "(one task per map: list its datasets as 'sessions')"
            )
        seen[job.name] = number
        jobs.append(job)
    if not jobs:
        raise ManifestError(f"manifest {src} lists no maps")
    return jobs
