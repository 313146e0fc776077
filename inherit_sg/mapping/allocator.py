"""Keep a mapping process's resident memory close to what it really holds (glibc only).

Mapping allocates and frees many frame-sized numpy arrays on two threads. With glibc's
defaults each thread gets its own malloc arena (up to eight per core), and memory freed
inside an arena stays with the process until the top of that arena is free. On house
811 (640×480, two floors) a build's resident memory reached about 1.2 GB, of which
``malloc_trim`` handed back 460 MB at the end: memory freed long before, never returned.

Two cheap measures, both no-ops where the C library is not glibc:

- :func:`limit_arenas` caps the arenas at :data:`MAX_ARENAS` (the process's threads then
  share them). :func:`inherit_sg.facade.build_map` sets it before the database, the
  models and the mapping threads start; a server's live sessions leave it alone, as
  its request threads would then contend for two arenas;
- :func:`release_free_memory` gives freed heap pages back to the system (``malloc_trim``),
  called after each global update, when the largest temporary arrays are gone.

``bench/performance.py`` measures the effect (peak RSS of a whole build).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import logging
import threading

log = logging.getLogger(__name__)

# glibc's mallopt parameter for the arena count (malloc.h: M_ARENA_MAX = -8).
_M_ARENA_MAX = -8
# Arenas kept for the whole process: one per core of the 2-core reference machine.
MAX_ARENAS = 2

_lock = threading.Lock()
_libc: ctypes.CDLL | None = None
_loaded = False
_limited = False


def _glibc() -> ctypes.CDLL | None:
    """The C library when it is glibc (it has ``malloc_trim`` and ``mallopt``), else None."""
    global _libc, _loaded
    with _lock:
        if not _loaded:
            _loaded = True
            name = ctypes.util.find_library("c")
            try:
                lib = ctypes.CDLL(name) if name else None
            except OSError:
                lib = None
            if lib is not None and hasattr(lib, "malloc_trim") and hasattr(lib, "mallopt"):
                lib.malloc_trim.argtypes = [ctypes.c_size_t]
                lib.mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
                _libc = lib
        return _libc


def limit_arenas(count: int = MAX_ARENAS) -> bool:
    """Cap glibc's malloc arenas at ``count`` (once per process); whether it applied."""
    global _limited
    lib = _glibc()
    if lib is None:
        return False
    with _lock:
        if not _limited:
            _limited = bool(lib.mallopt(_M_ARENA_MAX, max(1, count)))
            log.debug("malloc arenas capped at %d: %s", count, _limited)
        return _limited


def release_free_memory() -> bool:
    """Return freed heap memory to the system; whether any was returned."""
    lib = _glibc()
    return bool(lib.malloc_trim(0)) if lib is not None else False
