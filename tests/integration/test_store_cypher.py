"""User Cypher through MapStore: guard, read-only transactions, errors, limits."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.errors import CypherError, InputError, MapError, ReadOnlyViolationError
from inherit_sg.store import MapStore
from inherit_sg.store.kuzu_graph import KuzuGraph
from tests.integration.store_data import sample_graph


@pytest.fixture(scope="module")
def map_path(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("cy") / "map"
    with MapStore.create(path) as store:
        store.write_changes(sample_graph())
    return path


def test_guard_and_errors(map_path: Path) -> None:
    with MapStore.open(map_path, write=True) as store:
        with pytest.raises(ReadOnlyViolationError, match="DETACH DELETE"):
            store.cypher("MATCH (o:Object) DETACH DELETE o")
        with pytest.raises(CypherError, match="one Cypher statement"):
            store.cypher("MATCH (n) RETURN n; MATCH (m) RETURN m")
        with pytest.raises(CypherError, match="MATC"):
            store.cypher("MATC (n) RETURN n")
        with pytest.raises(CypherError, match="Nope"):
            store.cypher("MATCH (n:Nope) RETURN n")
        res = store.cypher(
            "MATCH (o:Object) WHERE o.label = $l RETURN o.id ORDER BY o.id", {"l": "chair"}
        )
        assert res.columns == ["o.id"] and res.rows == [["obj:0"], ["obj:4"]]
        assert not res.truncated and res.to_dict()["rows"] == res.rows
        made = store.cypher("CREATE (:Floor {id: 'floor:9', level: 9}) RETURN 1", read_only=False)
        assert made.rows == [[1]]
        assert store.stats().nodes["Floor"] == 3
        store.cypher("MATCH (f:Floor {id: 'floor:9'}) DELETE f", read_only=False)
        with pytest.raises(InputError, match=r"index\.kuzu"):
            store.cypher(
                "CALL CREATE_VECTOR_INDEX('ObjectText', 'x', 'vec', metric := 'cosine')",
                read_only=False,
            )
        q = store.get_node("obj:2").visual_feature  # searches still work after raw writes
        assert store.vector_search("object_visual", q, k=1)[0][0] == "obj:2"  # type: ignore[arg-type]
        assert store.text_search("Object", "green", k=10)


def test_read_only_database_and_transactions(map_path: Path) -> None:
    graph = KuzuGraph(map_path / "graph.kuzu", read_only=True)
    try:
        with pytest.raises(MapError, match="read-only"), graph.writer():
            pass
        with graph.snapshot() as conn, pytest.raises(RuntimeError, match="read-only"):
            conn.execute("CREATE (:Floor {id: 'floor:8', level: 8})")
        res = graph.query("MATCH (f:Floor) RETURN count(*)")
        assert res.rows == [[2]]
    finally:
        graph.close()
    graph = KuzuGraph(map_path / "graph.kuzu", read_only=False)
    try:  # a writable database still runs user reads in a READ ONLY transaction
        with graph.snapshot() as conn, pytest.raises(RuntimeError, match="read-only"):
            conn.execute("CREATE (:Floor {id: 'floor:8', level: 8})")
    finally:
        graph.close()
