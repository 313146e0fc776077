"""Lexical tagging: analysed words → tokens carrying every reading the vocabulary knows.

spaCy supplies the word classes and lemmas (:mod:`.tokens`); the vocabulary files supply
domain meaning. Multi-word entries ("coffee table", "next to", "in the corner", "as you
come through") are merged by longest match; a phrase matches with its last word's lemma
when that word is a plural noun ("arm chairs" → "arm chair") and with its first word's
lemma when it is a verb ("hanging out" → "hang out"). A token keeps all its readings
(``"glass"`` is both a material and a noun, ``"that"`` a determiner, a relative pronoun
and an anaphor) and the grammar picks one from context. A word no vocabulary knows is
read by its part of speech: a noun is an open-vocabulary object word (its lemma is the
label), an adjective an attribute kept as written, a verb a verb by its lemma.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from inherit_sg.nlp import known_lemma
from inherit_sg.retrieval.rules.spelling import is_known_word
from inherit_sg.retrieval.rules.tokens import Word
from inherit_sg.vocab import colours as colour_vocab
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab import rooms as room_vocab
from inherit_sg.vocab.functions import function_verbs
from inherit_sg.vocab.lexicon import lexicon

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
}
_ONE_WORDS = {"one": False, "ones": True}
_QUESTION_WORDS = frozenset({"where", "what", "which", "how", "why", "when", "who", "whom"})
_RELATIVE_TAGS = frozenset({"WDT", "WP", "WP$"})
_RELATIVE_WORDS = frozenset({"that", "which", "who", "whose"})
_NUMERAL_SUFFIXES = ("st", "nd", "rd", "th")


@dataclass
class Tok:
    """One token: its surface words, readings (tag → value) and spaCy's analysis of
    its last word."""

    text: str
    tags: dict[str, Any] = field(default_factory=dict)
    plural: bool = False
    pos: str = ""
    lemma: str = ""
    tag: str = ""

    def has(self, *tags: str) -> bool:
        """True when the token has any of ``tags``."""
        return not self.tags.keys().isdisjoint(tags)

    def __repr__(self) -> str:
        return f"{self.text}/{'|'.join(self.tags)}"


def _put(table: dict[tuple[str, ...], dict[str, Any]], phrase: str, tag: str, value: Any) -> None:
    table.setdefault(tuple(phrase.split()), {}).setdefault(tag, value)


@lru_cache(maxsize=1)
def phrase_table() -> tuple[dict[tuple[str, ...], dict[str, Any]], int, frozenset[str]]:
    """(phrase → readings, longest phrase length, function verb set), built once."""
    lx = lexicon()
    t: dict[tuple[str, ...], dict[str, Any]] = {}
    for phrase, label in object_vocab.phrases().items():
        _put(t, phrase, "noun", (label,))
    for phrase in object_vocab.general_words():
        labels = object_vocab.labels_for(phrase)
        if labels:
            t.setdefault(tuple(phrase.split()), {})["noun"] = labels
    for phrase, rtype in room_vocab.room_words().items():
        _put(t, phrase, "room", rtype)
    simple_sets = (
        (lx.area_heads, "area_head"),
        (lx.vague_places, "vague"),
        (lx.generic_things, "generic"),
        (lx.room_words, "room_word"),
        (lx.floor_nouns, "floor_noun"),
        (lx.negations, "neg"),
        (lx.exceptions, "except"),
        (lx.emphasis, "emph"),
        (lx.hedges, "hedge"),
        (lx.determiners, "det"),
        (lx.seekers, "seeker"),
        (lx.be_like, "be"),
        (lx.have_like, "have"),
        (lx.anaphors, "anaphor"),
        (lx.other_words, "other"),
        (lx.away_prepositions, "away"),
        (lx.outside_prepositions, "away"),
        (lx.adverbs, "adv"),
        (lx.subordinators, "sub"),
        (lx.example_words, "like"),
        (lx.filler, "filler"),
        (lx.middle, "middle"),
        (lx.abstract_nouns, "abstract"),
    )
    for words, tag_name in simple_sets:
        for phrase in words:
            _put(t, phrase, tag_name, phrase)
    valued: tuple[tuple[dict[str, Any], str], ...] = (
        (colour_vocab.colour_words(), "colour"),
        (lx.materials, "material"),
        (lx.adjectives, "adj"),
        (lx.prepositions, "prep"),
        (lx.superlatives, "super"),
        (lx.ordinals, "ord"),
        (lx.numbers, "num"),
        (lx.floor_phrases, "floor"),
        (lx.directions, "dir"),
        (lx.sides, "side"),
        (lx.placements, "placement"),
        (lx.viewpoints, "view"),
    )
    for tables, tag_name in valued:
        for phrase, value in tables.items():
            _put(t, phrase, tag_name, value)
    for word, n in lx.ordinals.items():
        for noun in lx.floor_nouns:
            _put(t, f"{word} {noun}", "floor", n - 1 if n > 0 else "top")
    for word, tag_name in _SIMPLE.items():
        _put(t, word, tag_name, word)
    for word in colour_vocab.shade_words():
        _put(t, word, "shade", word)
    verbs = function_verbs()
    for verb in verbs:
        _put(t, verb, "fverb", verb)
    longest = max(len(k) for k in t)
    return t, longest, verbs


@lru_cache(maxsize=1)
def _longest_from() -> dict[str, int]:
    """First word of a phrase → the most words a phrase opened by it has, so that a
    lookup tries only the lengths some phrase could fill."""
    table, _, verbs = phrase_table()
    out: dict[str, int] = {}
    for key in (*table, *(tuple(v.split()) for v in verbs)):
        if key and len(key) > out.get(key[0], 1):
            out[key[0]] = len(key)
    return out


def _lookup(words: list[Word], i: int) -> tuple[int, dict[str, Any], bool]:
    table, longest, verbs = phrase_table()
    first = words[i]
    from_first = _longest_from()
    reach = from_first.get(first.text, 1)
    if first.pos in ("VERB", "AUX"):
        reach = max(reach, from_first.get(first.lemma, 1))
    for n in range(min(longest, reach, len(words) - i), 0, -1):
        span = words[i : i + n]
        if any(w.text == "," for w in span[1:]):
            continue
        if (
            n > 1
            and span[-1].tag == "TO"
            and i + n < len(words)
            and words[i + n].tag == "VB"
            and not _compound_noun_at(table, words, i + n)
        ):
            continue  # "go to charge my phone": "to" opens a purpose, it is no "go to"
        key = tuple(w.text for w in span)
        hit = table.get(key)
        if hit is not None and n > 1 and _posture_of_thing(hit, span, words, i):
            continue  # "the lamp standing next to the sofa": "standing" + "next to"
        plural = False
        last = span[-1]
        if hit is None and (last.plural or last.tag == "VBZ"):
            for stem in _singulars(last):
                hit = table.get((*key[:-1], stem))
                if hit is not None and (_FUNCTION_WORDS.isdisjoint(hit) or last.text == stem + "s"):
                    plural = "noun" in hit
                    break
                hit = None  # "notes" is no plural of "not" ("nothings" is "nothing's")
        if hit is None and span[0].pos in ("VERB", "AUX") and span[0].lemma != key[0]:
            phrase = " ".join((span[0].lemma, *key[1:]))
            if phrase in verbs:
                hit = {"fverb": phrase}
        if hit is not None:
            return n, hit, plural or (last.plural and "noun" in hit)
    return 0, {}, False


def _compound_noun_at(
    table: dict[tuple[str, ...], dict[str, Any]], words: list[Word], j: int
) -> bool:
    """Whether a noun of two or three words opens at word ``j`` ("next to trash can":
    spaCy's verb "trash" opens a thing, not a purpose)."""
    for n in (3, 2):
        key = tuple(w.text for w in words[j : j + n])
        if len(key) == n and "noun" in table.get(key, {}):
            return True
    return False


# Words before a posture participle that make the participle the thing's, not the
# speaker's: "the lamp standing in the corner", "the chair that is sitting by the door".
_THING_POSTURE = frozenset({"is", "'s", "was", "that", "which", "who", "it", "one"})


def _posture_of_thing(hit: dict[str, Any], span: list[Word], words: list[Word], i: int) -> bool:
    """Whether a viewpoint phrase opened by a participle ("standing next to", "sitting
    in") follows a noun or says where a thing stands, so it is no viewpoint."""
    if set(hit) != {"view"} or span[0].tag != "VBG" or i == 0:
        return False
    prev = words[i - 1]
    return prev.pos in ("NOUN", "PROPN") or prev.text in _THING_POSTURE


def _singulars(word: Word) -> list[str]:
    """Singular forms to look a plural noun up by: spaCy's lemma, then the word less its
    plural ending where the vocabulary knows that form ("ottomans": spaCy's lemmatiser
    says "othman")."""
    out = [word.lemma] if word.lemma != word.text else []
    text = word.text
    if text.endswith("s") and len(text) > 3:
        out.append(text[:-1])  # "ottomans" → "ottoman"
        if text.endswith("es") and len(text) > 4:
            out.append(text[:-2])  # "benches" → "bench"
    return out


def _number(word: Word) -> int | None:
    text = word.text
    if text.isdigit():
        return int(text)
    return None


def _grammar(tok: Tok, word: Word, first: bool) -> None:
    """Readings that come from spaCy's tags rather than from the vocabulary."""
    lx = lexicon()
    text = word.text
    if word.lemma == "be" and word.pos in ("AUX", "VERB"):
        tok.tags.setdefault("be", text)
    if word.tag == "MD" or (word.lemma == "do" and word.pos == "AUX"):
        tok.tags.setdefault("modal", text)
    if text in _QUESTION_WORDS and (word.tag.startswith("W") or first):
        tok.tags.setdefault("wh", text)
    opens_question = first and text in _QUESTION_WORDS  # "which room is the piano in"
    if (
        text in _RELATIVE_WORDS
        and (word.tag in _RELATIVE_TAGS or text == "that")
        and not opens_question
    ):
        tok.tags.setdefault("rel", text)
    if word.pos == "DET" and text not in lx.anaphors and "det" not in tok.tags:
        tok.tags["det"] = text
    if word.dep == "poss" and word.pos in ("NOUN", "PROPN") and text not in lx.anaphors:
        # a possessor acts as a determiner: "jake's desk", "the dog's leash"
        tok.tags = {"det": text}
    if word.lemma in lx.other_verbs and word.pos in ("VERB", "AUX"):
        tok.tags.setdefault("overb", word.lemma)


def _single(word: Word, first: bool) -> Tok:
    """Readings of a word with no vocabulary entry (open vocabulary, by part of speech)."""
    _, _, verbs = phrase_table()
    tok = Tok(word.text, pos=word.pos, lemma=word.lemma, tag=word.tag)
    text = word.text
    if text in _ONE_WORDS:
        tok.tags["one"] = True
        tok.plural = _ONE_WORDS[text]
        return tok
    number = _number(word)
    if number is not None:
        tok.tags["num"] = number
        return tok
    if text[:-2].isdigit() and text[-2:] in _NUMERAL_SUFFIXES:
        tok.tags["ord"] = int(text[:-2])
        return tok
    _grammar(tok, word, first)
    if tok.has("be", "modal", "wh", "rel", "det"):
        return tok
    if word.pos == "VERB" and word.tag in ("VBN", "VBD") and word.dep == "amod":
        tok.tags["adj"] = ("state", text)  # "the cracked one", "a folded towel"
        return tok
    if word.pos in ("VERB", "AUX") and not is_known_word(text):
        tok.tags["unk"] = text  # no English verb: a name spaCy guessed ("roundmetaltable")
    elif word.pos in ("VERB", "AUX"):
        if word.lemma in verbs:
            tok.tags["fverb"] = word.lemma
        else:
            tok.tags.setdefault("overb", word.lemma)
            if word.tag == "VB" and first:
                tok.tags["seek"] = word.lemma  # an imperative: "select", "identify"
    elif word.pos in ("NOUN", "PROPN"):
        tok.tags["unk"] = word.lemma if word.plural else text
        tok.plural = word.plural
    elif word.pos == "ADJ" and _part_word(word):
        tok.tags["unk"] = text  # "with the backrest": spaCy reads the "-est" as a superlative
    elif word.pos == "ADJ":
        tok.tags["adj"] = ("other", word.lemma if word.tag == "JJ" else text)
    elif word.pos == "ADV":
        tok.tags["adv"] = text
    elif word.pos == "NUM":
        tok.tags["num"] = 1
    elif word.pos == "X" and text.isalpha():
        tok.tags["unk"] = text  # a word spaCy does not know as anything else
    return tok


def _part_word(word: Word) -> bool:
    """Whether spaCy's adjective is a part noun of the vocabulary in a noun's place
    ("a chair with a backrest")."""
    return word.dep in ("pobj", "dobj", "nsubj", "attr", "conj") and object_vocab.is_part(
        word.text, None
    )


# Readings after which a word needs no open-vocabulary reading of its own.
_CLOSED = ("noun", "room", "unk", "det", "num", "ord", "prep", "be", "modal", "neg", "anaphor",
           "seeker", "generic", "vague", "area_head", "room_word", "floor_noun", "floor",
           "colour", "material", "adj", "fverb", "one", "side", "middle", "super", "placement",
           "dir", "ord", "abstract")  # fmt: skip


def _open_readings(tok: Tok, word: Word) -> None:
    """A word the vocabulary knows only in another role ("face" as a viewpoint cue, "back"
    as a direction) keeps its reading as a noun or verb where spaCy reads it so ("wash my
    face", "the back of the chair")."""
    if word.pos == "VERB" and word.tag != "VB" and not tok.has("fverb", "prep", "be", "modal"):
        tok.tags.setdefault("overb", word.lemma)  # "Grandpa left his hearing aid"
    if tok.has(*_CLOSED) or word.text in _SIMPLE:
        return
    if word.pos in ("NOUN", "PROPN"):
        tok.tags["unk"] = word.lemma if word.plural else word.text
        tok.plural = word.plural
    elif word.pos == "VERB":
        tok.tags.setdefault("overb", word.lemma)


_PARTICLES = ("on", "off", "up", "down", "out")
# Verbs that take a particle before their object: "switch on the lamp", "light up the hall".
_PARTICLE_VERBS = frozenset(
    {"turn", "switch", "shut", "power", "flip", "flick", "light", "plug", "pick", "put",
     "wipe", "clean", "hang", "take", "set", "lock", "open", "close", "dim", "hand"}
)  # fmt: skip


def _verb_with_particle(words: list[Word], i: int) -> bool:
    """Whether the sentence-opening word ``i``, a verb by spaCy, takes a particle before
    its object ("Switch on the lamp", "Turn off the TV"): a particle, then a determiner."""
    if i + 2 >= len(words) or words[i].pos != "VERB":
        return False  # "lamp on the desk" names a lamp: only spaCy's verbs
    particle, after = words[i + 1], words[i + 2]
    if not _known_verb(words[i].lemma):
        return False  # "Mirror on the back of the door", "towel on the rack"
    return particle.text in _PARTICLES and after.pos == "DET"


def _verb_with_object(words: list[Word], i: int) -> bool:
    """Whether the sentence-opening word ``i``, which spaCy reads as the root verb with
    the object that follows ("vacuum the rug", "switch the telly off"), is a command,
    though the vocabulary knows the word as a thing too (a vacuum, a switch)."""
    word = words[i]
    if word.pos != "VERB" or word.tag != "VB" or word.dep != "ROOT" or i + 2 >= len(words):
        return False
    if words[i + 1].pos != "DET":
        return False
    return any(w.dep == "dobj" for w in words[i + 2 : i + 5])


def _mistagged_command(words: list[Word], i: int) -> bool:
    """Whether the request-opening word ``i``, which spaCy took for a noun, a name or an
    adverb ("Fluff the cushions", "Hoover the rug", "Dust the chandelier"), is a command:
    an English verb (by spaCy's lemma lists) in the singular, right before a determiner
    and a noun other than "one" ("chair the one by the window" names a chair)."""
    word = words[i]
    if word.pos not in ("NOUN", "PROPN", "ADV") or word.tag in ("NNS", "NNPS"):
        return False
    if i + 2 >= len(words) or words[i + 1].text not in _OBJECT_DETERMINERS:
        return False
    if words[i + 1].text in ("that", "this") or word.text in colour_vocab.colour_words():
        return False  # "chair that has a backpack", "brown the cabinet under the sink"
    if not known_lemma(word.text.lower(), "verb"):
        return False
    for after in words[i + 2 : i + 6]:
        if after.pos == "ADP" or after.text in ("one", "ones", ","):
            return False
        if after.pos in ("NOUN", "PROPN") and after.dep != "compound":
            return after.dep in ("dobj", "appos", "npadvmod", "nsubj")  # its object
    return False


def _verb_for_me(words: list[Word], i: int) -> bool:
    """Whether the clause-opening word ``i``, a verb by spaCy, gives something to the
    speaker ("throw me the ball", "pass us the salt"), though the vocabulary knows it
    as a thing (a throw)."""
    return (
        i + 2 < len(words)
        and words[i].pos == "VERB"
        and words[i].tag == "VB"
        and words[i + 1].text in ("me", "us")
        and words[i + 2].pos in ("DET", "PRON", "NOUN", "ADJ", "NUM")
    )


def _verb_before_place(words: list[Word], i: int) -> bool:
    """Whether the sentence-opening word ``i`` (or one after "go" / "come"), a verb by
    spaCy, is followed by a place ("Stand next to the bookshelf", "go sit by the window"):
    a command, though the vocabulary knows the word as a thing (a stand, a seat)."""
    if i + 1 >= len(words) or words[i].pos != "VERB" or words[i].tag != "VB":
        return False
    if not _known_verb(words[i].lemma):
        return False  # "Stove next to the dishwasher": spaCy's guess, a thing named
    if _names_thing_not_place_verb(words[i]) and words[i + 1].text != "to":
        return False  # "microwave on top of the counter" (but "switch to the larger box")
    return words[i + 1].pos in ("ADP", "ADV") and words[i + 1].text not in ("of", "'s")


def _names_thing_not_place_verb(word: Word) -> bool:
    """Whether a word is a thing's name whose verb (a need's verb, "to microwave", "to
    iron") is no verb of standing, moving or looking, so it is no command before a place."""
    return not _place_verb(word.lemma) and object_vocab.canonical_label(word.text) is not None


def _place_verb(lemma: str) -> bool:
    """Whether the vocabulary knows ``lemma`` as a verb of moving, standing, placing or
    looking, or as one of the other verbs."""
    lx = lexicon()
    return (
        lemma in lx.viewpoint_verbs
        or lemma in lx.locative_verbs
        or lemma in lx.other_verbs
        or lemma in lx.facing_verbs
    )


def _known_verb(lemma: str) -> bool:
    """Whether the vocabulary knows ``lemma`` as a verb of some kind (a verb of moving,
    looking, placing, a function verb or one of the other verbs), so that a word spaCy
    tags as a verb at the start of a request is read as one ("Turn on the lamp"; not
    "Mirror on the back of the door")."""
    return _place_verb(lemma) or lemma in _PARTICLE_VERBS or lemma in phrase_table()[2]


def _inside_compound(words: list[Word], i: int) -> bool:
    """Whether word ``i`` (a colour word) is a noun inside a compound noun, after another
    compound noun ("ice cream scoop", "the ice cream"), so no colour."""
    if i == 0 or words[i].pos != "NOUN":
        return False
    before = words[i - 1]
    return before.pos == "NOUN" and before.dep == "compound"


def _named_after_determiner(words: list[Word], i: int) -> bool:
    """Whether ``words[i]`` right after a determiner is a noun, or a gerund before one
    ("a hanging basket")."""
    if not i or words[i - 1].pos != "DET":
        return False
    if words[i].pos == "NOUN":
        return True
    return words[i].tag == "VBG" and i + 1 < len(words) and words[i + 1].pos == "NOUN"


def _verb_of_person(words: list[Word], i: int, tenses: tuple[str, ...]) -> bool:
    """Whether word ``i`` is, by spaCy, a verb in one of ``tenses`` right after a
    personal pronoun ("I left my badge", "you saw a drill", "did you notice a bag"),
    though the vocabulary knows it as a side or a thing."""
    return i > 0 and words[i].pos == "VERB" and words[i].tag in tenses and words[i - 1].tag == "PRP"


# Words that may follow "first" when it orders the steps of a request ("go to the kitchen
# first and then …", "find the copier first.").
_AFTER_STEP = frozenset({",", "and", "then", "so", "before", "please"})


def _first_in_time(words: list[Word], i: int) -> bool:
    """Whether "first" (or "last"), by spaCy an adverb after the object of a verb, says
    when a step is done ("find the copier first", "go to the kitchen first and then …"),
    not which thing of a row ("the chair first from the left")."""
    word = words[i]
    if word.text not in ("first", "last") or word.pos != "ADV" or i < 2:
        return False
    if i + 1 < len(words) and words[i + 1].text not in _AFTER_STEP:
        return False
    return words[i - 1].dep in ("dobj", "pobj") and any(w.pos == "VERB" for w in words[:i])


# Readings of function words, which have no plural ("notes" is not "not" + s).
_FUNCTION_WORDS = frozenset({"neg", "det", "prep", "be", "modal", "anaphor", "except", "sub",
                             "and", "or", "num", "ord"})  # fmt: skip
# Readings of a word the vocabulary knows only as a verb of a need.
_VERBISH = frozenset({"fverb", "overb", "seek", "unk"})


def _adjective_after_be(words: list[Word], i: int) -> bool:
    """Whether spaCy reads word ``i`` as an adjective right after "is" / "are"."""
    return i > 0 and words[i].pos == "ADJ" and words[i - 1].lemma == "be"


def _as_description(tok: Tok, word: Word) -> None:
    """Drop the verb readings of ``tok``; with nothing else known of it, it is an
    adjective of its own (spaCy's adjective) or an open-vocabulary noun."""
    for key in ("fverb", "overb", "seek"):
        tok.tags.pop(key, None)
    if set(tok.tags) <= {"unk"}:
        tok.tags = {"adj": ("other", word.text)} if word.pos == "ADJ" else {"unk": word.text}


def _modifies_noun(words: list[Word], i: int) -> bool:
    """Whether spaCy reads word ``i`` as a modifier inside a noun phrase (a compound or
    an adjective) with the noun it modifies after it."""
    word = words[i]
    if word.dep not in ("compound", "amod") or word.pos not in ("NOUN", "PROPN", "ADJ"):
        return False
    return i + 1 < len(words) and words[i + 1].pos in ("NOUN", "PROPN", "ADJ")


# Participles that say where a thing is, or that it went, rather than how it looks.
_PLACING_PARTICIPLES = frozenset(
    {"keep", "locate", "find", "store", "put", "place", "leave", "move", "go", "see",
     "mount", "hang", "situate", "position", "set", "bring", "take", "use"}
)  # fmt: skip


def _comparative_of(words: list[Word], i: int) -> bool:
    """Whether word ``i`` compares the things "of" names ("the darker of the two rugs"):
    a comparative (by spaCy, or an "-er" word spaCy took for a noun) right after "the",
    with "of" after it."""
    if i == 0 or words[i - 1].text != "the" or i + 1 >= len(words) or words[i + 1].text != "of":
        return False
    word = words[i]
    if known_lemma(word.text, "noun"):
        return False  # "the owner of the house", "the cooler of the two"
    return word.tag == "JJR" or (word.text.endswith("er") and known_lemma(word.text[:-2], "adj"))


def _read_in_context(tok: Tok, words: list[Word], i: int, verb: bool) -> None:
    """Readings of one word that the words around it decide: a participle that ends a
    clause after "be" says a state ("the radiator that isn't painted"; ``verb``: the
    word was read as a verb), and a comparative after "the" can name a thing ("where did
    I leave the lighter")."""
    ends = i + 1 >= len(words) or words[i + 1].text in (",", "and", "or", "but")
    if verb and ends and _state_after_be(words, i):
        tok.tags = {"adj": ("state", words[i].text)}
    if _comparative_as_noun(words, i):
        tok.tags = {"unk": words[i].text}
        tok.pos, tok.tag = "NOUN", "NN"


def _state_after_be(words: list[Word], i: int) -> bool:
    """Whether word ``i`` is a participle that says a state after "be" ("the radiator
    that is not painted", "the one that hasn't been cleaned") or after a noun and "not"
    ("tv not mounted"), not a verb of its own."""
    if words[i].tag not in ("VBN", "VBD") or i == 0:
        return False
    negated = words[i - 1].text == "not"
    if words[i].tag == "VBD" and not (negated and i > 1 and words[i - 2].pos in ("NOUN", "PROPN")):
        return False  # a past tense: "not" before one says a participle ("tv not mounted")
    if words[i].lemma in _PLACING_PARTICIPLES and not negated:
        return False  # "where is the kit kept", "has it been moved": where, not a look
    j = i - 1
    while j > 0 and (words[j].text == "not" or words[j].pos == "ADV"):
        j -= 1
    # "the tv that is not mounted", and in notes "tv not mounted"
    return words[j].lemma == "be" or (negated and words[j].pos in ("NOUN", "PROPN"))


def _comparative_as_noun(words: list[Word], i: int) -> bool:
    """Whether word ``i``, by spaCy a comparative adjective, is a thing's name: right
    after a determiner, with no noun, "of" or "one" after it, and a noun the vocabulary
    knows ("the lighter", "the cooler"; not "the larger of the two")."""
    word = words[i]
    if word.tag != "JJR" or i == 0 or words[i - 1].pos != "DET":
        return False
    after = words[i + 1] if i + 1 < len(words) else None
    if after is not None and after.pos in ("VERB", "AUX"):
        return False  # "where did the cleaner put the dustpan": who did it
    if after is not None and (
        after.pos in ("NOUN", "PROPN", "ADJ") or after.text in ("of", "one", "ones", "than")
    ):
        return False
    return known_lemma(word.text, "noun")


def _verb_after_to(words: list[Word], i: int) -> bool:
    """Whether word ``i`` is, by spaCy, a verb after "to" ("something to open a bottle
    with", "to clean the oven"), though the vocabulary knows it as an adjective."""
    return i > 0 and words[i - 1].tag == "TO" and words[i].tag == "VB" and words[i].pos == "VERB"


def _verb_of_subject(words: list[Word], i: int) -> bool:
    """Whether word ``i`` is, by spaCy, the finite verb of the noun just before it ("the
    plant blocks the view", "the lamp lights up the desk", "the cable runs along the
    wall"), though the vocabulary knows it as a thing or a function verb."""
    if i == 0 or words[i].pos != "VERB" or words[i].tag not in ("VBZ", "VBP"):
        return False
    subject = words[i - 1]
    if words[i].tag == "VBP" and subject.tag == "NN":
        # "the dumbbell rack along the wall", "the living-room pillow farthest from the
        # window": a singular noun has no plural verb
        return False
    if words[i].dep in ("ROOT", "conj", "relcl") and subject.dep == "nsubj":
        return True
    # "the shoes by the door are black and sit on a mat": a second verb of a thing's
    # sentence (the latest subject before it is a noun, not "I" or "you")
    subjects = [w for w in words[:i] if w.dep == "nsubj"]
    return words[i].dep == "conj" and bool(subjects) and subjects[-1].pos in ("NOUN", "PROPN")


def _participle_clause(words: list[Word], i: int) -> bool:
    """Whether word ``i`` opens a participle clause after a noun ("sitting on the couch
    watching telly", "the couch facing the tv"), by spaCy's parse, rather than a word of
    a compound name ("the tv viewing area")."""
    word = words[i]
    after_noun = i > 0 and words[i - 1].pos in ("NOUN", "PROPN")
    return word.tag == "VBG" and word.dep in ("acl", "advcl") and after_noun


def tag(words: list[Word]) -> list[Tok]:
    """Tokens for one sentence's ``words`` (output of :func:`.tokens.analyse_text`),
    longest phrases first."""
    out: list[Tok] = []
    i = 0
    while i < len(words):
        n, readings, plural = _lookup(words, i)
        first = i == 0 or words[i - 1].text in (",", "please", "and", "then", "now", "just")
        # "can you turn off the fan": the verb of a request put as a question
        first = first or (i > 1 and words[i - 1].text == "you" and words[i - 2].tag == "MD")
        # "go stand by the door", "come sit here": the second verb is the command
        serial = i > 0 and words[i - 1].lemma in ("go", "come") and words[i - 1].pos == "VERB"
        first = first or (serial and words[i].tag == "VB")
        if n:
            last = words[i + n - 1]
            pos, tag_ = last.pos, last.tag
            if n > 1 and "noun" in readings and pos in ("VERB", "AUX"):
                pos, tag_ = "NOUN", "NN"  # "tv stand under tv": spaCy's verb ends a thing's name
            tok = Tok(
                " ".join(w.text for w in words[i : i + n]),
                dict(readings),
                plural,
                pos=pos,
                lemma=last.lemma,
                tag=tag_,
            )
            if n == 1 and i == 0 and tok.has("other") and len(words) > 1 and words[1].text == ",":
                tok.tags = {"filler": words[i].text}  # "next, grab the potato": then
            if n == 1:
                _read_in_context(tok, words, i, verb=tok.has("be"))  # "it is not painted"
            if n == 1 and words[i].pos == "INTJ" and "neg" in tok.tags:
                del tok.tags["neg"]  # "no, not the sofa": "no" answers, it negates nothing
                tok.tags["filler"] = words[i].text
            if n == 1 and _verb_after_to(words, i) and tok.has("adj") and not tok.has("fverb"):
                tok.tags = {"overb": words[i].lemma}  # "something to open a bottle with"
                tok.pos, tok.tag = "VERB", "VB"
            if n == 1:
                if words[i].text in _ONE_WORDS:
                    tok.tags["one"] = True
                    tok.plural = _ONE_WORDS[words[i].text]
                if _participle_clause(words, i):
                    tok.tags["participle"] = True  # "the couch watching telly": a clause
                if tok.has("colour") and _inside_compound(words, i):
                    tok.tags = {"unk": words[i].text}  # "ice cream scoop", not a cream one
                if tok.has("dir") and _verb_of_person(words, i, ("VBD", "VBN")):
                    del tok.tags["dir"]  # "I left my badge on my desk": a verb, no side
                if tok.has("ord") and _first_in_time(words, i):
                    tok.tags = {"adv": words[i].text}  # "find the copier first": a step
                _grammar(tok, words[i], first)
                _open_readings(tok, words[i])
                if tok.has("fverb") and (
                    _adjective_after_be(words, i)
                    or (_modifies_noun(words, i) and set(tok.tags) <= _VERBISH | {"super"})
                ):
                    # "it is clear and has a blue lid", "lunch box on the windowsill",
                    # "clear plastic storage bin": a word of the thing's look or name, not
                    # the need "to clear" / "to lunch"; "lower kitchen cabinet": the lowest
                    _as_description(tok, words[i])
                if tok.has("be") and _named_after_determiner(words, i):
                    # "a set of two curtains", "in a hanging basket": a noun or a word of
                    # its name after its determiner, not "set" = placed, "hanging" = is
                    for key in ("be", "fverb", "overb"):
                        tok.tags.pop(key, None)
                    tok.tags["unk"] = words[i].text
                if words[i].pos == "AUX" and tok.has("modal"):
                    # "where do I go …": an auxiliary, not the function verb of "do laundry"
                    tok.tags.pop("fverb", None)
                    tok.tags.pop("overb", None)
                if first and _verb_before_place(words, i) and tok.has("noun"):
                    for key in ("noun", "unk", "attr"):  # "go stand next to the shelf"
                        tok.tags.pop(key, None)
                    tok.tags.setdefault("overb", words[i].lemma)
                if _verb_of_subject(words, i) and tok.has("noun", "unk", "fverb"):
                    for key in ("noun", "unk", "attr", "fverb"):  # "the plant blocks the view"
                        tok.tags.pop(key, None)
                    tok.tags.setdefault("overb", words[i].lemma)
                    tok.pos, tok.tag = "VERB", words[i].tag
                subject = i > 0 and words[i - 1].dep == "nsubj"
                if subject and tok.has("noun") and _verb_of_person(words, i, ("VB", "VBD", "VBP")):
                    for key in ("noun", "unk", "attr"):  # "you saw a drill", "did you notice"
                        tok.tags.pop(key, None)
                    tok.tags.setdefault("overb", words[i].lemma)
                commands = _verb_with_particle(words, i) or _verb_for_me(words, i)
                if first and (
                    commands or _verb_with_object(words, i) or _mistagged_command(words, i)
                ):
                    # "Switch on the lamp", "throw me the ball", "vacuum the rug", "switch
                    # the telly off": a command, not a noun
                    for key in ("noun", "unk", "attr"):
                        tok.tags.pop(key, None)
                    tok.tags.setdefault("overb", words[i].lemma)
                    tok.pos, tok.tag = "VERB", "VB"
                imperative = tok.tag == "VB" and first and tok.pos == "VERB"
                if imperative and not tok.has("fverb", "prep", "noun", "room", "except"):
                    tok.tags["seek"] = words[i].lemma
            after_det = i > 0 and words[i - 1].pos == "DET"
            if n == 1 and tok.has("away", "prep") and after_det and words[i].pos == "ADJ":
                tok.tags = {"adj": ("other", words[i].text)}  # "the outside tap": a kind
            of_after = i + 1 < len(words) and words[i + 1].text == "of"
            if n == 1 and tok.has("filler") and after_det and of_after and words[i].pos == "NOUN":
                del tok.tags["filler"]  # "at the head of the table": a noun, not "head to"
            if tok.has("except"):
                for key in ("seek", "overb", "fverb"):  # "avoid the living room": not X
                    tok.tags.pop(key, None)
            out.append(tok)
            i += n
        else:
            tok = _single(words[i], first)
            if _comparative_of(words, i):
                tok.tags = {"adj": ("other", words[i].lemma)}  # "the darker of the two rugs"
                tok.pos, tok.tag = "ADJ", "JJR"
            _read_in_context(tok, words, i, verb=tok.has("overb") and not tok.has("fverb"))
            if tok.has("modal") and _noun_after_determiner(words, i):
                tok.tags = {"unk": words[i].text}  # "an empty can on the desk": a thing
                tok.pos, tok.tag = "NOUN", "NN"
            if (
                first
                and tok.has("unk")
                and (_verb_before_object(words, i) or _mistagged_command(words, i))
            ):
                # "… and dust the bookcase": spaCy's noun is the command's verb
                tok.tags = {"overb": words[i].text, "seek": words[i].text}
                tok.pos, tok.tag = "VERB", "VB"
            out.append(tok)
            i += 1
    return _thing_after_except(_any_but(out))


def _thing_after_except(toks: list[Tok]) -> list[Tok]:
    """ "anything but that green thing", "except the broken things", "exclude anything in
    the attic": "thing" right after an exception and its modifiers, or "anything" right
    after it, stands for the kind sought, as "one" does."""
    for j, tok in enumerate(toks):
        whole = tok.text in ("anything", "everything")  # "exclude anything in the attic"
        if tok.text not in ("thing", "things") and not whole:
            continue
        if not tok.has("generic", "noun", "unk") and not whole:
            continue
        k = j - 1
        while k >= 0 and toks[k].has("det", "colour", "material", "adj", "size", "attr"):
            k -= 1  # "that green", "the chipped"
        if k >= 0 and (k < j - 1 or whole) and toks[k].has("except"):
            toks[j] = Tok(tok.text, {"one": True}, tok.text == "things", pos=tok.pos,
                          lemma=tok.lemma, tag=tok.tag)  # fmt: skip
    return toks


def _any_but(toks: list[Tok]) -> list[Tok]:
    """ "any chair but the red one": "but" after "any" and a noun (no comma between)
    rules out what follows, as "except" does."""
    for j in range(2, len(toks)):
        tok = toks[j]
        if tok.text != "but" or not toks[j - 1].has("noun", "unk", "one"):
            continue
        window = toks[max(0, j - 4) : j]
        opened = [k for k, t in enumerate(window) if t.text == "any"]
        if opened and not any(t.has("comma") for t in window[opened[-1] :]):
            toks[j] = Tok(tok.text, {"except": tok.text}, pos=tok.pos, lemma=tok.lemma, tag=tok.tag)
    return toks


# Determiners that open a command's object right after its verb ("dust the bookcase",
# "mop my floor").
_OBJECT_DETERMINERS = frozenset(
    {"the", "a", "an", "my", "your", "our", "his", "her", "their", "all", "those", "these",
     "that", "this", "some", "each", "every"}
)  # fmt: skip


def _verb_before_object(words: list[Word], i: int) -> bool:
    """Whether the clause-opening word ``i`` (tagged NN, VB or VBP by spaCy; the caller
    checks that no vocabulary knows it) is the verb of a command whose object follows at
    once ("go to the library and dust the bookcase"): a word at the head of its clause
    (its own root or a conjunct) followed by a determiner and then more words."""
    if i + 2 >= len(words) or words[i].tag not in ("NN", "VB", "VBP"):
        return False
    return words[i].dep in ("ROOT", "conj") and words[i + 1].text in _OBJECT_DETERMINERS


def _noun_after_determiner(words: list[Word], i: int) -> bool:
    """Whether a word spaCy took for a modal stands in a noun phrase ("an empty can",
    "the can"): after a determiner, or an adjective after one, and not before a verb."""
    if words[i].text != "can":
        return False  # the one modal that is also a thing
    j = i - 1
    while j >= 0 and (
        words[j].pos in ("ADJ", "NOUN") or words[j].text in colour_vocab.colour_words()
    ):
        j -= 1  # "an empty can", "the red can" (spaCy's proper noun), "the gas can"
    after = words[i + 1] if i + 1 < len(words) else None
    if after is not None and after.pos in ("VERB", "AUX"):
        return False  # "where did the cleaner put the dustpan": who did it
    if after is not None and (after.tag == "VB" or after.text in ("not", "n't", "also")):
        return False  # "this can be moved", "the kids can't reach it"
    return j >= 0 and j < i and words[j].pos == "DET" and words[j].text not in ("that", "this")
