"""Lexical tagging: words → tokens carrying every reading the lexicon knows.

Multi-word entries ("coffee table", "next to", "could you please") are merged by longest
match; a plural last word matches its singular entry. A token keeps all its readings
(``"glass"`` is both a material and a noun, ``"that"`` a determiner, a relative pronoun
and an anaphor) and the grammar picks one from context.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from inherit_sg.retrieval import lexicon as lx

# Closed-class words without lexicon tables of their own.
_SIMPLE: dict[str, str] = {
    "with": "with",
    "without": "without",
    "and": "and",
    "or": "or",
    "but": "but",
    "nor": "or",
    "to": "to",
    "for": "for",
    "of": "of",
    "from": "from",
    "while": "while",
    "whilst": "while",
    "during": "while",
    "than": "than",
    ",": "comma",
    "left": "dir",
    "right": "dir",
}
_ONE_WORDS = {"one": False, "ones": True}


@dataclass
class Tok:
    """One token: its surface words and its readings (tag → value)."""

    text: str
    tags: dict[str, Any] = field(default_factory=dict)
    plural: bool = False

    def has(self, *tags: str) -> bool:
        """True when the token has any of ``tags``."""
        return any(t in self.tags for t in tags)

    def __repr__(self) -> str:
        return f"{self.text}/{'|'.join(self.tags)}"


def _put(table: dict[tuple[str, ...], dict[str, Any]], phrase: str, tag: str, value: Any) -> None:
    table.setdefault(tuple(phrase.split()), {}).setdefault(tag, value)


@lru_cache(maxsize=1)
def phrase_table() -> tuple[dict[tuple[str, ...], dict[str, Any]], int, frozenset[str]]:
    """(phrase → readings, longest phrase length, function verb set), built once."""
    t: dict[tuple[str, ...], dict[str, Any]] = {}
    for word, labels in lx.SHARED_NOUNS.items():
        t.setdefault(tuple(word.split()), {})["noun"] = labels
    for canon, synonyms in lx.OBJECTS.items():
        for phrase in (canon, *synonyms):
            _put(t, phrase, "noun", (canon,))
    for canon, synonyms in lx.ROOMS.items():
        for phrase in (canon, *synonyms):
            _put(t, phrase, "room", canon)
    simple_sets = (
        (lx.AREA_HEADS, "area_head"),
        (lx.VAGUE_PLACES, "vague"),
        (lx.GENERIC_THINGS, "generic"),
        (lx.ROOM_WORDS, "room_word"),
        (lx.FLOOR_NOUNS, "floor_noun"),
        (lx.NEGATIONS, "neg"),
        (lx.EXCEPTIONS, "except"),
        (lx.EMPHASIS, "emph"),
        (lx.HEDGES, "hedge"),
        (lx.DETERMINERS, "det"),
        (lx.SEEKERS, "seeker"),
        (lx.MODALS, "modal"),
        (lx.BE_WORDS, "be"),
        (lx.HAVE_WORDS, "have"),
        (lx.REL_PRONOUNS, "rel"),
        (lx.ANAPHORS, "anaphor"),
        (lx.OTHER_WORDS, "other"),
        (lx.QUESTION_WORDS, "wh"),
        (lx.AWAY_PREPOSITIONS, "away"),
        (lx.OUTSIDE_PREPOSITIONS, "away"),
        (lx.ADVERBS, "adv"),
        (lx.SUBORDINATORS, "sub"),
        (lx.EXAMPLE_WORDS, "like"),
        (lx.FILLER, "filler"),
    )
    for words, tag in simple_sets:
        for phrase in words:
            _put(t, phrase, tag, phrase)
    valued: tuple[tuple[dict[str, Any], str], ...] = (
        (lx.COLOURS, "colour"),
        (lx.MATERIALS, "material"),
        (lx.ADJECTIVES, "adj"),
        (lx.PREPOSITIONS, "prep"),
        (lx.SUPERLATIVES, "super"),
        (lx.ORDINALS, "ord"),
        (lx.NUMBERS, "num"),
        (lx.FLOOR_PHRASES, "floor"),
    )
    for tables, tag in valued:
        for phrase, value in tables.items():
            _put(t, phrase, tag, value)
    for word, n in lx.ORDINALS.items():
        for noun in lx.FLOOR_NOUNS:
            _put(t, f"{word} {noun}", "floor", n - 1 if n > 0 else "top")
    for word, tag in _SIMPLE.items():
        _put(t, word, tag, word)
    for word in lx.COLOUR_SHADES:
        _put(t, word, "shade", word)
    verbs: set[str] = set()
    for _, verb_list, _, _ in lx.FUNCTIONS:
        for verb in verb_list:
            verbs.add(verb)
            _put(t, verb, "fverb", verb)
    longest = max(len(k) for k in t)
    return t, longest, frozenset(verbs)


def _lookup(words: list[str], i: int) -> tuple[int, dict[str, Any], bool]:
    table, longest, verbs = phrase_table()
    for n in range(min(longest, len(words) - i), 0, -1):
        key = tuple(words[i : i + n])
        hit = table.get(key)
        plural = False
        if hit is None:
            last = lx.singular(key[-1])
            if last != key[-1]:
                hit = table.get((*key[:-1], last))
                plural = hit is not None
        if hit is None and n >= 2:
            # inflected multi-word verb: "hanging out", "throwing away"
            lemma = lx.verb_lemma(key[0], verbs)
            phrase = " ".join((lemma, *key[1:]))
            if lemma != key[0] and phrase in verbs:
                hit = {"fverb": phrase}
        if hit is not None:
            return n, hit, plural
    return 0, {}, False


def _single(word: str) -> Tok:
    """Readings of a word with no lexicon entry (inflections, numbers, open vocabulary)."""
    _, _, verbs = phrase_table()
    tok = Tok(word)
    if word in _ONE_WORDS:
        tok.tags["one"] = True
        tok.plural = _ONE_WORDS[word]
        return tok
    if word.isdigit():
        tok.tags["num"] = int(word)
        return tok
    if word[:-2].isdigit() and word[-2:] in ("st", "nd", "rd", "th"):
        tok.tags["ord"] = int(word[:-2])
        return tok
    lemma = lx.verb_lemma(word, verbs)
    if lemma in verbs and lemma != word:
        tok.tags["fverb"] = lemma
    else:
        other = lx.verb_lemma(word, lx.OTHER_VERBS)
        if other in lx.OTHER_VERBS:
            tok.tags["overb"] = other
    if word.endswith("ly") and len(word) > 4:
        tok.tags["adv"] = word
    elif "fverb" not in tok.tags and "overb" not in tok.tags:
        noun = lx.singular(word)
        tok.tags["unk"] = noun
        tok.plural = noun != word
    return tok


def tag(words: list[str]) -> list[Tok]:
    """Tokens for ``words`` (output of :func:`tokenize`), longest phrases first."""
    out: list[Tok] = []
    i = 0
    while i < len(words):
        n, readings, plural = _lookup(words, i)
        if n:
            tok = Tok(" ".join(words[i : i + n]), dict(readings), plural)
            if n == 1 and words[i] in _ONE_WORDS:
                tok.tags["one"] = True
                tok.plural = _ONE_WORDS[words[i]]
            if n == 1 and "overb" not in tok.tags and words[i] in lx.OTHER_VERBS:
                tok.tags["overb"] = words[i]
            out.append(tok)
            i += n
        else:
            out.append(_single(words[i]))
            i += 1
    return out


def _entry(phrase: str) -> dict[str, Any]:
    table, _, _ = phrase_table()
    words = phrase.lower().replace("_", " ").replace("-", " ").split()
    if not words:
        return {}
    hit = table.get(tuple(words))
    if hit is None:
        hit = table.get((*words[:-1], lx.singular(words[-1])))
    return hit or {}


def canonical_noun(phrase: str) -> tuple[str, ...]:
    """Canonical labels of a noun phrase ("couches" → ``("sofa",)``); an unknown noun
    gives its singular form ("security scanners" → ``("security scanner",)``)."""
    hit = _entry(phrase)
    if "noun" in hit:
        return tuple(hit["noun"])
    words = phrase.lower().split()
    return (" ".join([*words[:-1], lx.singular(words[-1])]),) if words else ()


def room_type(phrase: str) -> str | None:
    """Canonical room type of a room phrase ("restroom" → "bathroom"), or None."""
    value = _entry(phrase).get("room")
    if value is None and len(phrase.split()) > 1:
        value = _entry(phrase.split()[-1]).get("room")
    return str(value) if value is not None else None
