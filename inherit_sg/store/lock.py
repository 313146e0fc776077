"""The writer lock of a map: ``fcntl.flock`` on ``map.lock`` held while the map is open
for writing.

The file names the holder (pid, host, command line, start time) so a refused writer can
say who is in the way. Only the flock counts: a file left behind by a killed process is
not a lock and is simply taken over. Locks are per open file, so a second writer inside
the same process is refused too.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import socket
import sys
import time
from dataclasses import asdict, dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import IO

from inherit_sg.errors import MapError, MapLockedError


@dataclass(frozen=True)
class LockHolder:
    """Who holds (or last held) a map's writer lock."""

    pid: int
    host: str
    command: str
    since: str

    @classmethod
    def current(cls) -> LockHolder:
        """This process."""
        command = " ".join([Path(sys.argv[0]).name, *sys.argv[1:]]) if sys.argv else "python"
        return cls(os.getpid(), socket.gethostname(), command, datetime.now(UTC).isoformat())

    def describe(self) -> str:
        """Human-readable form used in error messages."""
        return f"pid {self.pid} ({self.command}) since {self.since} on host {self.host}"


def read_holder(lock_path: Path) -> LockHolder | None:
    """The holder recorded in the lock file, if it parses."""
    try:
        data = json.loads(lock_path.read_text(encoding="utf-8"))
        return LockHolder(int(data["pid"]), str(data["host"]), str(data["command"]), data["since"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def is_locked(lock_path: Path) -> bool:
    """Whether some open file currently holds the flock on ``lock_path``."""
    if not lock_path.exists():
        return False
    with open(lock_path, "a+b") as fh:
        try:
            fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return True
        fcntl.flock(fh.fileno(), fcntl.LOCK_UN)
        return False


def locked_error(map_path: Path, lock_path: Path) -> MapLockedError:
    """The error for a map held by another writer, naming the holder when known."""
    holder = read_holder(lock_path)
    who = holder.describe() if holder else "another process"
    return MapLockedError(f"map {map_path} is being written by {who}")


class WriterLock:
    """Exclusive, non-blocking (or bounded-wait) writer lock on one map."""

    def __init__(self, lock_path: Path, map_path: Path) -> None:
        self.lock_path = lock_path
        self.map_path = map_path
        self._fh: IO[bytes] | None = None

    @property
    def held(self) -> bool:
        """Whether this object holds the lock."""
        return self._fh is not None

    def acquire(self, timeout_s: float = 0.0) -> None:
        """Take the lock or raise :class:`MapLockedError` naming the holder; retries
        for up to ``timeout_s`` seconds."""
        if self._fh is not None:
            return
        try:
            fh = open(self.lock_path, "a+b")  # noqa: SIM115 - kept open while held
        except OSError as exc:
            raise MapError(f"cannot lock map {self.map_path}: {exc}") from None
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() >= deadline:
                    fh.close()
                    raise locked_error(self.map_path, self.lock_path) from None
                time.sleep(0.05)
        fh.seek(0)
        fh.truncate()
        fh.write(json.dumps(asdict(LockHolder.current())).encode("utf-8"))
        fh.flush()
        os.fsync(fh.fileno())
        self._fh = fh

    def release(self) -> None:
        """Clear the holder record and drop the lock (no-op when not held)."""
        fh, self._fh = self._fh, None
        if fh is None:
            return
        with contextlib.suppress(OSError):
            fh.seek(0)
            fh.truncate()
        fcntl.flock(fh.fileno(), fcntl.LOCK_UN)
        fh.close()
