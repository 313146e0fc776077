"""The Cypher lexer used by the read-only guard and the migration runner."""

from __future__ import annotations

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
