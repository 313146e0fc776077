"""Spelling: typed requests carry typos ("teh chager on my nighstand"). Before analysis,
words that are neither English words nor vocabulary words are corrected to the closest
word, preferring words of the vocabulary, by symspellpy (symmetric-delete lookup over
its bundled English frequency dictionary plus every vocabulary word).

Only clear cases are corrected: one edit (insert, delete, substitute or swap) for words
of five letters or more, a swap of letters for shorter ones ("teh" → "the", "fidn" →
"find"), a dropped letter of a vocabulary word for three-letter ones ("dsk" → "desk"),
and one edit that gives a vocabulary word for four-letter ones ("towl" → "towel"); words with digits, acronyms in capitals ("TV", "PC") and two-letter words stay
as written. The dictionary is loaded on the first word that needs it (about 0.5 s), so
requests without typos never pay for it. Apostrophe-less contractions ("thats", "dont")
are restored from ``lexicon.toml``.
"""

from __future__ import annotations

import re
import threading
from functools import lru_cache
from importlib import resources
from itertools import pairwise

from inherit_sg.vocab import colours as colour_vocab
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab import rooms as room_vocab
from inherit_sg.vocab.functions import function_verbs
from inherit_sg.vocab.lexicon import lexicon

_WORD = re.compile(r"[A-Za-z]+(?:'[A-Za-z]+)?")
# Count given to vocabulary words: above any English word of the bundled dictionary, so
# that among equally close corrections the vocabulary's word wins.
_VOCAB_COUNT = 10**12
_lock = threading.Lock()


@lru_cache(maxsize=1)
def vocabulary_words() -> frozenset[str]:
    """Every single word the vocabulary files know (objects, rooms, lexicon, colours,
    functions)."""
    lx = lexicon()
    phrases: set[str] = set(object_vocab.phrases()) | set(object_vocab.general_words())
    phrases |= set(room_vocab.room_words()) | set(colour_vocab.colour_words())
    phrases |= set(function_verbs())
    for table in (
        lx.materials, lx.adjectives, lx.prepositions, lx.superlatives, lx.ordinals,
        lx.numbers, lx.directions, lx.sides, lx.placements, lx.floor_phrases, lx.viewpoints,
    ):  # fmt: skip
        phrases |= set(table)
    for words in (
        lx.filler, lx.negations, lx.exceptions, lx.determiners, lx.seekers, lx.anaphors,
        lx.area_heads, lx.generic_things, lx.floor_nouns, lx.be_like, lx.have_like,
    ):  # fmt: skip
        phrases |= set(words)
    return frozenset(w for p in phrases for w in p.split() if w.isalpha())


@lru_cache(maxsize=1)
def _object_words() -> frozenset[str]:
    """Single words that name things (object labels and their synonyms)."""
    return frozenset(w for p in object_vocab.phrases() for w in p.split() if w.isalpha())


@lru_cache(maxsize=1)
def _checker() -> object:
    """The loaded symspellpy checker (English dictionary + vocabulary words)."""
    from symspellpy import SymSpell

    with _lock:
        checker = SymSpell(max_dictionary_edit_distance=1, prefix_length=7)
        path = resources.files("symspellpy") / "frequency_dictionary_en_82_765.txt"
        with resources.as_file(path) as dictionary:
            checker.load_dictionary(str(dictionary), term_index=0, count_index=1)
        for word in vocabulary_words():
            checker.create_dictionary_entry(word, _VOCAB_COUNT)
        return checker


def _known(word: str) -> bool:
    checker = _checker()
    return word in vocabulary_words() or word in checker.words  # type: ignore[attr-defined]


def is_known_word(word: str) -> bool:
    """Whether ``word`` (lower case) is an English or a vocabulary word."""
    return word in vocabulary_words() or _known(word)


# A real word this many times rarer than a thing's name one vowel away is read as that
# name misspelt ("calender" → "calendar": 1.3 M against 101 M in the English dictionary).
_RARER = 40
_VOWELS = frozenset("aeiouy")


def _vowel_slip(word: str, name: str) -> bool:
    """Whether ``name`` is ``word`` with the vowel of its unstressed last syllable written
    as another ("calender", "dispensar"): the commonest misspelling of a real word, where
    the vowel is heard as "uh". A vowel further in ("suction" / "section") is a word of its
    own."""
    if len(word) != len(name):
        return False
    diff = [(i, a, b) for i, (a, b) in enumerate(zip(word, name, strict=True)) if a != b]
    if len(diff) != 1:
        return False
    i, a, b = diff[0]
    return a in _VOWELS and b in _VOWELS and len(word) - i <= 3


