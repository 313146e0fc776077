"""Compacting a map (``MapStore.compact``, ``inherit-sg map compact``) on real Kuzu and
LanceDB: every node, edge, vector, keyframe and session is the same afterwards, the
files are smaller, and a failed rewrite leaves the map as it was."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.errors import MapError, MapLockedError
from inherit_sg.model import Edge, EdgeKind, Session
from inherit_sg.store import MapStore
from inherit_sg.store import compact as compact_mod
from inherit_sg.store import search as search_mod
from inherit_sg.store.compact import table_digests
from inherit_sg.store.indexes import VECTOR_INDEXES
from tests.integration.store_data import assert_same_graph, keyframe, make_object, sample_graph


def _written_many_times(path: Path) -> None:
    """A map written the way a mapping session writes it: many small flushes that
    move, relabel, add and remove objects, then keyframes and a session."""
    rng = np.random.default_rng(21)
    graph = sample_graph(n_objects=8)
    with MapStore.create(path) as store:
        store.write_changes(graph)
        for step in range(25):
            for i in range(8):
                obj = graph.get(f"obj:{i}")
                obj.position = (float(i), float(step), 0.5)  # type: ignore[union-attr]
                obj.observation_count += 1  # type: ignore[union-attr]
                graph.touch(obj.id)
            new = make_object(rng, 100 + step)
            graph.add_or_update(new)
            graph.add_edge(Edge.make(EdgeKind.HAS_OBJECT, "area:0", new.id))
            if step % 3 == 0 and step:
                graph.remove(f"obj:{100 + step - 1}")
            store.write_changes(graph)
        store.add_keyframes([keyframe(rng, i) for i in range(6)])
        store.upsert_session(Session("session:a", "morning", started=1.0, finished=2.0))


def _everything(store: MapStore) -> dict[str, object]:
    """What a user can read back from a map, for comparison."""
    with store._g().snapshot() as conn:  # every table's rows, hashed
        digests = table_digests(conn)
    obj = store.get_node("obj:3")
    return {
        "graph": store.load_graph(),
        "digests": digests,
        "sessions": store.sessions(),
        "keyframe": store.get_keyframe("kf:2", with_image=True),
        "visual": store.vector_search("object_visual", obj.visual_feature, k=5),  # type: ignore[attr-defined]
        "text": store.text_search("Object", "chair", k=50),
        "rooms": store.text_search("Room", "kitchen", k=5),
    }


def test_compact_keeps_everything_and_shrinks_the_map(tmp_path: Path) -> None:
    path = tmp_path / "m"
    _written_many_times(path)
    with MapStore.open(path, write=True) as store:
        before = _everything(store)
        report = store.compact()
        after = _everything(store)  # the same store goes on working
    assert_same_graph(before["graph"], after["graph"])  # type: ignore[arg-type]
    for key in ("digests", "sessions", "visual", "text", "rooms"):
        assert before[key] == after[key], key
    kf_before, kf_after = before["keyframe"], after["keyframe"]
    assert kf_after.jpeg == kf_before.jpeg and kf_after.pose == kf_before.pose  # type: ignore[attr-defined]
    assert report.after["graph.kuzu"] < report.before["graph.kuzu"]
    assert report.saved > 0 and report.tables >= 15
    with MapStore.open(path) as store:  # a reader sees the compacted map, index included
        again = _everything(store)
    assert_same_graph(before["graph"], again["graph"])  # type: ignore[arg-type]
    assert again["digests"] == before["digests"] and again["text"] == before["text"]
    assert not list(path.glob(".compact-*"))  # no work files left


def test_a_rewrite_that_differs_is_abandoned(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "m"
    _written_many_times(path)
    with MapStore.open(path) as store, store._g().snapshot() as conn:
        rows_before = table_digests(conn)
    real = compact_mod.table_digests
    calls = {"n": 0}

    def second_differs(conn):  # type: ignore[no-untyped-def]
        calls["n"] += 1
        found = real(conn)
        if calls["n"] == 2:  # the rewrite's digests: pretend a row went missing
            found["Object"] = compact_mod.TableDigest(found["Object"].rows - 1, "lost")
        return found

    monkeypatch.setattr(compact_mod, "table_digests", second_differs)
    with MapStore.open(path, write=True) as store:
        with pytest.raises(MapError, match="differs in Object; the map is unchanged"):
            store.compact()
        assert store.get_node("obj:3").label  # still open and readable
    monkeypatch.undo()
    with MapStore.open(path) as store, store._g().snapshot() as conn:
        assert table_digests(conn) == rows_before  # the original file, rows untouched
    assert not list(path.glob(".compact-*"))


def test_compact_needs_the_writer_lock(tmp_path: Path) -> None:
    path = tmp_path / "m"
    _written_many_times(path)
    with MapStore.open(path, write=True), pytest.raises(MapLockedError):
        MapStore.open(path, write=True)
    with MapStore.open(path) as reader, pytest.raises(MapError, match="read-only"):
        reader.compact()


def test_small_vector_sets_stay_out_of_the_mirror_until_they_grow(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Sets of at most EXACT_MAX_ROWS vectors are searched exactly over the graph, so
    the search index keeps no copy of them; past it the whole set is mirrored and gets
    its HNSW index."""
    monkeypatch.setattr(search_mod, "EXACT_MAX_ROWS", 20)
    rng = np.random.default_rng(4)
    spec = VECTOR_INDEXES["object_visual"]
    objs = [make_object(rng, i, area=None) for i in range(30)]
    with MapStore.create(tmp_path / "m") as store:
        store.upsert_nodes(objs[:15])
        assert store._index is not None and not store._index.has_hnsw(spec)
        with store._index.db.snapshot() as conn:
            assert not conn.execute(f"MATCH (v:{spec.table}) RETURN count(v)").get_next()[0]  # type: ignore[union-attr]
        store.upsert_nodes(objs[15:])
        assert store._index.has_hnsw(spec)
        with store._index.db.snapshot() as conn:
            mirrored = conn.execute(f"MATCH (v:{spec.table}) RETURN count(v)").get_next()[0]  # type: ignore[union-attr]
        assert mirrored == 30
        hits = store.vector_search("object_visual", objs[7].visual_feature, k=1)  # type: ignore[arg-type]
        assert hits[0][0] == objs[7].id


def test_cli_compacts_an_old_map(tmp_path: Path) -> None:
    path = tmp_path / "m"
    _written_many_times(path)
    out = subprocess.run(
        [sys.executable, "-m", "inherit_sg.cli.main", "map", "compact", str(path), "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    result = json.loads(out.stdout)
    assert result["after"]["graph.kuzu"] < result["before"]["graph.kuzu"]
    assert result["saved"] > 0
    bad = subprocess.run(
        [sys.executable, "-m", "inherit_sg.cli.main", "map", "compact", str(tmp_path / "none")],
        capture_output=True,
        text=True,
    )
    assert bad.returncode != 0 and "none" in bad.stderr and "Traceback" not in bad.stderr
