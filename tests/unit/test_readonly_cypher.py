"""The read-only Cypher guard: write clauses refused, look-alikes allowed."""

from __future__ import annotations

import pytest

from inherit_sg.errors import CypherError, ReadOnlyViolationError
from inherit_sg.store.readonly import READ_PROCEDURES, check_read_only

ALLOWED = [
    "MATCH (n:Object) RETURN n.id",
    "match (o:Object)-[:RELATION {predicate: 'near'}]->(b) where o.label = 'chair' return b",
    "MATCH (s:Session) RETURN s.created, s.set, s.delete",  # property names
    "MATCH (n) WHERE n.label = 'please SET the table; DROP it' RETURN n",  # string literal
    'MATCH (n) WHERE n.description CONTAINS "CREATE" RETURN n',
    "MATCH (n) RETURN n.`create`, n.label AS `DELETE me`",  # backtick identifiers
    "MATCH (n) // DELETE n\nRETURN n",  # line comment
    "MATCH (n) /* SET n.x = 1; CREATE (m) */ RETURN n",  # block comment
    "MATCH (n:Set) RETURN n",  # a label
    "MATCH ()-[r:MERGE]->() RETURN count(r)",  # a rel type
    "RETURN {create: 1, drop: 2} AS m",  # map keys
    "MATCH (create:Object) RETURN create.id",  # a variable followed by a label
    "MATCH (n) WHERE n.label = 'it''s a \\'SET\\'' RETURN n",  # escaped quotes
    "WITH $set AS s RETURN s",  # parameter
    "UNWIND [1, 2, 3] AS x RETURN x * 2",
    "OPTIONAL MATCH (a)-[*1..3]-(b) RETURN a, b LIMIT 5",
    "MATCH (a)--(b) RETURN count(*)",  # undirected pattern, not a comment
    "CALL QUERY_VECTOR_INDEX('ObjectVisual', 'object_visual_hnsw', $q, 5) RETURN node.id",
    "CALL query_fts_index('Object', 'object_fts', 'red chair') RETURN node.id, score",
    "CALL SHOW_TABLES() RETURN *",
    "CALL table_info('Object') RETURN *",
    "CALL `SHOW_INDEXES`() RETURN *",
    "CALL db_version() RETURN *",
    "CALL current_setting('threads') RETURN *",
    "EXPLAIN MATCH (n) RETURN n",
    "PROFILE MATCH (n) RETURN n",
    "MATCH (n) RETURN n UNION MATCH (m) RETURN m",
    "RETURN 1.5e3, 'CHECKPOINT'",
    "MATCH (n) RETURN n.commit_count",
]

REFUSED = [
    ("CREATE (:Object {id: 'x'})", "CREATE"),
    ("MATCH (n) SET n.label = 'x'", "SET"),
    ("match (n) set n.label = 'x'", "SET"),
    ("MATCH (n) DELETE n", "DELETE"),
    ("MATCH (n) DETACH DELETE n", "DETACH DELETE"),
    ("MERGE (n:Object {id: 'x'})", "MERGE"),
    ("MATCH (n) REMOVE n.label", "REMOVE"),
    ("DROP TABLE Object", "DROP"),
    ("ALTER TABLE Object ADD x INT64", "ALTER"),
    ("COPY Object FROM 'objects.csv'", "COPY"),
    ("COPY (MATCH (n) RETURN n) TO '/tmp/out.csv'", "COPY"),
    ("LOAD FROM '/etc/passwd' RETURN *", "LOAD FROM"),
    ("LOAD WITH HEADERS (a STRING) FROM 'x.csv' RETURN *", "LOAD WITH"),
    ("LOAD EXTENSION fts", "LOAD EXTENSION"),
    ("INSTALL httpfs", "INSTALL"),
    ("FORCE INSTALL httpfs", "FORCE"),
    ("UNINSTALL fts", "UNINSTALL"),
    ("UPDATE fts", "UPDATE"),
    ("ATTACH 'other.kuzu' AS o (dbtype kuzu)", "ATTACH"),
    ("DETACH o", "DETACH"),
    ("USE o", "USE"),
    ("CHECKPOINT", "CHECKPOINT"),
    ("EXPORT DATABASE '/tmp/x'", "EXPORT"),
    ("IMPORT DATABASE '/tmp/x'", "IMPORT"),
    ("BEGIN TRANSACTION", "BEGIN"),
    ("COMMIT", "COMMIT"),
    ("ROLLBACK", "ROLLBACK"),
    ("COMMENT ON TABLE Object IS 'x'", "COMMENT ON"),
    ("CALL CREATE_VECTOR_INDEX('ObjectVisual', 'i', 'vec')", "CALL CREATE_VECTOR_INDEX"),
    ("CALL drop_fts_index('Object', 'object_fts')", "CALL DROP_FTS_INDEX"),
    ("CALL DROP_VECTOR_INDEX('ObjectVisual', 'object_visual_hnsw')", "CALL DROP_VECTOR_INDEX"),
    ("CALL threads=1", "CALL THREADS"),
    ("CALL READ_CSV('/etc/passwd') RETURN *", "CALL READ_CSV"),
    ("CALL FILE_INFO('/etc/passwd') RETURN *", "CALL FILE_INFO"),
    ("CALL PROJECT_GRAPH('g', ['Room'], ['CONNECTS'])", "CALL PROJECT_GRAPH"),
    ("RETURN nextval('seq')", "NEXTVAL()"),
    ("MATCH (n) RETURN n; CREATE (:Object {id: 'y'})", "CREATE"),  # second statement
    ("MATCH (n) WITH n /* ok */ SET n.x = 1", "SET"),  # after a comment
    ("MATCH (n) WHERE n.label = 'CREATE' SET n.label = 'x'", "SET"),  # after a string
    ("EXPLAIN CREATE (:Object {id: 'x'})", "CREATE"),
    ("MATCH (n) SET\nn.x = 1", "SET"),
    ("MATCH (n) SET n:Label", "SET"),
]


@pytest.mark.parametrize("query", ALLOWED)
def test_reads_pass(query: str) -> None:
    check_read_only(query)


@pytest.mark.parametrize(("query", "clause"), REFUSED)
def test_writes_are_refused_by_name(query: str, clause: str) -> None:
    with pytest.raises(ReadOnlyViolationError) as err:
        check_read_only(query)
    assert f"may not use {clause} " in err.value.message
    assert err.value.http_status == 403


def test_position_is_reported() -> None:
    with pytest.raises(ReadOnlyViolationError, match="line 2, column 3"):
        check_read_only("MATCH (n)\n  DELETE n")


@pytest.mark.parametrize("query", ["RETURN 'open", "MATCH (n) RETURN n.`x", "RETURN 1 /* never"])
def test_unterminated_tokens_are_cypher_errors(query: str) -> None:
    with pytest.raises(CypherError, match="unterminated"):
        check_read_only(query)


def test_allow_list_only_holds_readers() -> None:
    assert not any(p.startswith(("CREATE", "DROP", "READ_", "LOAD")) for p in READ_PROCEDURES)
    assert {"QUERY_VECTOR_INDEX", "QUERY_FTS_INDEX", "SHOW_TABLES"} <= READ_PROCEDURES
