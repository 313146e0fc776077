"""A small Cypher lexer: enough to find clause keywords outside string literals,
backtick identifiers and comments, and to split a script into statements."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from enum import Enum

from inherit_sg.errors import CypherError


class TokenKind(Enum):
    """Lexical classes the guard and the statement splitter care about."""

    WORD = "word"  # bare identifier or keyword
    QUOTED = "quoted"  # `backtick identifier`
    STRING = "string"  # 'text' or "text"
    NUMBER = "number"
    PARAM = "param"  # $name
    PUNCT = "punct"  # any other single character


@dataclass(frozen=True)
class Token:
    """One token with its position (1-based line and column) in the query."""

    kind: TokenKind
    text: str
    offset: int
    line: int
    column: int

    @property
    def upper(self) -> str:
        """Upper-cased text (keywords are case-insensitive)."""
        return self.text.upper()


def _is_word_char(ch: str) -> bool:
    return ch.isalnum() or ch == "_"


def _where(text: str, offset: int) -> tuple[int, int]:
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return line, column


def _skip_quoted(text: str, start: int, quote: str) -> int:
    """Index just past the literal opened at ``start``; backslash escapes in strings,
    doubled quotes in both strings and backtick identifiers."""
    i = start + 1
    n = len(text)
    while i < n:
        ch = text[i]
        if ch == "\\" and quote != "`":
            i += 2
            continue
        if ch == quote:
            if i + 1 < n and text[i + 1] == quote:
                i += 2
                continue
            return i + 1
        i += 1
    line, col = _where(text, start)
    what = "backtick identifier" if quote == "`" else "string literal"
    raise CypherError(f"unterminated {what} starting at line {line}, column {col}")


def tokenize(text: str) -> Iterator[Token]:
    """Yield the tokens of ``text``, skipping whitespace and comments.

    Raises :class:`CypherError` for an unterminated string, identifier or comment.
    """
    i = 0
    n = len(text)
    while i < n:
        ch = text[i]
        if ch.isspace():
            i += 1
            continue
        if text.startswith("//", i):
            end = text.find("\n", i)
            i = n if end < 0 else end + 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            if end < 0:
                line, col = _where(text, i)
                raise CypherError(f"unterminated comment starting at line {line}, column {col}")
            i = end + 2
            continue
        start = i
        if ch in "'\"`":
            i = _skip_quoted(text, i, ch)
            kind = TokenKind.QUOTED if ch == "`" else TokenKind.STRING
        elif ch == "$" and i + 1 < n and _is_word_char(text[i + 1]):
            i += 1
            while i < n and _is_word_char(text[i]):
                i += 1
            kind = TokenKind.PARAM
        elif ch.isdigit():
            while i < n and (_is_word_char(text[i]) or text[i] == "."):
                i += 1
            kind = TokenKind.NUMBER
        elif _is_word_char(ch):
            while i < n and _is_word_char(text[i]):
                i += 1
            kind = TokenKind.WORD
        else:
            i += 1
            kind = TokenKind.PUNCT
        line, col = _where(text, start)
        yield Token(kind, text[start:i], start, line, col)


def split_statements(text: str) -> list[str]:
    """Split a script at top-level semicolons; empty statements are dropped."""
    out: list[str] = []
    start = 0
    for tok in tokenize(text):
        if tok.kind is TokenKind.PUNCT and tok.text == ";":
            out.append(text[start : tok.offset])
            start = tok.offset + 1
    out.append(text[start:])
    return [s.strip() for s in out if any(True for _ in tokenize(s))]
