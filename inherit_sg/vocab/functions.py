"""Functions (``functions.toml``): what people want to do → the object kinds that serve
it, and problem statements that imply a need."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from inherit_sg.vocab import VocabularyError, load_table, string_list


@dataclass(frozen=True)
class FunctionSense:
    """One way of asking for ``function``: verbs (empty = any verb or none), object words
    (empty = the verb's default sense) and the likely kinds, most likely first.
    ``stranded`` are "verb particle" phrases read only where the particle ends a purpose
    clause ("something to stand on"), never elsewhere ("a lamp standing on the floor")."""

    function: str
    verbs: tuple[str, ...]
    objects: tuple[str, ...]
    kinds: tuple[str, ...]
    stranded: tuple[str, ...] = ()


@dataclass(frozen=True)
class Problem:
    """A statement implying ``function``: subject words (any; empty = none needed),
    state words (any) and the likely kinds."""

    function: str
    subjects: tuple[str, ...]
    states: tuple[str, ...]
    kinds: tuple[str, ...]


def _kinds(
    entry: dict[str, Any], groups: dict[str, tuple[str, ...]], where: str
) -> tuple[str, ...]:
    value = entry.get("kinds")
    if isinstance(value, str) and value.startswith("@"):
        if value[1:] not in groups:
            raise VocabularyError(f"{where}: kinds names the unknown group {value!r}")
        return groups[value[1:]]
    kinds = string_list(entry, "kinds", where)
    if not kinds:
        raise VocabularyError(f"{where}: needs at least one kind")
    return kinds


def _function(entry: dict[str, Any], where: str) -> str:
    value = entry.get("function")
    if not isinstance(value, str) or not value.strip():
        raise VocabularyError(f"{where}: needs a 'function' name")
    return value.strip().lower()


@lru_cache(maxsize=1)
def groups() -> dict[str, tuple[str, ...]]:
    """Named groups of kinds ("seats", "tables", "storage")."""
    table = load_table("functions").get("groups", {})
    if not isinstance(table, dict):
        raise VocabularyError("functions.toml: [groups] must be a table")
    return {name: string_list(table, name, "functions.toml [groups]") for name in table}


@lru_cache(maxsize=1)
def senses() -> tuple[FunctionSense, ...]:
    """Every function sense, in file order."""
    data = load_table("functions")
    out = []
    for i, entry in enumerate(data.get("sense", [])):
        where = f"functions.toml sense #{i + 1}"
        if not isinstance(entry, dict):
            raise VocabularyError(f"{where} must be a table")
        out.append(
            FunctionSense(
                function=_function(entry, where),
                verbs=string_list(entry, "verbs", where),
                objects=string_list(entry, "objects", where),
                kinds=_kinds(entry, groups(), where),
                stranded=string_list(entry, "stranded", where),
            )
        )
    return tuple(out)


@lru_cache(maxsize=1)
def problems() -> tuple[Problem, ...]:
    """Every problem statement, in file order."""
    data = load_table("functions")
    out = []
    for i, entry in enumerate(data.get("problem", [])):
        where = f"functions.toml problem #{i + 1}"
        if not isinstance(entry, dict):
            raise VocabularyError(f"{where} must be a table")
        states = string_list(entry, "states", where)
        if not states:
            raise VocabularyError(f"{where}: needs at least one state word")
        out.append(
            Problem(
                function=_function(entry, where),
                subjects=string_list(entry, "subjects", where),
                states=states,
                kinds=_kinds(entry, groups(), where),
            )
        )
    return tuple(out)


def kinds_serving(function: str) -> tuple[str, ...]:
    """Kinds that serve ``function`` over all its senses, most likely first."""
    found = [k for s in senses() if s.function == function for k in s.kinds]
    return tuple(dict.fromkeys(found))


@lru_cache(maxsize=1)
def _usual_rooms() -> dict[str, str]:
    from inherit_sg.vocab.rooms import room_types

    table = load_table("functions").get("rooms", {})
    if not isinstance(table, dict):
        raise VocabularyError("functions.toml: [rooms] must be a table")
    known = set(room_types())
    out: dict[str, str] = {}
    for function, rtype in table.items():
        if not isinstance(rtype, str) or rtype not in known:
            raise VocabularyError(
                f"functions.toml [rooms] {function!r}: {rtype!r} is not a room type of rooms.toml"
            )
        out[function.strip().lower()] = rtype
    return out


def usual_room(function: str) -> str | None:
    """The room type where ``function`` is usually done ("wash dishes": a kitchen), from
    ``[rooms]`` in ``functions.toml``; None when it has none."""
    return _usual_rooms().get(function.strip().lower())


@lru_cache(maxsize=1)
def sense_phrases() -> tuple[tuple[str, str], ...]:
    """Every way the vocabulary asks for a function as a short phrase, with the function:
    each verb with each of its objects ("listen to playlist", "put out fire"), a verb
    alone where the sense has no objects, an object alone where it has no verbs. A
    phrase that two senses share keeps the first. Retrieval reads an unknown purpose
    by its nearest phrase here (:func:`inherit_sg.retrieval.match.resolve_matches`)."""
    out: dict[str, str] = {}
    for sense in senses():
        for verb in sense.verbs or ("",):
            for obj in sense.objects or ("",):
                phrase = " ".join(w for w in (verb, obj) if w)
                if phrase:
                    out.setdefault(phrase, sense.function)
    return tuple(out.items())


@lru_cache(maxsize=1)
def multiword_sense_phrases() -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The phrases of :func:`sense_phrases` of two words or more, and the function of
    each (single words resemble others by spelling as much as by meaning)."""
    pairs = [(p, f) for p, f in sense_phrases() if len(p.split()) > 1]
    return tuple(p for p, _ in pairs), tuple(f for _, f in pairs)


def function_verbs() -> frozenset[str]:
    """Every verb (lemma or "lemma particle") that names a function."""
    return frozenset(v for s in senses() for v in s.verbs)
