"""Crash safety and the writer lock, with real subprocesses."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.config import Config
from inherit_sg.errors import MapLockedError
from inherit_sg.store import MapStore

BATCH = 25

WRITER = textwrap.dedent(
    """
    import sys
    import numpy as np
    from inherit_sg.model import BBox3D, Edge, EdgeKind, ObjectNode, NodeId, SceneGraph
    from inherit_sg.store import MapStore

    store = MapStore.open(sys.argv[1], write=True)
    print("ready", flush=True)
    rng = np.random.default_rng(0)
    batch = 0
    while True:
        objs = [
            ObjectNode(
                NodeId(f"obj:{batch}_{j}"), f"thing {batch}", (float(j), 0.0, 0.0),
                BBox3D((j - 0.1, -0.1, 0.0), (j + 0.1, 0.1, 0.2)),
                description=f"batch {batch} item {j}",
                visual_feature=rng.normal(size=256).astype(np.float32),
                text_embedding=rng.normal(size=384).astype(np.float32),
            )
            for j in range(BATCH)
        ]
        graph = SceneGraph()
        for obj in objs:
            graph.add_or_update(obj)
        for j in range(BATCH - 1):
            graph.add_edge(Edge.make(EdgeKind.RELATION, objs[j].id, objs[j + 1].id, predicate="next"))
        store.write_changes(graph)  # one transaction per batch
        print(batch, flush=True)
        batch += 1
    """
).replace("BATCH", str(BATCH))

HOLDER = textwrap.dedent(
    """
    import sys, time
    from inherit_sg.store import MapStore
    store = MapStore.open(sys.argv[1], write=True)
    print("held", flush=True)
    time.sleep(60)
    """
)


def spawn(code: str, *args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-c", code, *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def check_batches(store: MapStore, committed: int) -> None:
    """Every reported batch is complete; no batch is partly there."""
    res = store.cypher("MATCH (o:Object) RETURN o.label, count(*) ORDER BY o.label")
    counts = {int(label.split()[1]): n for label, n in res.rows}
    assert set(range(committed)) <= set(counts)
    assert all(n == BATCH for n in counts.values()), counts
    assert max(counts) <= committed  # at most the batch in flight made it
    edges = store.cypher("MATCH ()-[r:RELATION]->() RETURN count(r)").rows[0][0]
    stats = store.stats()
    assert edges == len(counts) * (BATCH - 1)
    assert stats.vectors["object_visual"] == stats.vectors["object_text"] == len(counts) * BATCH


def test_sigkill_mid_batch_keeps_every_committed_batch(tmp_path: Path) -> None:
    path = tmp_path / "map"
    MapStore.create(path).close()
    proc = spawn(WRITER, str(path))
    assert proc.stdout is not None
    assert proc.stdout.readline().strip() == "ready", proc.stderr.read() if proc.stderr else ""
    lines: list[str] = []
    stamps: list[float] = []
    while len(lines) < 4:
        line = proc.stdout.readline()
        assert line, proc.stderr.read() if proc.stderr else "writer died"
        lines.append(line.strip())
        stamps.append(time.monotonic())
    time.sleep(float(np.median(np.diff(stamps[1:]))) / 2)  # halfway through the next batch
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    committed = len(lines) + sum(1 for _ in proc.stdout)  # lines printed before the kill
    with MapStore.open(path) as reader:  # read-only first: replays the WAL read-only
        check_batches(reader, committed)
        q = reader.get_node("obj:2_3").visual_feature
        assert reader.vector_search("object_visual", q, k=1)[0][0] == "obj:2_3"  # type: ignore[arg-type]
    with MapStore.open(path, write=True) as writer:  # the stale lock file is no lock
        check_batches(writer, committed)
        assert writer.text_search("Object", "batch", k=1)


def test_second_writer_process_gets_the_holder(tmp_path: Path) -> None:
    path = tmp_path / "map"
    MapStore.create(path).close()
    proc = spawn(HOLDER, str(path))
    try:
        assert proc.stdout is not None and proc.stdout.readline().strip() == "held"
        for write in (True, False):  # writers and readers both get the holder's name
            with pytest.raises(MapLockedError) as err:
                MapStore.open(path, write=write)
            msg = err.value.message
            assert msg.startswith(f"map {path} is being written by pid {proc.pid} (")
            assert str(path) in msg and " since " in msg and "-c" in msg
    finally:
        proc.kill()
        proc.wait()
    MapStore.open(path, write=True).close()  # free again once the holder is gone


def test_in_process_writer_is_exclusive(tmp_path: Path) -> None:
    path = tmp_path / "map"
    with MapStore.create(path), pytest.raises(MapLockedError, match=f"pid {os.getpid()}"):
        MapStore.open(path, write=True)
    code = (
        f"from inherit_sg.store import MapStore; MapStore.open({str(path)!r}, write=True).close()"
    )
    child = subprocess.run(
        [sys.executable, "-c", code + "; print('ok')"],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert child.stdout.strip() == "ok", child.stderr


def test_writer_waits_for_lock_timeout(tmp_path: Path) -> None:
    path = tmp_path / "map"
    cfg = Config()
    cfg.store.lock_timeout_s = 0.3
    with MapStore.create(path):
        start = time.monotonic()
        with pytest.raises(MapLockedError):
            MapStore.open(path, write=True, config=cfg)
        assert time.monotonic() - start >= 0.3
