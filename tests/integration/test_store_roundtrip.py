"""MapStore round trips on real Kuzu + LanceDB in tmp_path."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.errors import InputError, MapError, MapNotFoundError, NodeNotFoundError
from inherit_sg.model import Edge, EdgeKind, Layer, ObjectStatus, Session, make_id
from inherit_sg.store import MapStore
from inherit_sg.store.keyframes import KeyframeBlobs
from tests.integration.store_data import (
    assert_same_graph,
    assert_same_node,
    keyframe,
    make_object,
    sample_graph,
)


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, object]:
    """A map holding the sample graph, closed."""
    path = tmp_path_factory.mktemp("rt") / "map"
    graph = sample_graph()
    with MapStore.create(path) as store:
        changes = store.write_changes(graph)
        assert changes.new_nodes and not graph.changes.new_nodes
    return path, graph


def test_every_node_and_edge_type_round_trips(saved: tuple[Path, object]) -> None:
    path, graph = saved
    with MapStore.open(path) as store:
        loaded = store.load_graph()
    assert_same_graph(graph, loaded)  # type: ignore[arg-type]
    assert loaded.changes.empty
    kitchen = loaded.get("room:0")
    assert kitchen.mask is not None and kitchen.mask.cells.shape == (17, 23)  # type: ignore[union-attr]
    door = loaded.edge(("CONNECTS", "room:0", "room:1", ""))
    assert door is not None and door.prop("door") == (2.0, 0.5, 0.0) and door.prop("width") == 0.9
    hallway = loaded.get("room:1")
    assert hallway.text_embedding is None and hallway.mask is None  # type: ignore[union-attr]


def test_get_node_and_public_tables(saved: tuple[Path, object]) -> None:
    path, graph = saved
    with MapStore.open(path) as store:
        assert_same_node(graph.get("obj:3"), store.get_node("obj:3"))  # type: ignore[attr-defined]
        with pytest.raises(NodeNotFoundError):
            store.get_node("obj:999")
        with pytest.raises(NodeNotFoundError):
            store.get_node("nonsense")
        res = store.cypher(
            "MATCH (f:Floor)-[:HAS_ROOM]->(r:Room)-[:HAS_AREA]->(a:Area)-[:HAS_OBJECT]->(o:Object) "
            "WHERE o.status = 'active' RETURN f.level, r.label, a.label, o.id, o.bbox_max[3] "
            "ORDER BY o.id"
        )
        assert res.columns[:3] == ["f.level", "r.label", "a.label"]
        assert [r[3] for r in res.rows] == ["obj:0", "obj:1", "obj:2", "obj:3", "obj:5"]
        assert all(r[:3] == [0, "kitchen", "dining area"] and r[4] == 1.0 for r in res.rows)
        attrs = store.cypher("MATCH (o:Object {id: 'obj:2'}) RETURN o.attributes").rows[0][0]
        assert json.loads(attrs) == {"colour": "green", "n": 2, "size_m": [0.6, 0.6, 1.0]}
        rel = store.cypher(
            "MATCH (:Object {id: 'obj:0'})-[r:RELATION]->(b:Object) "
            "RETURN r.predicate, r.confidence, b.id ORDER BY r.predicate"
        ).rows
        assert rel == [["left_of", 0.6, "obj:1"], ["near", 0.8, "obj:1"]]
        limited = store.cypher("MATCH (o:Object) RETURN o.id", max_rows=2)
        assert len(limited.rows) == 2 and limited.truncated


def test_write_changes_updates_and_removals(tmp_path: Path) -> None:
    graph = sample_graph(seed=3)
    rng = np.random.default_rng(9)
    with MapStore.create(tmp_path / "m") as store:
        store.write_changes(graph)
        obj = graph.get("obj:1")
        obj.label = "armchair"  # type: ignore[union-attr]
        obj.status = ObjectStatus.REMOVED  # type: ignore[union-attr]
        obj.visual_feature = None  # type: ignore[union-attr]
        graph.touch("obj:1")
        graph.get("obj:2").text_embedding = rng.normal(size=384).astype(np.float32)  # type: ignore[union-attr]
        graph.touch("obj:2")
        graph.remove("obj:3")
        graph.remove_edge(EdgeKind.RELATION, "obj:0", "obj:1", "near")
        graph.add_or_update(make_object(rng, 10))
        graph.add_edge(Edge.make(EdgeKind.HAS_OBJECT, "area:0", "obj:10"))
        graph.add_edge(
            Edge.make(EdgeKind.RELATION, "obj:10", "obj:0", predicate="on", confidence=1.0)
        )
        graph.merge_nodes("obj:4", "obj:5")
        changes = store.write_changes(graph)
        assert "obj:3" in changes.removed_nodes and "obj:10" in changes.new_nodes
        assert store.write_changes(graph).empty
        loaded = store.load_graph()
        assert_same_graph(graph, loaded)
        stats = store.stats()
        assert stats.vectors["object_visual"] == len(list(graph.objects())) - 1
        assert stats.edges["RELATION"] == 2


def test_failed_write_is_rolled_back_and_changes_kept(tmp_path: Path) -> None:
    graph = sample_graph(n_objects=3)
    rng = np.random.default_rng(1)
    with MapStore.create(tmp_path / "m") as store:
        store.write_changes(graph)
        graph.add_or_update(make_object(rng, 7))
        bad = make_object(rng, 8)
        bad.visual_feature = np.ones(12, dtype=np.float32)  # wrong dimension
        graph.add_or_update(bad)
        with pytest.raises(InputError, match=r"obj:8.*256"):
            store.write_changes(graph)
        assert {"obj:7", "obj:8"} <= graph.changes.new_nodes  # put back for a retry
        with pytest.raises(NodeNotFoundError):
            store.get_node("obj:7")  # nothing of the failed transaction is visible
        bad.visual_feature = rng.normal(size=256).astype(np.float32)
        store.write_changes(graph)
        assert store.get_node("obj:8").label == bad.label


def test_edges_need_both_ends(tmp_path: Path) -> None:
    with MapStore.create(tmp_path / "m") as store:
        store.write_changes(sample_graph(n_objects=2))
        with pytest.raises(InputError, match="obj:77"):
            store.upsert_edges([Edge.make(EdgeKind.RELATION, "obj:0", "obj:77", predicate="near")])
        store.upsert_edges([Edge.make(EdgeKind.RELATION, "obj:1", "obj:0", predicate="near")])
        store.upsert_edges(
            [Edge.make(EdgeKind.RELATION, "obj:1", "obj:0", predicate="near", confidence=0.3)]
        )
        rel = store.cypher("MATCH (:Object {id:'obj:1'})-[r:RELATION]->() RETURN r.confidence")
        assert rel.rows == [[0.3]]  # replaced, not duplicated
        store.delete_edges([("RELATION", "obj:1", "obj:0", "near")])
        assert store.stats().edges["RELATION"] == 2
        store.delete_nodes(["obj:0"])
        stats = store.stats()
        assert stats.nodes["Object"] == 1 and stats.edges["RELATION"] == 0
        assert stats.vectors["object_visual"] == 1


def test_keyframes_sessions_and_stats(tmp_path: Path) -> None:
    rng = np.random.default_rng(5)
    path = tmp_path / "m"
    with MapStore.create(path) as store:
        store.write_changes(sample_graph(n_objects=2))  # SEEN_IN kf:0, kf:1 before they exist
        frames = [keyframe(rng, i) for i in range(4)]
        store.add_keyframes(frames)
        store.add_keyframes([frames[2]])  # idempotent
        session = Session("session:a", "morning", started=10.0, dataset="replica/office0")
        store.upsert_session(session)
        session.finished, session.frames, session.keyframes = 20.0, 100, 4
        store.upsert_session(session)
        store.upsert_session(Session("session:b", "evening", started=30.0))
        stats = store.stats()
    assert stats.nodes["Keyframe"] == 4 and stats.edges["SEEN_IN"] == 2
    assert stats.sessions == 2 and stats.nodes["Object"] == 2
    assert stats.bytes_total >= stats.bytes_graph + stats.bytes_lance > 0
    assert set(stats.to_dict()) >= {"nodes", "edges", "bytes_graph", "bytes_lance", "bytes_total"}
    card = json.loads((path / "map.json").read_text())
    assert [s["id"] for s in card["sessions"]] == ["session:a", "session:b"]
    assert card["sessions"][0]["frames"] == 100 and card["visual_dim"] == 256
    with MapStore.open(path) as store:
        assert [s.name for s in store.sessions()] == ["morning", "evening"]
        assert store.sessions()[0] == session
        plain = store.get_keyframe("kf:2")
        assert plain.jpeg is None and plain.pose == frames[2].pose and plain.frame_index == 20
        full = store.get_keyframe("kf:2", with_image=True)
        assert full.jpeg == frames[2].jpeg
        assert np.array_equal(full.global_feature, frames[2].global_feature)  # type: ignore[arg-type]
        hits = store.keyframe_search(frames[3].global_feature, k=2)  # type: ignore[arg-type]
        assert hits[0][0] == "kf:3" and hits[0][1] == pytest.approx(0.0, abs=1e-5)
        assert len(hits) == 2 and hits[1][1] >= hits[0][1]
        with pytest.raises(NodeNotFoundError):
            store.get_keyframe("kf:404")


def test_read_only_store_refuses_writes(saved: tuple[Path, object]) -> None:
    path, _ = saved
    with MapStore.open(path) as store:
        assert not store.writable
        node = store.get_node("obj:0")
        for call in (
            lambda: store.upsert_nodes([node]),
            lambda: store.delete_nodes(["obj:0"]),
            lambda: store.upsert_session(Session("s", "x", 0.0)),
            lambda: store.cypher("MATCH (o:Object) SET o.label = 'x'", read_only=False),
        ):
            with pytest.raises(MapError, match="read-only"):
                call()
    with pytest.raises(MapError, match="closed"):
        store.get_node("obj:0")


def test_missing_and_existing_maps(tmp_path: Path) -> None:
    with pytest.raises(MapNotFoundError, match="does not exist"):
        MapStore.open(tmp_path / "nowhere")
    (tmp_path / "plain").mkdir()
    (tmp_path / "plain" / "notes.txt").write_text("hi")
    with pytest.raises(MapNotFoundError, match="not an INHerit-SG map"):
        MapStore.open(tmp_path / "plain", write=True)
    with pytest.raises(MapError, match="not empty"):
        MapStore.create(tmp_path / "plain")
    MapStore.create(tmp_path / "m").close()
    with pytest.raises(MapError, match="already exists"):
        MapStore.create(tmp_path / "m")


def test_bad_node_ids_are_input_errors(tmp_path: Path) -> None:
    with MapStore.create(tmp_path / "m") as store:
        with pytest.raises(InputError, match="kf:1"):
            store.delete_nodes(["kf:1"])
        with pytest.raises(InputError, match="unknown edge kind"):
            store.delete_edges([("LIKES", "obj:0", "obj:1", "")])
        obj = make_object(np.random.default_rng(0), 1)
        obj.id = make_id(Layer.ROOM, 1)
        with pytest.raises(InputError, match="OBJECT"):
            store.upsert_nodes([obj])


def test_keyframe_rows_left_only_in_lancedb_are_dropped(tmp_path: Path) -> None:
    rng = np.random.default_rng(6)
    path = tmp_path / "m"
    kept, orphan = keyframe(rng, 1), keyframe(rng, 99)
    with MapStore.create(path) as store:
        store.add_keyframes([kept])
    # a crash between the LanceDB write and the Kuzu commit leaves a row like this one
    KeyframeBlobs(path / "lance", 256, writable=True).upsert([orphan])
    with MapStore.open(path) as store:
        hits = store.keyframe_search(orphan.global_feature, k=5)  # type: ignore[arg-type]
        assert [h[0] for h in hits] == ["kf:1"]
    with MapStore.open(path, write=True) as store:
        store.add_keyframes([keyframe(rng, 2)])
    assert KeyframeBlobs(path / "lance", 256, writable=False).ids() == {"kf:1", "kf:2"}


def test_keyframe_lookups_follow_writes_deletes_and_other_writers(tmp_path: Path) -> None:
    """Keyframe pictures are read by Lance row id (faster than a filtered scan); the row
    read must always be the keyframe asked for, after replacements, deletes, many
    appends (fragment compaction) and writes through another handle."""
    rng = np.random.default_rng(7)
    lance = tmp_path / "lance"
    writer = KeyframeBlobs(lance, 256, writable=True)
    frames = {f.id: f for f in (keyframe(rng, i) for i in range(6))}
    writer.upsert(list(frames.values()))
    reader = KeyframeBlobs(lance, 256, writable=False)

    def check(blobs: KeyframeBlobs) -> None:
        for kf_id, kf in frames.items():
            got = blobs.get(kf_id)
            assert got is not None and got[0] == kf.jpeg, kf_id
            assert np.array_equal(got[1], kf.global_feature)  # type: ignore[arg-type]

    check(writer)
    check(reader)
    frames["kf:2"] = keyframe(rng, 2)  # the same id with new bytes
    writer.upsert([frames["kf:2"]])
    writer.delete(["kf:4"])
    del frames["kf:4"]
    for i in range(100, 140):  # one fragment each: enough to trigger compaction
        frames[f"kf:{i}"] = keyframe(rng, i)
        writer.upsert([frames[f"kf:{i}"]])
    check(writer)
    assert writer.get("kf:4") is None
    other = KeyframeBlobs(lance, 256, writable=True)  # a second writer the first never sees
    frames["kf:3"] = keyframe(rng, 3)
    other.upsert([frames["kf:3"], keyframe(rng, 200)])
    fresh = KeyframeBlobs(lance, 256, writable=False)
    check(fresh)
    got = fresh.get("kf:200")
    assert got is not None
