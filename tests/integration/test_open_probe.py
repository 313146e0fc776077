"""The open probe: a Kuzu file whose opening kills the engine is found in a throwaway
process, and the map answers with a clear error (graph) or without its derived search
index (index) instead of going down; unchanged files are not probed again."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.errors import MapCorruptError
from inherit_sg.store import MapStore, open_probe
from inherit_sg.store.mapdir import GRAPH_FILE, INDEX_FILE
from tests.e2e.oracle_maps import oracle_map

# A probe child that dies of SIGSEGV on the file named in CRASH_ON, as Kuzu 0.11.3 does on
# some damaged files (a real damaged file that crashes it cannot be made reliably here).
CRASHING_CHILD = """
import os, signal, sys
for path in sys.argv[1:]:
    if path.endswith(os.environ["CRASH_ON"]):
        os.kill(os.getpid(), signal.SIGSEGV)
    print(path, flush=True)
"""


@pytest.fixture
def map_dir(tmp_path: Path) -> Path:
    return oracle_map(tmp_path, "probe", 3)


def _crash_on(monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    monkeypatch.setattr(open_probe, "_CHILD", CRASHING_CHILD)
    monkeypatch.setenv("CRASH_ON", name)


def test_a_graph_that_crashes_the_engine_gives_a_clear_error(
    map_dir: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (map_dir / open_probe.STAMP_FILE).unlink(missing_ok=True)
    _crash_on(monkeypatch, GRAPH_FILE)
    with pytest.raises(MapCorruptError, match="crashed opening it"):
        MapStore.open(map_dir)


def test_an_index_that_crashes_the_engine_is_left_out_then_rebuilt(
    map_dir: Path, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    (map_dir / open_probe.STAMP_FILE).unlink(missing_ok=True)
    _crash_on(monkeypatch, INDEX_FILE)
    with caplog.at_level("WARNING"), MapStore.open(map_dir) as store:
        assert store.cypher("MATCH (o:Object) RETURN count(o)").rows[0][0] > 0
    assert "index.kuzu is damaged (the database engine crashed opening it" in caplog.text
    with MapStore.open(map_dir, write=True):  # a writer rebuilds the derived index
        pass
    assert "rebuilding it" in caplog.text
    monkeypatch.undo()
    with MapStore.open(map_dir) as store:  # the rebuilt index opens, unprobed
        assert store.cypher("MATCH (o:Object) RETURN count(o)").rows[0][0] > 0


def test_files_a_writer_left_are_not_probed_again(
    map_dir: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    with MapStore.open(map_dir, write=True):
        pass  # the writer records the stamps of what it wrote
    _crash_on(monkeypatch, GRAPH_FILE)
    assert open_probe.crashing_files(map_dir, [GRAPH_FILE, INDEX_FILE]) == {}
    (map_dir / open_probe.STAMP_FILE).unlink()
    assert GRAPH_FILE in open_probe.crashing_files(map_dir, [GRAPH_FILE, INDEX_FILE])