def _slip_from_end(word: str, name: str) -> int:
    """How far from the word's end a vowel slip ("sofe" → "sofa": 1) lies; the word's
    length when ``name`` is no vowel slip of it."""
    if not _vowel_slip(word, name):
        return len(word)
    return next(len(word) - i for i, (a, b) in enumerate(zip(word, name, strict=True)) if a != b)


def _misspelt_name(word: str) -> str | None:
    """The thing's name that a rare real word of five letters or more misspells by one
    vowel ("calender" → "calendar"), or None."""
    if len(word) < 5:
        return None
    counts = _checker().words  # type: ignore[attr-defined]

    def english(w: str) -> int:  # the dictionary's count, without the vocabulary's boost
        return int(counts.get(w, 0)) % _VOCAB_COUNT

    names = [n for n in _object_words() if _vowel_slip(word, n)]
    best = max(names, key=english, default=None)
    if best is None or english(best) < _RARER * english(word):
        return None
    return best


@lru_cache(maxsize=16384)
def correct_word(word: str) -> str | None:
    """The correction of one lower-case word, or None when it stands as written."""
    if len(word) < 3 or not word.isalpha() or word in vocabulary_words():
        return None
    if _known(word):
        return _misspelt_name(word)
    from symspellpy import Verbosity

    found = _checker().lookup(word, Verbosity.CLOSEST, max_edit_distance=1)  # type: ignore[attr-defined]
    if not found:
        return None
    vocab = vocabulary_words()
    # A dropped letter is the commonest slip: "towl" is a towel before it is a tool; and
    # a thing's name one unstressed vowel away beats a commoner word ("sofe": sofa, not
    # some).
    names = _object_words()
    best = sorted(
        found,
        key=lambda s: (
            _slip_from_end(word, s.term) if s.term in names else len(word),
            s.term not in vocab,
            len(s.term) != len(word) + 1,
            -s.count,
        ),
    )[0]
    swapped = sorted(best.term) == sorted(word)
    # "dsk" → "desk": a dropped letter of a thing's name (three-letter words only)
    dropped = len(best.term) == len(word) + 1 and best.term in _object_words()
    if len(word) < 5 and not swapped and not dropped and (len(word) < 4 or best.term not in vocab):
        return None  # short words: swapped or dropped letters, one edit to a vocabulary word
    return str(best.term)


@lru_cache(maxsize=4)
def _contraction_patterns(table: tuple[tuple[str, str], ...]) -> list[re.Pattern[str]]:
    """One pattern for the forms of two letters or more (any case) and one for the
    one-letter forms (lower case only), each form a whole word not followed by an
    apostrophe; longer forms first, so that "its an" wins over "its a"."""
    patterns = []
    for forms, flags in (
        ([w for w, _ in table if len(w) > 1], re.IGNORECASE),
        ([w for w, _ in table if len(w) == 1], 0),
    ):
        if forms:
            body = "|".join(re.escape(f) for f in sorted(forms, key=len, reverse=True))
            patterns.append(re.compile(rf"\b(?:{body})\b(?!')", flags))
    return patterns


def _contractions(text: str) -> str:
    """Restore apostrophes ("thats" → "that's"); one-letter forms ("u") only in lower
    case, so that "U-shaped" stays."""
    table = lexicon().contractions
    for pattern in _contraction_patterns(tuple(table.items())):
        text = pattern.sub(lambda m: table[m.group(0).lower()], text)
    return text


def correct_spelling(text: str) -> tuple[str, list[tuple[str, str]]]:
    """``text`` with typos corrected, and the (wrong, right) pairs in order."""
    text = _contractions(text)
    fixes: list[tuple[str, str]] = []

    def fix(match: re.Match[str]) -> str:
        word = match.group(0)
        if "'" in word or (word.isupper() and len(word) > 1):
            return word
        right = correct_word(word.lower())
        if right is None:
            return word
        fixes.append((word, right))
        return right.capitalize() if word[0].isupper() else right

    text = _WORD.sub(fix, text)
    text = _names_mended(text, fixes)  # "tv remove" → "tv remote"
    return _CLOSET_TO.sub(lambda m: _closest_typo(m, fixes), text), fixes


