"""Room types (``rooms.toml``): their names and aliases, the objects that are evidence
for or against each type, the size and shape cues and priors the mapper weighs with
them, related types, fixtures, and the words that name floors in room summaries.

The mapper infers a room's types from :func:`room_type_table` and :func:`fixtures`
(:mod:`inherit_sg.mapping.room_semantics`); the request parser and retrieval read room
names with :func:`room_words` and :func:`room_type`, and :func:`related` for types people
name interchangeably.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from inherit_sg.vocab import VocabularyError, load_table, string_list

_FILE = "rooms.toml"
# Trailing room numbers: "bedroom 2", "bedroom #2", "office 2b".
_NUMBER = re.compile(r"#?\d+[a-z]?")
_FIELDS = frozenset(
    {
        "aliases",
        "also",
        "prior",
        "base",
        "area",
        "narrow",
        "bare",
        "off_entrance",
        "related",
        "evidence",
        "single",
        "sets",
    }
)


@dataclass(frozen=True)
class RoomType:
    """One room type as ``rooms.toml`` defines it.

    ``evidence`` maps object kinds to weights (negative: evidence against the type);
    ``prior`` is the type's relative frequency in (0, 1]; ``base`` its score before any
    evidence; ``area`` its typical floor area range in m² (None: no size cue);
    ``narrow`` and ``bare`` the scores added when a room is long and narrow or holds
    only fixtures; ``off_entrance`` the score added on a storey without the building's
    entrance (an exterior door) when another storey has one; ``related`` the types
    people name it by, with a similarity;
    ``single`` whether a storey seldom has two rooms of the type; ``sets`` maps object
    kinds to ``(count, weight)``: at least ``count`` objects of the kind (or of kinds of
    it) together say ``weight`` more for the type (a set of chairs around a table);
    ``also`` the names of other types that people use for this one just as often ("den"
    for a TV room as well as a family room).
    """

    name: str
    aliases: tuple[str, ...]
    evidence: dict[str, float]
    prior: float = 1.0
    base: float = 0.0
    area: tuple[float, float] | None = None
    narrow: float = 0.0
    bare: float = 0.0
    off_entrance: float = 0.0
    related: dict[str, float] = field(default_factory=dict)
    single: bool = False
    sets: dict[str, tuple[int, float]] = field(default_factory=dict)
    also: tuple[str, ...] = ()


def _number(entry: dict[str, Any], key: str, where: str, default: float) -> float:
    value = entry.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise VocabularyError(f"{where}: {key!r} must be a number")
    return float(value)


def _evidence(entry: dict[str, Any], where: str) -> dict[str, float]:
    table = entry.get("evidence", {})
    if not isinstance(table, dict):
        raise VocabularyError(f"{where}: 'evidence' must be a table of label = weight")
    out: dict[str, float] = {}
    for label, weight in table.items():
        if (
            isinstance(weight, bool)
            or not isinstance(weight, int | float)
            or not math.isfinite(weight)
            or weight == 0
        ):
            raise VocabularyError(
                f"{where}: 'evidence' weight of {label!r} must be a non-zero number"
            )
        out[" ".join(label.lower().split())] = float(weight)
    return out


def _sets(entry: dict[str, Any], where: str) -> dict[str, tuple[int, float]]:
    table = entry.get("sets", {})
    if not isinstance(table, dict):
        raise VocabularyError(f"{where}: 'sets' must be a table of kind = [count, weight]")
    out: dict[str, tuple[int, float]] = {}
    for label, value in table.items():
        ok = (
            isinstance(value, list)
            and len(value) == 2
            and isinstance(value[0], int)
            and not isinstance(value[0], bool)
            and value[0] >= 2
            and isinstance(value[1], int | float)
            and not isinstance(value[1], bool)
            and math.isfinite(value[1])
            and value[1] != 0
        )
        if not ok:
            raise VocabularyError(
                f"{where}: 'sets' entry {label!r} must be [count >= 2, non-zero weight]"
            )
        out[" ".join(label.lower().split())] = (int(value[0]), float(value[1]))
    return out


def _area(entry: dict[str, Any], where: str) -> tuple[float, float] | None:
    value = entry.get("area")
    if value is None:
        return None
    ok = (
        isinstance(value, list)
        and len(value) == 2
        and all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
        and 0 < value[0] < value[1]
    )
    if not ok:
        raise VocabularyError(f"{where}: 'area' must be [smallest, largest] m², 0 < smallest")
    return float(value[0]), float(value[1])


def _related(entry: dict[str, Any], where: str) -> dict[str, float]:
    table = entry.get("related", {})
    if not isinstance(table, dict):
        raise VocabularyError(f"{where}: 'related' must be a table of type = similarity")
    out: dict[str, float] = {}
    for name, sim in table.items():
        if isinstance(sim, bool) or not isinstance(sim, int | float) or not 0 < sim <= 1:
            raise VocabularyError(
                f"{where}: 'related' similarity of {name!r} must be a number in (0, 1]"
            )
        out[name.strip().lower()] = float(sim)
    return out


def _flag(entry: dict[str, Any], key: str, where: str) -> bool:
    value = entry.get(key, False)
    if not isinstance(value, bool):
        raise VocabularyError(f"{where}: {key!r} must be true or false")
    return value


def _room_type(name: str, entry: Any) -> RoomType:
    where = f"{_FILE} [types.{name}]"
    if not isinstance(entry, dict):
        raise VocabularyError(f"{where} must be a table")
    unknown = sorted(set(entry) - _FIELDS)
    if unknown:
        raise VocabularyError(f"{where}: unknown field {unknown[0]!r}")
    prior = _number(entry, "prior", where, 1.0)
    if not 0 < prior <= 1:
        raise VocabularyError(f"{where}: 'prior' must be in (0, 1]")
    return RoomType(
        name=name.strip().lower(),
        aliases=string_list(entry, "aliases", where),
        evidence=_evidence(entry, where),
        prior=prior,
        base=_number(entry, "base", where, 0.0),
        area=_area(entry, where),
        narrow=_number(entry, "narrow", where, 0.0),
        bare=_number(entry, "bare", where, 0.0),
        off_entrance=_number(entry, "off_entrance", where, 0.0),
        related=_related(entry, where),
        single=_flag(entry, "single", where),
        sets=_sets(entry, where),
        also=string_list(entry, "also", where),
    )


@lru_cache(maxsize=1)
def _types() -> tuple[RoomType, ...]:
    data = load_table("rooms")
    table = data.get("types")
    if not isinstance(table, dict) or not table:
        raise VocabularyError(f"{_FILE}: needs at least one [types.<name>] table")
    out = tuple(_room_type(name, entry) for name, entry in table.items())
    names = {t.name for t in out}
    for t in out:
        for other in t.related:
            if other not in names or other == t.name:
                raise VocabularyError(
                    f"{_FILE} [types.{t.name}]: 'related' names {other!r}, not another type"
                )
    return out


@lru_cache(maxsize=1)
def _also_table() -> dict[str, tuple[str, ...]]:
    words = room_words()
    out: dict[str, list[str]] = {}
    for t in _types():
        for phrase in t.also:
            key = " ".join(phrase.lower().split())
            named = words.get(key)
            if named is None or named == t.name:
                raise VocabularyError(
                    f"{_FILE} [types.{t.name}]: 'also' entry {key!r} must be the name or an "
                    "alias of another type"
                )
            out.setdefault(key, []).append(t.name)
    return {k: tuple(v) for k, v in out.items()}


def also_named(phrase: str) -> tuple[str, ...]:
    """The types besides :func:`room_type` that ``phrase`` names just as well ("den": a
    family room, also a TV room), from the ``also`` lists of ``rooms.toml``; read like
    :func:`room_type` (longest tail, trailing numbers ignored)."""
    name = _room_name_in(phrase)
    return _also_table().get(name, ()) if name is not None else ()


def room_types() -> tuple[str, ...]:
    """Every room type, in file order."""
    return tuple(t.name for t in _types())


@lru_cache(maxsize=1)
def room_type_table() -> dict[str, RoomType]:
    """Room type name → its :class:`RoomType`, in file order."""
    return {t.name: t for t in _types()}


def aliases(rtype: str) -> tuple[str, ...]:
    """The aliases of room type ``rtype`` (file order); empty for an unknown type."""
    found = room_type_table().get(rtype)
    return found.aliases if found is not None else ()


@lru_cache(maxsize=1)
def evidence() -> dict[str, dict[str, float]]:
    """Room type → {object kind: evidence weight}, for the types with evidence, in file
    order (the order breaks ties between equally supported types). Negative weights are
    evidence against the type."""
    return {t.name: dict(t.evidence) for t in _types() if t.evidence}


def related(rtype: str) -> dict[str, float]:
    """Types people name ``rtype`` by (or ``rtype`` by them), with a similarity in
    (0, 1]: the larger of the two directions' values. Empty for an unknown type."""
    return dict(_related_table().get(rtype, {}))


