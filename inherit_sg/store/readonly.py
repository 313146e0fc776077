"""Read-only Cypher guard: refuse statements that could change the map or reach
outside it, before they get near the database.

The check is lexical (see :mod:`inherit_sg.store.cypher_lex`), so keywords inside
string literals, backtick identifiers and comments are ignored, and so are property
names (``n.created``), labels (``:Set``), parameters, map keys and variables used as
``create.id``. The store also runs
read-only statements in a ``READ ONLY`` transaction (and on a read-only database when
no writer holds the map), so this guard is the first of two locks, not the only one.
"""

from __future__ import annotations

from inherit_sg.errors import ReadOnlyViolationError
from inherit_sg.store.cypher_lex import Token, TokenKind, tokenize

# Clause keywords that write data, change the schema, the session or the files.
_WRITE_CLAUSES: dict[str, str] = {
    "CREATE": "writes data or schema",
    "MERGE": "writes data",
    "SET": "writes data",
    "DELETE": "deletes data",
    "DETACH": "deletes data or detaches a database",
    "REMOVE": "writes data",
    "DROP": "changes the schema",
    "ALTER": "changes the schema",
    "COPY": "writes or exports data",
    "LOAD": "reads files or loads extensions",
    "INSTALL": "installs extensions",
    "FORCE": "installs extensions",
    "UNINSTALL": "removes extensions",
    "UPDATE": "updates extensions",
    "ATTACH": "attaches another database",
    "USE": "switches databases",
    "CHECKPOINT": "writes the database file",
    "IMPORT": "imports a database",
    "EXPORT": "exports a database",
    "BEGIN": "controls transactions",
    "COMMIT": "controls transactions",
    "COMMIT_SKIP_CHECKPOINT": "controls transactions",
    "ROLLBACK": "controls transactions",
    "ROLLBACK_SKIP_CHECKPOINT": "controls transactions",
}

# Procedures (CALL name(...)) that only read. Everything else is refused, including
# CREATE_*/DROP_* index procedures, file readers and connection settings (CALL x=1).
READ_PROCEDURES: frozenset[str] = frozenset(
    {
        "QUERY_VECTOR_INDEX",
        "QUERY_FTS_INDEX",
        "SHOW_TABLES",
        "TABLE_INFO",
        "SHOW_CONNECTION",
        "CURRENT_SETTING",
        "DB_VERSION",
        "CATALOG_VERSION",
        "SHOW_INDEXES",
        "SHOW_FUNCTIONS",
        "SHOW_SEQUENCES",
        "SHOW_WARNINGS",
        "SHOW_LOADED_EXTENSIONS",
        "SHOW_ATTACHED_DATABASES",
        "SHOW_PROJECTED_GRAPHS",
        "PROJECTED_GRAPH_INFO",
        "STATS_INFO",
        "STORAGE_INFO",
    }
)

# Functions with side effects (sequence counters).
_WRITE_FUNCTIONS = frozenset({"NEXTVAL"})

# Second words that make a clause name more precise in messages.
_QUALIFIERS = {"DETACH": {"DELETE"}, "LOAD": {"FROM", "EXTENSION", "WITH"}}


def _violation(name: str, why: str, tok: Token) -> ReadOnlyViolationError:
    return ReadOnlyViolationError(
        f"read-only query may not use {name} ({why}) at line {tok.line}, column {tok.column}"
    )


def _is_clause_position(tokens: list[Token], i: int) -> bool:
    """False for words that are property names, labels, rel types, map keys or
    variables (a clause keyword is never preceded by ``.``/``:`` nor followed by
    ``:``/``.``)."""
    if i > 0 and tokens[i - 1].kind is TokenKind.PUNCT and tokens[i - 1].text in ".:":
        return False
    nxt = tokens[i + 1] if i + 1 < len(tokens) else None
    return not (nxt is not None and nxt.kind is TokenKind.PUNCT and nxt.text in ":.")


def check_read_only(query: str) -> None:
    """Raise :class:`ReadOnlyViolationError` naming the first clause of ``query`` that
    could write (or read files, or change the session); return None when it is safe."""
    tokens = list(tokenize(query))
    for i, tok in enumerate(tokens):
        if tok.kind is not TokenKind.WORD or not _is_clause_position(tokens, i):
            continue
        word = tok.upper
        nxt = tokens[i + 1] if i + 1 < len(tokens) else None
        if word in _WRITE_CLAUSES:
            name = word
            if nxt is not None and nxt.upper in _QUALIFIERS.get(word, ()):
                name = f"{word} {nxt.upper}"
            raise _violation(name, _WRITE_CLAUSES[word], tok)
        if word == "COMMENT" and nxt is not None and nxt.upper == "ON":
            raise _violation("COMMENT ON", "changes the schema", tok)
        if word in _WRITE_FUNCTIONS and nxt is not None and nxt.text == "(":
            raise _violation(f"{word}()", "advances a sequence", tok)
        if word == "CALL":
            if nxt is None or nxt.kind not in (TokenKind.WORD, TokenKind.QUOTED):
                continue  # CALL { subquery }: its own clauses are checked in turn
            proc = nxt.text.strip("`").upper()
            if proc not in READ_PROCEDURES:
                raise _violation(f"CALL {proc}", "not a read-only procedure", tok)
