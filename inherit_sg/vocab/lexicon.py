"""The request lexicon (``lexicon.toml``): words the request parser gives a domain
meaning — attribute adjectives, spatial prepositions, ranking words, places and
placements, floors, negation and emphasis, request framing, viewpoint cues and the words
of global questions and problem statements. Grammar itself (tokens, lemmas, tags,
dependencies) comes from spaCy (:mod:`inherit_sg.nlp`)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from inherit_sg.vocab import VocabularyError, load_table, string_list

_ATTRIBUTE_KEYS = ("size", "height", "shape", "state", "other")
_FLOOR_RELATIVE = ("upstairs", "downstairs", "top", "bottom")


def _section(data: dict[str, Any], *path: str) -> dict[str, Any]:
    node: Any = data
    for key in path:
        node = node.get(key) if isinstance(node, dict) else None
        if not isinstance(node, dict):
            raise VocabularyError(f"lexicon.toml: missing table [{'.'.join(path)}]")
    return node


def _words(data: dict[str, Any], section: str, key: str) -> frozenset[str]:
    return frozenset(_list(_section(data, section), key, f"lexicon.toml [{section}]"))


def _list(table: dict[str, Any], key: str, where: str) -> tuple[str, ...]:
    """A required list of words (a missing one is an error, not an empty list)."""
    if key not in table:
        raise VocabularyError(f"{where}: missing list {key!r}")
    return string_list(table, key, where)


def _str_map(table: dict[str, Any], where: str) -> dict[str, str]:
    out: dict[str, str] = {}
    for k, v in table.items():
        if not isinstance(v, str):
            raise VocabularyError(f"lexicon.toml [{where}]: {k!r} must map to a string")
        out[k.lower()] = v.lower()
    return out


def _place_map(table: dict[str, Any], where: str) -> dict[str, tuple[str, str]]:
    """``modifier = "predicate landmark"`` entries as (predicate, landmark) pairs."""
    out: dict[str, tuple[str, str]] = {}
    for key, value in _str_map(table, where).items():
        predicate, _, landmark = value.partition(" ")
        if not landmark.strip():
            raise VocabularyError(
                f"lexicon.toml [{where}]: {key!r} must map to 'predicate landmark', got {value!r}"
            )
        out[key] = (predicate, landmark.strip())
    return out


def _predicate_map(table: dict[str, Any], where: str) -> dict[str, str]:
    """``word = "predicate"`` entries, each a relation predicate with one landmark (a
    verb has one object; "between" needs two)."""
    out = _str_map(table, where)
    for key, value in out.items():
        if value == "between" or not value.replace("_", "").isalpha():
            raise VocabularyError(
                f"lexicon.toml [{where}]: {key!r} must map to a one-landmark relation "
                f"predicate, got {value!r}"
            )
    return out


def _int_map(table: dict[str, Any], where: str) -> dict[str, int]:
    out: dict[str, int] = {}
    for k, v in table.items():
        if not isinstance(v, int) or isinstance(v, bool):
            raise VocabularyError(f"lexicon.toml [{where}]: {k!r} must map to an integer")
        out[k.lower()] = v
    return out


@dataclass(frozen=True)
class Lexicon:
    """The parsed ``lexicon.toml`` (see the file's comments for each table)."""

    version: int
    materials: dict[str, str]
    adjectives: dict[str, tuple[str, str]]
    prepositions: dict[str, str]
    away_prepositions: frozenset[str]
    outside_prepositions: frozenset[str]
    # things "outside X" is beside, not out of: "the chair outside the sliding door"
    openings: frozenset[str]
    with_inverse: dict[str, str]
    relation_verbs: dict[str, str]
    superlatives: dict[str, str]
    ordinals: dict[str, int]
    numbers: dict[str, int]
    directions: dict[str, str]
    sides: dict[str, str]
    middle: frozenset[str]
    area_heads: frozenset[str]
    vague_places: frozenset[str]
    generic_things: frozenset[str]
    generic_areas: frozenset[str]
    room_words: frozenset[str]
    placements: dict[str, str]
    placement_nouns: dict[str, str]
    floor_nouns: frozenset[str]
    floor_phrases: dict[str, int | str]
    negations: frozenset[str]
    exceptions: frozenset[str]
    emphasis: frozenset[str]
    hedges: frozenset[str]
    fault_verbs: frozenset[str]
    determiners: frozenset[str]
    seekers: frozenset[str]
    report_sources: frozenset[str]
    report_verbs: frozenset[str]
    errand_markers: tuple[str, ...]
    anaphors: frozenset[str]
    other_words: frozenset[str]
    subordinators: frozenset[str]
    example_words: frozenset[str]
    adverbs: frozenset[str]
    filler: frozenset[str]
    meta_nouns: frozenset[str]
    be_like: frozenset[str]
    quantity_nouns: frozenset[str]
    on_rooms: frozenset[str]
    abstract_nouns: frozenset[str]
    position_nouns: dict[str, str]
    place_modifiers: dict[str, tuple[str, str]]
    corrections: frozenset[str]
    viewpoint_verbs: frozenset[str]
    seated_verbs: frozenset[str]
    facing_verbs: frozenset[str]
    contractions: dict[str, str]
    have_like: frozenset[str]
    other_verbs: frozenset[str]
    light_verbs: frozenset[str]
    mental_verbs: frozenset[str]
    locative_verbs: frozenset[str]
    locative_prepositions: frozenset[str]
    copular_verbs: frozenset[str]
    chore_verbs: frozenset[str]
    chore_prepositions: frozenset[str]
    viewpoints: dict[str, str]
    frames: dict[str, frozenset[str]]
    refine_openers: tuple[tuple[str, ...], ...]
    problems: dict[str, frozenset[str]]


def _adjectives(table: dict[str, Any]) -> dict[str, tuple[str, str]]:
    out: dict[str, tuple[str, str]] = {}
    for word, value in table.items():
        ok = isinstance(value, list) and len(value) == 2 and all(isinstance(v, str) for v in value)
        if not ok or value[0] not in _ATTRIBUTE_KEYS:
            raise VocabularyError(
                f"lexicon.toml [attributes.adjectives]: {word!r} must map to [key, value] "
                f"with key in {_ATTRIBUTE_KEYS}"
            )
        out[word.lower()] = (value[0], value[1].lower())
    return out


def _floor_phrases(table: dict[str, Any]) -> dict[str, int | str]:
    out: dict[str, int | str] = {}
    for phrase, value in table.items():
        if isinstance(value, bool) or not (isinstance(value, int) or value in _FLOOR_RELATIVE):
            raise VocabularyError(
                f"lexicon.toml [floors.phrases]: {phrase!r} must map to a level or one of "
                f"{_FLOOR_RELATIVE}"
            )
        out[phrase.lower()] = value
    return out


def _directions(table: dict[str, Any]) -> dict[str, str]:
    out: dict[str, str] = {}
    for side in table:
        for word in _list(table, side, "lexicon.toml [ranking.directions]"):
            out[word] = side
    return out


@lru_cache(maxsize=1)
def lexicon() -> Lexicon:
    """The request lexicon, parsed and validated once."""
    data = load_table("lexicon")
    rel = _section(data, "relations")
    rank = _section(data, "ranking")
    places = _section(data, "places")
    words = _section(data, "words")
    verbs = _section(data, "verbs")
    frames = _section(data, "frames")
    problems = _section(data, "problems")
    where = "lexicon.toml"
    return Lexicon(
        version=int(data["version"]),
        materials=_str_map(_section(data, "attributes", "materials"), "attributes.materials"),
        adjectives=_adjectives(_section(data, "attributes", "adjectives")),
        prepositions=_str_map(_section(rel, "prepositions"), "relations.prepositions"),
        away_prepositions=frozenset(_list(_section(rel, "negating"), "away", where)),
        outside_prepositions=frozenset(_list(_section(rel, "negating"), "outside", where)),
        openings=frozenset(_list(_section(rel, "negating"), "openings", where)),
        with_inverse=_str_map(_section(rel, "with_inverse"), "relations.with_inverse"),
        relation_verbs=_predicate_map(_section(rel, "verbs"), "relations.verbs"),
        superlatives=_str_map(_section(rank, "superlatives"), "ranking.superlatives"),
        ordinals=_int_map(_section(rank, "ordinals"), "ranking.ordinals"),
        numbers=_int_map(_section(rank, "numbers"), "ranking.numbers"),
        directions=_directions(_section(rank, "directions")),
        sides=_str_map(_section(rank, "sides"), "ranking.sides"),
        middle=frozenset(_list(_section(rank, "middle"), "words", where)),
        area_heads=frozenset(_list(places, "area_heads", where)),
        vague_places=frozenset(_list(places, "vague", where)),
        generic_things=frozenset(_list(places, "generic_things", where)),
        generic_areas=frozenset(_list(places, "generic_areas", where)),
        room_words=frozenset(_list(places, "room_words", where)),
        placements=_str_map(_section(places, "placements"), "places.placements"),
        placement_nouns=_str_map(_section(places, "placement_nouns"), "places.placement_nouns"),
        floor_nouns=_words(data, "floors", "nouns"),
        floor_phrases=_floor_phrases(_section(data, "floors", "phrases")),
        negations=_words(data, "logic", "negations"),
        exceptions=_words(data, "logic", "exceptions"),
        emphasis=_words(data, "logic", "emphasis"),
        hedges=_words(data, "logic", "hedges"),
        fault_verbs=_words(data, "logic", "fault_verbs"),
        determiners=frozenset(_list(words, "determiners", where)),
        seekers=frozenset(_list(words, "seekers", where)),
        report_sources=frozenset(_list(words, "report_sources", where)),
        report_verbs=frozenset(_list(words, "report_verbs", where)),
        errand_markers=tuple(_list(words, "errand_markers", where)),
        anaphors=frozenset(_list(words, "anaphors", where)),
        other_words=frozenset(_list(words, "other", where)),
        subordinators=frozenset(_list(words, "subordinators", where)),
        example_words=frozenset(_list(words, "examples", where)),
        adverbs=frozenset(_list(words, "adverbs", where)),
        filler=frozenset(_list(words, "filler", where)),
        meta_nouns=frozenset(_list(words, "meta_nouns", where)),
        be_like=frozenset(_list(words, "be_like", where)),
        quantity_nouns=frozenset(_list(words, "quantity_nouns", where)),
        on_rooms=frozenset(_list(words, "on_rooms", where)),
        abstract_nouns=frozenset(_list(words, "abstract_nouns", where)),
        position_nouns=_str_map(_section(words, "position_nouns"), "words.position_nouns"),
        place_modifiers=_place_map(_section(words, "place_modifiers"), "words.place_modifiers"),
        corrections=frozenset(_list(_section(words, "more"), "corrections", where)),
        viewpoint_verbs=frozenset(_list(_section(words, "more"), "viewpoint_verbs", where)),
        seated_verbs=frozenset(_list(_section(words, "more"), "seated_verbs", where)),
        facing_verbs=frozenset(_list(_section(words, "more"), "facing_verbs", where)),
        contractions={
            k.lower(): v for k, v in _section(words, "contractions").items() if isinstance(v, str)
        },
        have_like=frozenset(_list(words, "have_like", where)),
        other_verbs=frozenset(_list(verbs, "other", where)),
        light_verbs=frozenset(_list(verbs, "light", where)),
        mental_verbs=frozenset(_list(verbs, "mental", where)),
        locative_verbs=frozenset(_list(verbs, "locative", where)),
        locative_prepositions=frozenset(_list(verbs, "locative_prepositions", where)),
        copular_verbs=frozenset(_list(verbs, "copular", where)),
        chore_verbs=frozenset(_list(verbs, "chores", where)),
        chore_prepositions=frozenset(_list(verbs, "chore_prepositions", where)),
        viewpoints=_str_map(_section(data, "viewpoints"), "viewpoints"),
        frames={
            k: frozenset(_list(frames, k, where))
            for k in (
                "openers",
                "auxiliaries",
                "personal",
                "subjects",
                "predicates",
                "purpose_nouns",
            )
        },
        refine_openers=tuple(tuple(p.split()) for p in _list(frames, "refine_openers", where)),
        problems={
            k: frozenset(_list(problems, k, where))
            for k in ("subjects", "request_words", "speaker", "place_words")
        },
    )
