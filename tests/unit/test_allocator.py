"""The mapping process's allocator tuning (glibc arenas and trimming)."""

from __future__ import annotations

import ctypes.util
import platform

import pytest

from inherit_sg.mapping import allocator

GLIBC = platform.system() == "Linux" and platform.libc_ver()[0] == "glibc"


@pytest.mark.skipif(not GLIBC, reason="the tuning applies to glibc only")
def test_arena_cap_applies_once_and_stays() -> None:
    assert ctypes.util.find_library("c")
    assert allocator.limit_arenas() is True
    # a second call (a second build in the same process) keeps the first setting
    assert allocator.limit_arenas(allocator.MAX_ARENAS) is True


@pytest.mark.skipif(not GLIBC, reason="the tuning applies to glibc only")
def test_freed_heap_memory_is_handed_back() -> None:
    # many chunks below glibc's mmap threshold live on the heap; once freed, trimming
    # returns their pages
    chunks = [bytearray(64 * 1024) for _ in range(2000)]
    for chunk in chunks:
        chunk[0] = 1
    del chunks
    assert allocator.release_free_memory() is True


def test_without_glibc_both_are_no_ops(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(allocator, "_loaded", True)
    monkeypatch.setattr(allocator, "_libc", None)
    monkeypatch.setattr(allocator, "_limited", False)
    assert allocator.limit_arenas() is False
    assert allocator.release_free_memory() is False
