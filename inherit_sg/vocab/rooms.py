"""Room types (``rooms.toml``): their names and aliases, the objects that are evidence
for each type, and the words that name floors in room summaries.

The mapper names rooms from :func:`evidence`; the request parser and retrieval read
room names with :func:`room_words` and :func:`room_type`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from inherit_sg.vocab import VocabularyError, load_table, string_list

_FILE = "rooms.toml"
# Trailing room numbers: "bedroom 2", "bedroom #2", "office 2b".
_NUMBER = re.compile(r"#?\d+[a-z]?")


@dataclass(frozen=True)
class RoomType:
    """One room type: its name, aliases (file order) and evidence (label → weight)."""

    name: str
    aliases: tuple[str, ...]
    evidence: dict[str, float]


def _evidence(entry: dict[str, Any], where: str) -> dict[str, float]:
    table = entry.get("evidence", {})
    if not isinstance(table, dict):
        raise VocabularyError(f"{where}: 'evidence' must be a table of label = weight")
    out: dict[str, float] = {}
    for label, weight in table.items():
        if isinstance(weight, bool) or not isinstance(weight, int | float) or weight <= 0:
            raise VocabularyError(
                f"{where}: 'evidence' weight of {label!r} must be a positive number"
            )
        out[label.strip().lower()] = float(weight)
    return out


@lru_cache(maxsize=1)
def _types() -> tuple[RoomType, ...]:
    data = load_table("rooms")
    table = data.get("types")
    if not isinstance(table, dict) or not table:
        raise VocabularyError(f"{_FILE}: needs at least one [types.<name>] table")
    out = []
    for name, entry in table.items():
        where = f"{_FILE} [types.{name}]"
        if not isinstance(entry, dict):
            raise VocabularyError(f"{where} must be a table")
        out.append(
            RoomType(
                name=name.strip().lower(),
                aliases=string_list(entry, "aliases", where),
                evidence=_evidence(entry, where),
            )
        )
    return tuple(out)


def room_types() -> tuple[str, ...]:
    """Every room type, in file order."""
    return tuple(t.name for t in _types())


def aliases(rtype: str) -> tuple[str, ...]:
    """The aliases of room type ``rtype`` (file order); empty for an unknown type."""
    for t in _types():
        if t.name == rtype:
            return t.aliases
    return ()


@lru_cache(maxsize=1)
def evidence() -> dict[str, dict[str, float]]:
    """Room type → {object label: evidence weight}, for the types with evidence, in file
    order (the order breaks ties between equally supported types)."""
    return {t.name: dict(t.evidence) for t in _types() if t.evidence}


@lru_cache(maxsize=1)
def room_words() -> dict[str, str]:
    """Every surface phrase that names a room type (the type itself and its aliases) →
    the type; :class:`VocabularyError` when a phrase would name two types."""
    out: dict[str, str] = {}
    for t in _types():
        for phrase in (t.name, *t.aliases):
            key = " ".join(phrase.split())
            if not key:
                raise VocabularyError(f"{_FILE} [types.{t.name}]: 'aliases' has an empty entry")
            if out.get(key, t.name) != t.name:
                raise VocabularyError(
                    f"{_FILE} [types.{t.name}]: 'aliases' entry {key!r} already names {out[key]!r}"
                )
            out[key] = t.name
    return out


def _words(phrase: str) -> list[str]:
    words = phrase.lower().replace("-", " ").replace("_", " ").split()
    while words and _NUMBER.fullmatch(words[-1]):
        words.pop()
    return words


def room_type(phrase: str) -> str | None:
    """The room type ``phrase`` names, or None: case-insensitive, by the type's name or an
    alias ("Guest Room" → bedroom), else by the longest tail that is one ("upstairs guest
    bathroom" → bathroom); trailing numbers are ignored ("bedroom 2" → bedroom)."""
    words = _words(phrase)
    table = room_words()
    for start in range(len(words)):
        found = table.get(" ".join(words[start:]))
        if found is not None:
            return found
    return None


@lru_cache(maxsize=1)
def level_words() -> tuple[str, ...]:
    """Words naming floors in summaries, lowest first ("ground", "second", …)."""
    return string_list(load_table("rooms"), "level_words", _FILE)


def clear_caches() -> None:
    """Forget the parsed tables (after the files or ``DATA_DIR`` changed; tests)."""
    for fn in (_types, evidence, room_words, level_words):
        fn.cache_clear()
