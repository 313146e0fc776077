"""Request text checks, normalisation and word tokenisation."""

from __future__ import annotations

import re
import unicodedata

from inherit_sg.errors import QueryTextError

MAX_QUERY_CHARS = 1000

_CONTRACTIONS = {
    "can't": "can not",
    "cannot": "can not",
    "won't": "will not",
    "shan't": "shall not",
    "i'm": "i am",
    "let's": "let us",
    "where's": "where is",
    "what's": "what is",
    "that's": "that is",
    "there's": "there is",
    "here's": "here is",
    "it's": "it is",
    "who's": "who is",
    "how's": "how is",
}
_SUFFIXES = (("n't", " not"), ("'re", " are"), ("'ve", " have"), ("'ll", " will"), ("'d", " would"))
_WORD = re.compile(r"[a-z]+(?:'[a-z]+)?|\d+(?:st|nd|rd|th)?|,")
_QUOTES = str.maketrans({"’": "'", "‘": "'", "`": "'", "´": "'", "“": '"', "”": '"'})
_SEPARATORS = re.compile(r"[-_/+]+")
_LETTER_DIGIT = re.compile(r"(?<=[a-z])(?=\d)|(?<=\d)(?!st\b|nd\b|rd\b|th\b)(?=[a-z])")
_CLAUSE_BREAK = re.compile(r"[;:!?.()\[\]]+")


def check_query_text(text: object) -> str:
    """Return ``text`` stripped, or raise :class:`QueryTextError` saying what is wrong.

    A request must be a ``str`` with at least one letter, at most
    ``MAX_QUERY_CHARS`` characters, and no control characters other than whitespace.
    """
    if not isinstance(text, str):
        raise QueryTextError(f"query must be text, got {type(text).__name__}")
    stripped = text.strip()
    if not stripped:
        raise QueryTextError("query text is empty")
    if len(stripped) > MAX_QUERY_CHARS:
        raise QueryTextError(
            f"query text is {len(stripped)} characters long; the limit is {MAX_QUERY_CHARS}"
        )
    bad = [c for c in stripped if unicodedata.category(c) in ("Cc", "Cs") and not c.isspace()]
    if bad:
        raise QueryTextError(f"query text contains control character {bad[0]!r}")
    if not any(c.isalpha() for c in stripped):
        raise QueryTextError("query text contains no words")
    return stripped


def _expand(word: str) -> str:
    if word in _CONTRACTIONS:
        return _CONTRACTIONS[word]
    for suffix, full in _SUFFIXES:
        if word.endswith(suffix):
            stem = word[: -len(suffix)]
            return (stem if stem not in ("ca", "wo") else stem + "n") + full
    if word.endswith("'s"):
        return word[:-2]
    return word.replace("'", "")


def tokenize(text: str) -> list[str]:
    """Lower-case words with contractions expanded; clause breaks become commas.

    ``"Where's the TV-stand? I can't see it"`` → ``where is the tv stand , i can not see it``.
    """
    text = unicodedata.normalize("NFKC", text).translate(_QUOTES)
    # split camel case ("CoffeeTable") before lower-casing
    text = re.sub(r"(?<=[a-z])(?=[A-Z])", " ", text).lower()
    text = _SEPARATORS.sub(" ", text)
    text = _LETTER_DIGIT.sub(" ", text)
    text = _CLAUSE_BREAK.sub(" , ", text)
    words: list[str] = []
    for raw in _WORD.findall(text):
        words.extend(_expand(raw).split())
    while words and words[-1] == ",":
        words.pop()
    return words
