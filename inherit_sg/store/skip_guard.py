"""Refuse large ``SKIP`` values before they reach Kuzu.

Kuzu 0.11.3 crashes the whole process (segmentation fault) on ``ORDER BY … SKIP n``
once ``n`` exceeds roughly 11,500, even on a table with a few dozen rows. A served map
must not be killable by one read-only query, so statements whose ``SKIP`` (a literal or
a parameter) is above :data:`MAX_SKIP` are refused with a message that says how to page
instead.
"""

from __future__ import annotations

from typing import Any

from inherit_sg.errors import CypherError
from inherit_sg.store.cypher_lex import TokenKind, tokenize

MAX_SKIP = 10_000


def _value(text: str) -> int | None:
    try:
        return int(text)
    except ValueError:
        return None


def check_skip(query: str, params: dict[str, Any] | None = None) -> None:
    """Raise :class:`CypherError` when a ``SKIP`` of ``query`` exceeds :data:`MAX_SKIP`."""
    tokens = list(tokenize(query))
    for i, tok in enumerate(tokens[:-1]):
        if tok.kind is not TokenKind.WORD or tok.upper != "SKIP":
            continue
        nxt = tokens[i + 1]
        value: object = None
        if nxt.kind is TokenKind.NUMBER:
            value = _value(nxt.text)
        elif nxt.kind is TokenKind.PARAM:
            value = (params or {}).get(nxt.text.lstrip("$"))
        if isinstance(value, int) and value > MAX_SKIP:
            raise CypherError(
                f"SKIP {value} at line {tok.line} is above {MAX_SKIP}: the embedded database "
                "cannot skip that far safely; page on the sort key instead "
                "(e.g. WHERE o.id > $last ORDER BY o.id LIMIT n)"
            )


# What may follow a SKIP value without making it an expression.
_OPERATORS = frozenset("+-*/%^([.")


def check_plain_skip(query: str) -> None:
    """Raise :class:`CypherError` unless every ``SKIP`` takes a plain integer or a
    parameter. A computed offset (``SKIP (20000)``, ``SKIP 10000+10000``) gets past
    :func:`check_skip` and may crash Kuzu; this stricter rule guards the statements that
    must run in the serving process (a map open for writing admits no worker process)."""
    tokens = list(tokenize(query))
    for i, tok in enumerate(tokens):
        if tok.kind is not TokenKind.WORD or tok.upper != "SKIP":
            continue
        if i > 0 and tokens[i - 1].text == ".":  # a property named skip
            continue
        value = tokens[i + 1] if i + 1 < len(tokens) else None
        after = tokens[i + 2] if i + 2 < len(tokens) else None
        plain = value is not None and value.kind in (TokenKind.NUMBER, TokenKind.PARAM)
        if plain and after is not None and after.kind is TokenKind.PUNCT:
            plain = after.text not in _OPERATORS
        if not plain:
            raise CypherError(
                f"SKIP at line {tok.line} takes a computed value: while the map is being "
                "written (a live session), SKIP must be a plain number or a $parameter"
            )
