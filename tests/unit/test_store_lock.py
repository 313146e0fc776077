"""Writer lock file semantics inside one process."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from inherit_sg.errors import MapLockedError
from inherit_sg.store.lock import LockHolder, WriterLock, is_locked, read_holder


def test_lock_records_holder_and_is_exclusive(tmp_path: Path) -> None:
    lock_path = tmp_path / "map.lock"
    first = WriterLock(lock_path, tmp_path)
    first.acquire()
    assert first.held and is_locked(lock_path)
    holder = read_holder(lock_path)
    assert holder is not None and holder.pid == os.getpid() and holder.command
    second = WriterLock(lock_path, tmp_path)
    with pytest.raises(MapLockedError) as err:
        second.acquire(timeout_s=0.1)
    assert err.value.message == f"map {tmp_path} is being written by {holder.describe()}"
    assert err.value.http_status == 423
    first.release()
    assert not is_locked(lock_path) and read_holder(lock_path) is None
    second.acquire()
    second.release()
    second.release()  # releasing twice is harmless


def test_stale_lock_file_is_not_a_lock(tmp_path: Path) -> None:
    lock_path = tmp_path / "map.lock"
    stale = LockHolder(999_999, "elsewhere", "inherit-sg map build x", "2020-01-01T00:00:00")
    lock_path.write_text(json.dumps(stale.__dict__))
    assert not is_locked(lock_path)
    lock = WriterLock(lock_path, tmp_path)
    lock.acquire()
    current = read_holder(lock_path)
    assert current is not None and current.pid == os.getpid()
    lock.release()
    assert not is_locked(tmp_path / "absent.lock")
    assert "pid 999999 (inherit-sg map build x) since 2020" in stale.describe()
