"""Function senses: a verb and its object words → a canonical function and likely kinds.

"wash my hands" → ``wash hands`` (sink); "have a casual conversation" → ``talk``;
"watch something on a large screen" → ``watch tv``. A sense naming object words beats
the verb's default sense; senses without verbs are purpose nouns ("a meal", "a break")
that any verb, or none ("for a meeting"), can carry. The senses are data
(``functions.toml``, :mod:`inherit_sg.vocab.functions`); words are compared by lemma.
"""

from __future__ import annotations

from functools import lru_cache
from itertools import pairwise

from inherit_sg.vocab.functions import senses
from inherit_sg.vocab.lexicon import lexicon

Sense = tuple[str, tuple[str, ...]]
_FUNCTION_WORDS = frozenset({"for", "of", "to", "with", "and", "or", "out", "up", "down", "off"})


@lru_cache(maxsize=1)
def _by_verb() -> dict[str, list[tuple[str, frozenset[str], tuple[str, ...]]]]:
    table: dict[str, list[tuple[str, frozenset[str], tuple[str, ...]]]] = {}
    for sense in senses():
        for verb in (*sense.verbs, *sense.stranded) or ("",):
            table.setdefault(verb, []).append(
                (sense.function, frozenset(sense.objects), sense.kinds)
            )
    return table


def knows_verb(verb: str) -> bool:
    """Whether some sense names ``verb`` (a lemma or "lemma particle") itself."""
    return verb in _by_verb()


def object_terms(words: list[str], lemmas: list[str] | None = None) -> set[str]:
    """Words, their lemmas and adjacent pairs ("fresh air", "get together"); a compound
    word also pairs by its last word ("dirty" + "cereal bowl" → "dirty bowl")."""
    terms = set(words) | set(lemmas or ())
    # "a bottle of wine", "a glass of water": one token for the phrase, and its two nouns
    terms |= {part for term in list(terms) if " of " in term for part in term.split(" of ", 1)}
    for seq in (words, lemmas or []):
        terms |= {f"{a} {b}" for a, b in pairwise(seq)}
        heads = [w.rsplit(" ", 1)[-1] for w in seq]
        terms |= {f"{a} {b}" for a, b in pairwise(heads)}
    return terms


def match_function(
    verb: str | None,
    words: list[str],
    primary: list[str] | None = None,
    lemmas: list[str] | None = None,
) -> Sense | None:
    """The best sense for ``verb`` (a lemma or "lemma particle"; None for a bare purpose
    phrase) with object ``words`` (and their ``lemmas``), or None when nothing fits.

    Scores: verb with a matching object word 3, the verb's default sense 2, a purpose
    noun 1; a match on a ``primary`` word (the object's head) adds 0.5.
    """
    table = _by_verb()
    terms = object_terms(words, lemmas)
    heads = object_terms(primary or [])
    candidates: list[tuple[float, str, tuple[str, ...]]] = []
    if verb:
        for key in dict.fromkeys((verb, verb.split()[0])):
            for function, objects, labels in table.get(key, []):
                if objects & terms:
                    bonus = 0.5 if objects & heads else 0.0
                    candidates.append((3 + bonus, function, labels))
                elif not objects:
                    candidates.append((2, function, labels))
    # purpose nouns: the object's head when there is one ("grab the tv remote" is about
    # the remote, not about watching TV), else any word ("for a meeting")
    purpose_terms = object_terms(primary[-1:]) if primary else terms
    for function, objects, labels in table.get("", []):
        if objects & purpose_terms:
            candidates.append((1.5 if primary else 1.0, function, labels))
    if not candidates:
        return None
    best = max(c[0] for c in candidates)
    _, function, labels = next(c for c in candidates if c[0] == best)
    return function, labels


def has_own_sense(verb: str, words: list[str], lemmas: list[str] | None = None) -> bool:
    """Whether ``verb`` itself, with these object words, names a function ("take a
    shower", "use the toilet"); a purpose noun any verb carries does not count."""
    terms = object_terms(words, lemmas)
    table = _by_verb()
    for key in dict.fromkeys((verb, verb.split()[0])):
        for _, objects, _ in table.get(key, []):
            if objects & terms:
                return True
    return False


def open_function(verb: str, words: list[str]) -> str:
    """A function named by the request's own words when no sense fits ("adjust chair")."""
    lx = lexicon()
    skip = lx.determiners | lx.seekers | lx.prepositions.keys() | _FUNCTION_WORDS
    content = [w for w in words if w not in skip and w.isalpha() and len(w) > 2]
    return " ".join([verb, *content[:2]])
