"""Schema migrations: recorded, idempotent, upgrade older maps, refuse newer ones."""

from __future__ import annotations

import shutil
from pathlib import Path

import kuzu
import pytest

from inherit_sg.errors import MapCorruptError, SchemaVersionError
from inherit_sg.store import MapStore
from inherit_sg.store import migrations as mig
from inherit_sg.store.kuzu_util import rows, table_names

DIMS = {"visual_dim": 16, "text_dim": 8, "image_feature_dim": 4}


LATEST = mig.latest_version()  # of the packaged migrations
NEXT = LATEST + 1


def schema_copy(tmp_path: Path, extra: str | None = None) -> Path:
    """The packaged migrations, plus an optional step after them (version NEXT)."""
    folder = tmp_path / "schema"
    folder.mkdir()
    for file in mig.schema_dir().glob("*.cypher"):
        shutil.copy(file, folder / file.name)
    if extra is not None:
        (folder / f"{NEXT:04d}_notes.cypher").write_text(extra, encoding="utf-8")
    return folder


NOTES = """
// a note table and a new Object column
CREATE NODE TABLE IF NOT EXISTS Note(id STRING PRIMARY KEY, label STRING, text STRING);
ALTER TABLE Object ADD IF NOT EXISTS confidence DOUBLE DEFAULT 1.0;
/* index calls are skipped when the index exists */
CALL CREATE_FTS_INDEX('Note', 'note_fts', ['text']);
"""


def test_apply_is_recorded_and_idempotent(tmp_path: Path) -> None:
    db = kuzu.Database(str(tmp_path / "g.kuzu"))
    conn = kuzu.Connection(db)
    assert mig.recorded_version(conn) == 0
    assert mig.apply_migrations(conn, DIMS, tmp_path) == list(range(1, LATEST + 1))
    assert mig.apply_migrations(conn, DIMS, tmp_path) == []
    assert mig.recorded_version(conn) == LATEST >= 2
    recorded = rows(
        conn, "MATCH (m:_Migration) RETURN m.version, m.name, m.applied_at ORDER BY m.version"
    )
    assert recorded[0][:2] == [1, "init"] and recorded[0][2]
    assert recorded[1][:2] == [2, "room_types"]
    assert {"Floor", "Room", "Area", "Object", "Keyframe", "Session", "RELATION"} <= table_names(
        conn
    )
    info = rows(conn, "CALL TABLE_INFO('ObjectVisual') RETURN name, type")
    assert ["vec", "FLOAT[16]"] in info
    conn.close()
    db.close()


def test_older_database_is_upgraded(tmp_path: Path) -> None:
    folder = schema_copy(tmp_path, NOTES)
    db = kuzu.Database(str(tmp_path / "g.kuzu"))
    conn = kuzu.Connection(db)
    mig.apply_migrations(conn, DIMS, tmp_path, mig.load_migrations(folder)[:1])
    conn.execute("CREATE (:Object {id: 'obj:1', label: 'cup'})")
    applied = mig.apply_migrations(conn, DIMS, tmp_path, mig.load_migrations(folder))
    assert applied == list(range(2, NEXT + 1)) and mig.recorded_version(conn) == NEXT
    assert rows(conn, "MATCH (o:Object) RETURN o.id, o.confidence") == [["obj:1", 1.0]]
    conn.execute("CREATE (:Note {id: 'n1', label: '', text: 'remember the milk'})")
    hits = rows(conn, "CALL QUERY_FTS_INDEX('Note', 'note_fts', 'milk') RETURN node.id")
    assert hits == [["n1"]]
    assert mig.apply_migrations(conn, DIMS, tmp_path, mig.load_migrations(folder)) == []
    conn.execute(f"MATCH (m:_Migration {{version: {NEXT}}}) DELETE m")  # as if cut short
    assert mig.apply_migrations(conn, DIMS, tmp_path, mig.load_migrations(folder)) == [NEXT]
    assert rows(conn, "CALL QUERY_FTS_INDEX('Note', 'note_fts', 'milk') RETURN count(*)") == [[1]]
    conn.close()
    db.close()


def test_index_call_detection() -> None:
    assert mig.index_call("// c\nCALL create_fts_index('Object', 'o_fts', ['label'])") == (
        "Object",
        "o_fts",
    )
    assert mig.index_call('CALL CREATE_VECTOR_INDEX("T", "i", \'vec\')') == ("T", "i")
    assert mig.index_call("CALL DROP_FTS_INDEX('Object', 'o_fts')") is None
    assert mig.index_call("CREATE NODE TABLE A(id STRING PRIMARY KEY)") is None


def test_store_upgrades_on_writable_open_only(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "map"
    MapStore.create(path).close()
    folder = schema_copy(tmp_path, NOTES)
    monkeypatch.setattr(mig, "schema_dir", lambda: folder)
    older = rf"version {LATEST}, older than version {NEXT}.*writing"
    with pytest.raises(SchemaVersionError, match=older):
        MapStore.open(path)
    with MapStore.open(path, write=True) as store:
        assert store.info.schema_version == NEXT
        assert store.cypher("MATCH (m:_Migration) RETURN count(*)").rows == [[NEXT]]
    with MapStore.open(path) as store:
        assert store.cypher("CALL TABLE_INFO('Note') RETURN count(*)").rows == [[3]]
    assert f'"schema_version": {NEXT}' in (path / "map.json").read_text()


def test_newer_map_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "map"
    with MapStore.create(path) as store:
        store.cypher(  # as if a later INHerit-SG had upgraded the map
            "CREATE (:_Migration {version: 7, name: 'future', applied_at: ''})", read_only=False
        )
    for write in (False, True):
        with pytest.raises(SchemaVersionError) as err:
            MapStore.open(path, write=write)
        assert str(path) in err.value.message and "version 7" in err.value.message
        assert f"version {mig.latest_version()}" in err.value.message
    assert not (path / "map.lock").read_text()  # the refused writer released its lock


def test_bad_migration_files(tmp_path: Path) -> None:
    folder = tmp_path / "schema"
    folder.mkdir()
    (folder / "0001_a.cypher").write_text(
        "CREATE NODE TABLE IF NOT EXISTS A(id STRING PRIMARY KEY);"
    )
    (folder / "0003_c.cypher").write_text("")
    with pytest.raises(MapCorruptError, match="gaps"):
        mig.load_migrations(folder)
    (folder / "0003_c.cypher").rename(folder / "3_c.cypher")
    with pytest.raises(MapCorruptError, match="NNNN_name"):
        mig.load_migrations(folder)
    (folder / "3_c.cypher").unlink()
    (folder / "0002_b.cypher").write_text("CREATE NODE TABLE B(id STRING PRIMARY KEY, x NOPE);")
    db = kuzu.Database(str(tmp_path / "g.kuzu"))
    conn = kuzu.Connection(db)
    with pytest.raises(MapCorruptError, match="0002_b"):
        mig.apply_migrations(conn, DIMS, tmp_path, mig.load_migrations(folder))
    assert mig.recorded_version(conn) == 1  # the failed step is not recorded
    conn.close()
    db.close()
