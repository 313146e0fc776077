"""Opening the parts of a map directory: the graph database (migrated when writable),
the search index database, both with clear errors for locked or broken maps."""

from __future__ import annotations

import logging
import shutil
from pathlib import Path

from inherit_sg.errors import MapCorruptError, MapLockedError, SchemaVersionError
from inherit_sg.store.kuzu_graph import KuzuGraph
from inherit_sg.store.lock import is_locked, locked_error
from inherit_sg.store.mapdir import (
    GRAPH_FILE,
    INDEX_FILE,
    LANCE_DIR,
    LOCK_FILE,
    MAP_JSON,
    MapInfo,
)
from inherit_sg.store.migrations import (
    apply_migrations,
    check_not_newer,
    latest_version,
    recorded_version,
)
from inherit_sg.store.search_index import SearchIndex

# Files an interrupted ``create`` may leave behind before map.json exists.
CREATE_LEFTOVERS = {
    GRAPH_FILE,
    GRAPH_FILE + ".wal",
    INDEX_FILE,
    INDEX_FILE + ".wal",
    LANCE_DIR,
    LOCK_FILE,
}


log = logging.getLogger(__name__)


def clear_leftovers(root: Path) -> None:
    """Remove what an interrupted create left (the caller holds the lock and checked
    that nothing else is in the directory)."""
    for name in CREATE_LEFTOVERS - {LOCK_FILE}:
        leftover = root / name
        if leftover.is_dir():
            shutil.rmtree(leftover)
        else:
            leftover.unlink(missing_ok=True)


# What Kuzu raises when it cannot open a file: RuntimeError for its own checks (a lock, a
# bad header), and whatever a C++ failure maps to on a garbled file (std::bad_alloc as
# MemoryError, std::length_error as ValueError, …).
_KUZU_OPEN_ERRORS = (RuntimeError, MemoryError, ValueError, IndexError, OverflowError)


def _damaged(root: Path, name: str, why: str) -> MapCorruptError:
    return MapCorruptError(
        f"map {root}: cannot open {name} ({why}); the file is damaged: restore the map "
        "from a backup, or import an earlier export (inherit-sg import FILE --map NEW)"
    )


def _open_kuzu(root: Path, name: str, read_only: bool) -> KuzuGraph:
    try:
        return KuzuGraph(root / name, read_only=read_only)
    except _KUZU_OPEN_ERRORS as exc:
        if "lock" not in str(exc).lower():
            raise _damaged(root, name, str(exc)) from None
        if is_locked(root / LOCK_FILE):
            raise locked_error(root, root / LOCK_FILE) from None
        raise MapLockedError(f"map {root} is open in another process ({name} is locked)") from None


def open_graph(
    root: Path, info: MapInfo, *, write: bool, create: bool = False, crashed: str | None = None
) -> KuzuGraph:
    """The graph database: created and migrated (``create``), migrated (``write``), or
    checked to be at this code's schema version (read-only). ``crashed``: why opening the
    file killed a probe process (:mod:`.open_probe`); it is then not opened here."""
    if not create and not (root / GRAPH_FILE).exists():
        raise MapCorruptError(f"map {root} has no {GRAPH_FILE}")
    if crashed is not None:
        raise _damaged(root, GRAPH_FILE, crashed)
    graph = _open_kuzu(root, GRAPH_FILE, read_only=not write)
    try:
        known = latest_version()
        if not create and info.schema_version > 0 and recorded_version(graph.reader()) == 0:
            # an empty or zeroed file must not be "upgraded" into an empty map
            raise _damaged(
                root, GRAPH_FILE, f"it holds no schema, though {MAP_JSON} records version "
                f"{info.schema_version}",
            )  # fmt: skip
        if write:
            with graph.writer() as conn:
                apply_migrations(conn, info.dims, root)
        else:
            have = check_not_newer(graph.reader(), root, known)
            if have < known:
                raise SchemaVersionError(
                    f"map {root} has schema version {have}, older than version {known} "
                    "used by this INHerit-SG; open it once for writing to upgrade it"
                )
    except BaseException:
        graph.close()
        raise
    return graph


def _raise_if_locked(root: Path, exc: Exception) -> None:
    """MapLockedError when Kuzu refused the search index because another process has it."""
    if "lock" in str(exc).lower():
        raise MapLockedError(
            f"map {root} is open in another process ({INDEX_FILE} is locked)"
        ) from None


def open_index(
    root: Path, info: MapInfo, *, write: bool, crashed: str | None = None
) -> SearchIndex | None:
    """The search index database; None for a read-only store when it is missing or
    damaged. A writable store whose index cannot be opened starts a fresh one (it is
    derived). ``crashed``: why opening the file killed a probe process; it is then
    treated as damaged without being opened here."""
    file = root / INDEX_FILE
    if not write:
        if not file.exists():
            return None
        try:
            if crashed is not None:
                raise RuntimeError(crashed)
            return SearchIndex(file, info.dims, read_only=True)
        except _KUZU_OPEN_ERRORS as exc:
            _raise_if_locked(root, exc)
            # derived data: the map answers without it (exact search over the graph)
            log.warning(
                "map %s: %s is damaged (%s); searching without it until the map is opened "
                "for writing (inherit-sg map build, or a live session), which rebuilds it",
                root, INDEX_FILE, str(exc).splitlines()[0][:200],
            )  # fmt: skip
            return None
    try:
        if crashed is not None:
            raise RuntimeError(crashed)
        return SearchIndex(file, info.dims, read_only=False)
    except _KUZU_OPEN_ERRORS as exc:
        _raise_if_locked(root, exc)
        log.warning("map %s: %s is damaged (%s); rebuilding it", root, INDEX_FILE, exc)
        remove_database(file)
        return SearchIndex(file, info.dims, read_only=False)


def remove_database(file: Path) -> None:
    """Delete a Kuzu database file and its write-ahead log (either may be missing)."""
    for path in (file, file.with_name(file.name + ".wal")):
        path.unlink(missing_ok=True)