@lru_cache(maxsize=1)
def _related_table() -> dict[str, dict[str, float]]:
    out: dict[str, dict[str, float]] = {t.name: {} for t in _types()}
    for t in _types():
        for other, sim in t.related.items():
            out[t.name][other] = max(out[t.name].get(other, 0.0), sim)
            out[other][t.name] = max(out[other].get(t.name, 0.0), sim)
    return out


@lru_cache(maxsize=1)
def fixtures() -> frozenset[str]:
    """Labels that say nothing about a room's type (doors, windows, lights)."""
    return frozenset(string_list(load_table("rooms"), "fixtures", _FILE))


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
    name = _room_name_in(phrase)
    return room_words()[name] if name is not None else None


def _room_name_in(phrase: str) -> str | None:
    """The name or alias ``phrase`` is, else its longest tail that is one (trailing
    numbers ignored); None when no tail names a room type."""
    words = _words(phrase)
    table = room_words()
    for start in range(len(words)):
        tail = " ".join(words[start:])
        if tail in table:
            return tail
    return None


# Kinds of room qualifier: whose the room is, and which by size ("the big bathroom").
QUALIFIER_KINDS = ("private", "shared", "largest", "smallest", "front", "back", "other")


@lru_cache(maxsize=1)
def _qualifiers() -> dict[str, str]:
    data = load_table("rooms").get("qualifiers", {})
    if not isinstance(data, dict):
        raise VocabularyError(f"{_FILE}: 'qualifiers' must be a table")
    out: dict[str, str] = {}
    for kind in QUALIFIER_KINDS:
        for phrase in string_list(data, kind, f"{_FILE} [qualifiers]"):
            out[" ".join(phrase.lower().split())] = kind
    return out


def room_qualifier(phrase: str) -> str | None:
    """Which of several rooms of a type ``phrase`` means: "private" ("master bathroom",
    "en suite"), "shared" ("guest bathroom", "spare room"), "largest" ("the big
    bathroom", "the main bedroom"), "smallest" ("the small bathroom"), "front", "back",
    "other" ("the second bathroom": not the main one) or None, by the
    words of ``[qualifiers]`` in ``rooms.toml`` (the longest phrase found wins)."""
    text = " " + " ".join(_words(phrase)) + " "
    found = [(len(q), kind) for q, kind in _qualifiers().items() if f" {q} " in text]
    return max(found)[1] if found else None


@lru_cache(maxsize=1)
def level_words() -> tuple[str, ...]:
    """Words naming floors in summaries, lowest first ("ground", "second", …)."""
    return string_list(load_table("rooms"), "level_words", _FILE)


def clear_caches() -> None:
    """Forget the parsed tables (after the files or ``DATA_DIR`` changed; tests)."""
    for fn in (
        _types,
        room_type_table,
        evidence,
        _related_table,
        fixtures,
        room_words,
        _also_table,
    ):
        fn.cache_clear()
    _qualifiers.cache_clear()
    level_words.cache_clear()
