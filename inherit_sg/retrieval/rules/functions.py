"""Function senses: a verb and its object words → a canonical function and likely kinds.

"wash my hands" → ``wash hands`` (sink); "have a casual conversation" → ``talk``;
"watch something on a large screen" → ``watch tv``. A sense naming object words beats
the verb's default sense; senses without verbs are purpose nouns ("a meal", "a break")
that any verb, or none ("for a meeting"), can carry.
"""

from __future__ import annotations

from functools import lru_cache
from itertools import pairwise

from inherit_sg.retrieval import lexicon as lx

Sense = tuple[str, tuple[str, ...]]
_FUNCTION_WORDS = frozenset({"for", "of", "to", "with", "and", "or", "out", "up", "down", "off"})


@lru_cache(maxsize=1)
def _by_verb() -> dict[str, list[tuple[str, frozenset[str], tuple[str, ...]]]]:
    table: dict[str, list[tuple[str, frozenset[str], tuple[str, ...]]]] = {}
    for function, verbs, objects, labels in lx.FUNCTIONS:
        for verb in verbs or ("",):
            table.setdefault(verb, []).append((function, frozenset(objects), labels))
    return table


def _object_terms(words: list[str]) -> set[str]:
    terms = {lx.singular(w) for w in words} | set(words)
    # two-word purpose nouns ("fresh air", "get together")
    terms |= {f"{a} {b}" for a, b in pairwise(words)}
    return terms


def match_function(
    verb: str | None, words: list[str], primary: list[str] | None = None
) -> Sense | None:
    """The best sense for ``verb`` (a lemma or "lemma particle"; None for a bare purpose
    phrase) with object ``words``, or None when nothing fits.

    Scores: verb with a matching object word 3, the verb's default sense 2, a purpose
    noun 1; a match on a ``primary`` word (the object's head) adds 0.5.
    """
    table = _by_verb()
    terms = _object_terms(words)
    heads = _object_terms(primary or [])
    candidates: list[tuple[float, str, tuple[str, ...]]] = []
    if verb:
        for key in dict.fromkeys((verb, verb.split()[0])):
            for function, objects, labels in table.get(key, []):
                if objects & terms:
                    bonus = 0.5 if objects & heads else 0.0
                    candidates.append((3 + bonus, function, labels))
                elif not objects:
                    candidates.append((2, function, labels))
    for function, objects, labels in table.get("", []):
        if objects & terms:
            candidates.append((1 + (0.5 if objects & heads else 0.0), function, labels))
    if not candidates:
        return None
    best = max(c[0] for c in candidates)
    _, function, labels = next(c for c in candidates if c[0] == best)
    return function, labels


def open_function(verb: str, words: list[str]) -> str:
    """A function named by the request's own words when no sense fits ("adjust chair")."""
    skip = lx.DETERMINERS | lx.SEEKERS | lx.PREPOSITIONS.keys() | _FUNCTION_WORDS
    content = [lx.singular(w) for w in words if w not in skip and w.isalpha() and len(w) > 2]
    return " ".join([verb, *content[:2]])
