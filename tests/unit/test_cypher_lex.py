"""The Cypher lexer used by the read-only guard and the migration runner."""

from __future__ import annotations

import pytest

from inherit_sg.errors import CypherError
from inherit_sg.store.cypher_lex import TokenKind, split_statements, tokenize


def test_token_kinds_and_positions() -> None:
    toks = list(tokenize("MATCH (n:`My Label`)\nWHERE n.x = 'a;b' AND n.y > $p RETURN 1.5"))
    kinds = {t.text: t.kind for t in toks}
    assert kinds["MATCH"] is TokenKind.WORD
    assert kinds["`My Label`"] is TokenKind.QUOTED
    assert kinds["'a;b'"] is TokenKind.STRING
    assert kinds["$p"] is TokenKind.PARAM
    assert kinds["1.5"] is TokenKind.NUMBER
    where = next(t for t in toks if t.text == "WHERE")
    assert (where.line, where.column) == (2, 1)


def test_comments_are_skipped_but_dashes_are_not() -> None:
    texts = [t.text for t in tokenize("a // x y\n b /* c\n d */ e--f")]
    assert texts == ["a", "b", "e", "-", "-", "f"]


def test_split_statements_respects_literals_and_comments() -> None:
    script = """
    // header; not a statement
    CREATE NODE TABLE A(id STRING PRIMARY KEY); -- keep
    MATCH (n) WHERE n.x = 'x;y' RETURN n;
    /* ; */
    RETURN "a;b";;
    """
    parts = split_statements(script)
    assert len(parts) == 3
    assert parts[0].startswith("// header") and parts[0].endswith("PRIMARY KEY)")
    assert parts[1].startswith("-- keep")  # '--' is not a Cypher comment
    assert parts[1].endswith("MATCH (n) WHERE n.x = 'x;y' RETURN n")
    assert parts[2].startswith("/* ; */") and parts[2].endswith('RETURN "a;b"')


def test_split_statements_of_blank_input() -> None:
    assert split_statements("  ;; // nothing\n") == []


def test_a_computed_skip_is_refused_where_no_worker_can_run_it() -> None:
    from inherit_sg.store.skip_guard import check_plain_skip

    for fine in (
        "MATCH (o) RETURN o SKIP 5 LIMIT 5",
        "MATCH (o) RETURN o SKIP $offset",
        "CALL { MATCH (o) RETURN o SKIP 3 } RETURN o",
        "MATCH (o) RETURN o.skip AS s",  # a property named skip is no clause
    ):
        check_plain_skip(fine)
    for computed in (
        "MATCH (o:Object) RETURN o.id ORDER BY o.id SKIP (20000) LIMIT 5",
        "MATCH (o) RETURN o SKIP 10000+10000 LIMIT 5",
        "MATCH (o) RETURN o SKIP toInteger('5')",
        "MATCH (o) RETURN o SKIP 2*5000",
    ):
        with pytest.raises(CypherError, match="plain number"):
            check_plain_skip(computed)