@lru_cache(maxsize=1)
def _second_words() -> dict[str, frozenset[str]]:
    """For each first word of a two-word thing's name, its second words ("tv" → remote,
    stand, …)."""
    table: dict[str, set[str]] = {}
    for phrase in object_vocab.phrases():
        words = phrase.split()
        if len(words) == 2:
            table.setdefault(words[0], set()).add(words[1])
    return {first: frozenset(seconds) for first, seconds in table.items()}


@lru_cache(maxsize=1)
def _one_edit() -> object:
    from symspellpy.editdistance import DistanceAlgorithm, EditDistance

    return EditDistance(DistanceAlgorithm.DAMERAU_OSA)


@lru_cache(maxsize=1)
def _verbs_only() -> frozenset[str]:
    """Words the vocabulary knows only as the verbs of functions ("remove", "charge")."""
    lx = lexicon()
    other: set[str] = set(lx.directions) | set(lx.sides) | set(lx.adjectives) | set(lx.filler)
    verbs = {w for v in function_verbs() for w in v.split()}
    return frozenset(verbs - other - _object_words())


# Words before a thing's name ("the tv remove", "my phone charter").
_NAME_OPENERS = frozenset({"the", "my", "a", "an", "your", "our", "his", "her", "their", "this"})


def _names_mended(text: str, fixes: list[tuple[str, str]]) -> str:
    """ "tv remove" → "tv remote", "phone charter" → "phone charger": a real word one edit
    from the second word of a thing's name whose first word comes just before it, where
    the word is no word of the vocabulary and only one such name fits."""
    words = list(re.finditer(r"[A-Za-z]+", text))
    # a word the speller just mended is tried again as written ("ironing bord": "board",
    # not the "bird" the speller chose alone)
    written = {right: wrong.lower() for wrong, right in fixes}
    out, last = [], 0
    for k, (before, match) in enumerate(pairwise(words)):
        first, second = before.group(0).lower(), match.group(0).lower()
        seconds = _second_words().get(first)
        if seconds and second in written and second not in seconds:
            typed = written[second]
            near = [w for w in seconds if _one_edit().compare(typed, w, 1) == 1]  # type: ignore[attr-defined]
            if len(near) == 1:
                fixes[:] = [(w, near[0] if r == second else r) for w, r in fixes]
                out += [text[last : match.start()], near[0]]
                last = match.end()
                continue
        if (
            not seconds
            or len(second) < 4
            or text[before.end() : match.start()] != " "
            or second in seconds
            or second in _object_words()
        ):
            continue
        # a verb the vocabulary knows ("remove") only right after "the" / "my"; other
        # words of the vocabulary stand ("the wall right above the bed")
        named = k > 0 and words[k - 1].group(0).lower() in _NAME_OPENERS
        if second in vocabulary_words() and not (named and second in _verbs_only()):
            continue
        near = [
            w
            for w in sorted(seconds)
            if _one_edit().compare(second, w, 1) == 1  # type: ignore[attr-defined]
            and second != f"{w}s"  # "pc towers": a plural, not a slip
        ]
        if len(near) == 1:
            fixes.append((match.group(0), near[0]))
            out += [text[last : match.start()], near[0]]
            last = match.end()
    return "".join([*out, text[last:]])


# "the monitor closet to the window": "closest" with a dropped letter, after a thing's name
# (not "the coat closet to the left", a closet of its own).
_CLOSET_TO = re.compile(r"\b([A-Za-z]+) (closet) (to|from)\b", re.IGNORECASE)


_CLOSET_KINDS = frozenset(
    {"coat", "linen", "broom", "storage", "hall", "hallway", "utility", "supply", "clothes",
     "shoe", "cleaning", "in", "bedroom", "bathroom", "master", "guest", "towel", "closet"}
)  # fmt: skip


def _closest_typo(match: re.Match[str], fixes: list[tuple[str, str]]) -> str:
    thing = match.group(1).lower()
    if thing in _CLOSET_KINDS or not object_vocab.canonical_label(thing):
        return match.group(0)  # "the closet to the left", "the coat closet to the left"
    fixes.append((match.group(2), "closest"))
    return f"{match.group(1)} closest {match.group(3)}"
