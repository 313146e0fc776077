"""Open a map's Kuzu files in a throwaway process first, so that a damaged file cannot
take down the process that serves it.

Kuzu 0.11.3 ends its process with a segmentation fault when it opens some damaged files
(bit flips in ``index.kuzu``, for one), before any Python error can be raised. So before
a map's databases are opened here, a child process opens each of them read-only; a file
on which the child dies of a signal is reported as damaged. Errors the child survives are
left to the ordinary open, which names them.

Probing costs about 0.2 s, so the files' sizes and modification times are remembered in
``<map>/opened.json`` after a probe that passed and after a writer closed them (a writer
trusts what it wrote): an unchanged file is not probed again.
"""

from __future__ import annotations

import contextlib
import json
import os
import subprocess
import sys
from pathlib import Path

STAMP_FILE = "opened.json"
PROBE_TIMEOUT_S = 60.0

_CHILD = """
import sys
import kuzu
for path in sys.argv[1:]:
    try:
        db = kuzu.Database(path, read_only=True)
        conn = kuzu.Connection(db)
        conn.execute("CALL SHOW_TABLES() RETURN name")
        conn.close()
        db.close()
    except Exception:
        pass  # an error the ordinary open will name
    print(path, flush=True)
"""


def _stamp(file: Path) -> list[int] | None:
    """Size and modification time of ``file`` and of its write-ahead log."""
    try:
        st = file.stat()
    except OSError:
        return None
    stamp = [st.st_size, st.st_mtime_ns]
    wal = file.with_name(file.name + ".wal")
    with contextlib.suppress(OSError):
        wst = wal.stat()
        stamp += [wst.st_size, wst.st_mtime_ns]
    return stamp


def _read_stamps(root: Path) -> dict[str, list[int]]:
    try:
        data = json.loads((root / STAMP_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}


def remember(root: Path, names: list[str]) -> None:
    """Record the current stamps of ``names`` as safe to open (best effort: a map on
    read-only storage is simply probed every time)."""
    stamps = _read_stamps(root)
    for name in names:
        stamp = _stamp(root / name)
        if stamp is None:
            stamps.pop(name, None)
        else:
            stamps[name] = stamp
    tmp = root / f".{STAMP_FILE}.{os.getpid()}"
    try:
        tmp.write_text(json.dumps(stamps), encoding="utf-8")
        tmp.replace(root / STAMP_FILE)
    except OSError:
        tmp.unlink(missing_ok=True)


def crashing_files(root: Path, names: list[str]) -> dict[str, str]:
    """Name → why, for the files among ``names`` (in ``root``) whose opening kills the
    database engine. Files that do not exist, or that are unchanged since they were last
    known to be safe, are not opened."""
    known = _read_stamps(root)
    todo = [n for n in names if (s := _stamp(root / n)) is not None and known.get(n) != s]
    crashed: dict[str, str] = {}
    while todo:
        paths = [str(root / n) for n in todo]
        try:
            proc = subprocess.run(
                [sys.executable, "-c", _CHILD, *paths],
                capture_output=True,
                text=True,
                timeout=PROBE_TIMEOUT_S,
            )
        except subprocess.TimeoutExpired:
            late = f"opening it did not finish in {PROBE_TIMEOUT_S:.0f} s"
            crashed.update(dict.fromkeys(todo, late))
            break
        done = set(proc.stdout.split())
        opened = [n for n, p in zip(todo, paths, strict=True) if p in done]
        if proc.returncode == 0 or len(opened) == len(todo):
            break
        culprit = todo[len(opened)]
        signal_no = -proc.returncode if proc.returncode < 0 else None
        crashed[culprit] = (
            f"the database engine crashed opening it (signal {signal_no})"
            if signal_no
            else f"the database engine failed opening it (exit {proc.returncode})"
        )
        todo = todo[len(opened) + 1 :]
    safe = [n for n in names if n not in crashed and (root / n).exists()]
    if safe:
        remember(root, safe)
    return crashed
