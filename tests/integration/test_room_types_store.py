"""The inferred room types on the Room node: migration of maps made at schema 1, the store
round trip on real Kuzu, Cypher over the column, and the JSON export / import."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from inherit_sg.errors import SchemaVersionError
from inherit_sg.facade import MapService, import_into_new_map
from inherit_sg.model import FloorNode, Layer, RoomNode, SceneGraph, make_id
from inherit_sg.store import MapStore
from inherit_sg.store import migrations as mig

TV_LIVING = (("living room", 0.5), ("tv room", 0.35), ("family room", 0.1))


def room_graph() -> SceneGraph:
    """A floor with a room that has inferred types and one that has none."""
    g = SceneGraph()
    g.add_or_update(FloorNode(make_id(Layer.FLOOR, 0), 0, "ground", 0.0, 2.8))
    g.add_or_update(
        RoomNode(make_id(Layer.ROOM, 0), "living room", floor_id="floor:0", types=TV_LIVING)
    )
    g.add_or_update(RoomNode(make_id(Layer.ROOM, 1), "kitchen", floor_id="floor:0"))
    return g


def test_a_schema_1_map_is_migrated(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    first = tmp_path / "schema1"
    first.mkdir()
    shutil.copy(mig.schema_dir() / "0001_init.cypher", first / "0001_init.cypher")
    path = tmp_path / "map"
    monkeypatch.setattr(mig, "schema_dir", lambda: first)
    with MapStore.create(path) as store:  # as made before rooms had types
        assert store.info.schema_version == 1
        store.cypher(
            "CREATE (:Room {id: 'room:0', label: 'kitchen', summary: 'a kitchen'})",
            read_only=False,
        )
        assert "types" not in {
            r[0] for r in store.cypher("CALL TABLE_INFO('Room') RETURN name").rows
        }
    monkeypatch.undo()
    latest = mig.latest_version()
    with pytest.raises(SchemaVersionError, match=f"version 1, older than version {latest}"):
        MapStore.open(path)
    with MapStore.open(path, write=True) as store:
        assert store.info.schema_version == latest
        info = dict(store.cypher("CALL TABLE_INFO('Room') RETURN name, type").rows)
        assert info["types"] == "STRING"  # JSON [[type, p], …]
        room = store.get_node("room:0")
        assert isinstance(room, RoomNode) and room.label == "kitchen" and room.types == ()
        room.types = (("kitchen", 0.9), ("dining room", 0.05))
        new = RoomNode(make_id(Layer.ROOM, 1), "living room", types=TV_LIVING)
        store.upsert_nodes([room, new])  # one updated and one appended in the same write
    with MapStore.open(path) as store:
        again, added = store.get_node("room:0"), store.get_node("room:1")
        assert isinstance(again, RoomNode) and isinstance(added, RoomNode)
        assert again.types == (("kitchen", 0.9), ("dining room", 0.05))
        assert again.summary == "a kitchen" and added.types == TV_LIVING
    assert f'"schema_version": {latest}' in (path / "map.json").read_text()


def test_types_round_trip_and_answer_cypher(tmp_path: Path) -> None:
    path = tmp_path / "map"
    with MapStore.create(path) as store:
        store.write_changes(room_graph())
    with MapStore.open(path) as store:
        loaded = store.load_graph()
        living, kitchen = loaded.get("room:0"), loaded.get("room:1")
        assert isinstance(living, RoomNode) and isinstance(kitchen, RoomNode)
        assert living.types == TV_LIVING and kitchen.types == ()
        maybe_tv = store.cypher(
            "MATCH (r:Room) WHERE r.types CONTAINS '\"tv room\"' RETURN r.id, r.label"
        ).rows
        assert maybe_tv == [["room:0", "living room"]]
        stored = store.cypher("MATCH (r:Room) RETURN r.id, r.types ORDER BY r.id").rows
        assert json.loads(stored[0][1]) == [[t, p] for t, p in TV_LIVING]
        assert stored[1] == ["room:1", "[]"]


def test_json_export_and_import_keep_the_types(tmp_path: Path) -> None:
    path = tmp_path / "map"
    with MapStore.create(path) as store:
        store.write_changes(room_graph())
    out = tmp_path / "map.json"
    with MapService.open(path) as service:
        service.export_json(out)
    doc = json.loads(out.read_text())
    rooms = {r["id"]: r for r in doc["nodes"] if r["layer"] == "ROOM"}
    assert rooms["room:0"]["types"] == [[t, p] for t, p in TV_LIVING]
    assert rooms["room:1"]["types"] == []
    import_into_new_map(out, tmp_path / "copy")
    with MapStore.open(tmp_path / "copy") as store:
        copy = store.get_node("room:0")
        assert isinstance(copy, RoomNode) and copy.types == TV_LIVING
    # an export written before rooms had types imports with none
    for rec in doc["nodes"]:
        rec.pop("types", None)
    older = tmp_path / "older.json"
    older.write_text(json.dumps(doc))
    import_into_new_map(older, tmp_path / "older")
    with MapStore.open(tmp_path / "older") as store:
        plain = store.get_node("room:0")
        assert isinstance(plain, RoomNode) and plain.types == () and plain.label == "living room"


def test_malformed_types_in_an_export_are_refused(tmp_path: Path) -> None:
    from inherit_sg.errors import InputError
    from inherit_sg.exchange.records import node_from_record, node_to_record

    rec = node_to_record(RoomNode(make_id(Layer.ROOM, 0), "kitchen", types=(("kitchen", 1.0),)))
    assert node_from_record(rec) == RoomNode(
        make_id(Layer.ROOM, 0), "kitchen", types=(("kitchen", 1.0),)
    )
    rec["types"] = ["kitchen"]
    with pytest.raises(InputError, match="types"):
        node_from_record(rec)
