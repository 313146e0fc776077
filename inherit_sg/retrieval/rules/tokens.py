"""Request text checks and analysis: text → sentences of words with spaCy's lemmas and
tags.

The text is normalised only where spaCy's tokenizer would otherwise split or join the
wrong things (curly quotes, camel case "CoffeeTable", separators "TV-stand", letters glued
to digits "bedroom2", a missing space after a full stop "bed.it"), and typos are corrected
(:mod:`.spelling`); spaCy then gives the
tokens, lemmas, part-of-speech tags, the dependency parse and the sentences. Contractions
come back as full words ("n't" → "not", "'s" → "is" where it is the verb; a possessive
"'s" is dropped); clause punctuation becomes ``","`` tokens.
"""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass

from inherit_sg.errors import QueryTextError
from inherit_sg.nlp import analyse, known_lemma, lemma_phrase, singular_read_as_plural
from inherit_sg.retrieval.rules.sayings import plain_sayings

MAX_QUERY_CHARS = 5000

_QUOTES = str.maketrans({"’": "'", "‘": "'", "`": "'", "´": "'", "“": '"', "”": '"'})
_CAMEL = re.compile(r"(?<=[a-z])(?=[A-Z][a-z])")
_SEPARATORS = re.compile(r"[-_/+#]+")
# A hyphen with space on both sides is a dash between phrases ("the master bath - the
# other sink"), not a joiner of words ("medium-sized").
_SPACED_DASH = re.compile(r"(?:^|\s)-{1,2}(?=\s|$)")
_LETTER_DIGIT = re.compile(r"(?<=[A-Za-z])(?=\d)|(?<=\d)(?!st\b|nd\b|rd\b|th\b)(?=[A-Za-z])")
_GLUED_STOP = re.compile(r"(?<=[a-z])([.!?;,])(?=[A-Za-z])")
_SPACES = re.compile(r"\s+")
# "… a black game console which is the target": the thing just named is the one meant.
_WHICH_IS_TARGET = re.compile(
    r"(?<!\s),?\s+(?:which|that)\s+is\s+(?:the|our)\s+(?:target|object)(?:\s+described)?\b",
    re.I,  # (the look-behind starts a match only where a run of spaces starts)
)
# A diary-style past with no subject at the start: "lost one earbud somewhere …",
# "dropped the remote behind the couch", "left my phone in the car" (with "I" added).
_NO_SUBJECT_PAST = re.compile(
    r"^(?:(lost|dropped|misplaced|forgot|stashed|hid|moved|tossed|threw)\s+"
    r"(?=(?:my|the|a|an|one|our|his|her|their|some|both)\b)"
    r"|(left)\s+(?=(?:my|our|his|her|their)\b))",
    re.IGNORECASE,
)
# "where'd I put it", "what'd you do with it": after a question word, 'd is "did".
_WH_DID = re.compile(r"\b(where|what|who|how|why|when)'d\b", re.IGNORECASE)
# A chat mention of whom the message is for ("@robot grab the scissors").
_MENTION = re.compile(r"(?<![\w@])@\w+")
# Contracted forms spaCy returns as separate tokens, by (text, coarse tag).
_CONTRACTED = {
    "n't": "not",
    "nt": "not",
    "'re": "are",
    "'m": "am",
    "'ve": "have",
    "'ll": "will",
    "'d": "would",
    "ca": "can",
    "wo": "will",
    "sha": "shall",
}
_CLAUSE_PUNCT = frozenset(",;:!?.()[]{}…—–")


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


@dataclass(frozen=True)
class Word:
    """One analysed word: lower-case surface form (contractions expanded), lemma,
    coarse and fine part-of-speech tags and dependency label."""

    text: str
    lemma: str
    pos: str
    tag: str
    dep: str = ""

    @property
    def plural(self) -> bool:
        """True for a plural noun (spaCy's NNS / NNPS)."""
        return self.tag in ("NNS", "NNPS")


COMMA = Word(",", ",", "PUNCT", ",")
# Words the rewriting passes insert ("there is a coat rack", "the tub in the bathroom",
# "its the cabinet" → "it is the cabinet").
THE = Word("the", "the", "DET", "DT", "det")
A = Word("a", "a", "DET", "DT", "det")
IN = Word("in", "in", "ADP", "IN", "prep")
IT = Word("it", "it", "PRON", "PRP", "nsubj")
IS = Word("is", "be", "AUX", "VBZ", "ROOT")


# A hedge in brackets after a word: "the leather(?) ottoman".
_BRACKETED_DOUBT = re.compile(r"\(\s*\?+\s*\)")
# "-ish" hedges: "wooden-ish", "brownish", "reddish", "bluish".
_ISH = re.compile(r"\b([A-Za-z]+?)(-?)ish\b")
# A hyphenated participle made from a noun: "glass-topped", "heart-shaped", "l-shaped".
_HYPHEN_PARTICIPLE = re.compile(r"\b([A-Za-z]+)-([A-Za-z]+ed)\b")
# How far away, in steps or feet: "about three steps away", "two paces ahead" (no stairs).
_PACES_AWAY = re.compile(
    r"\b(?:about |around |maybe |roughly |like )?(?:\d+|a|one|two|three|four|five|six|seven|"
    r"eight|nine|ten|a few|few|couple of|a couple of) (?:steps?|paces?|feet|foot) "
    r"(?:away|ahead|in front|forward|behind me|back)\b",
    re.IGNORECASE,
)
# A day of the week, with its preposition: when something happened, not where ("the boots
# I left in the mudroom on monday", "since Tuesday", "Friday night").
_WEEKDAY = re.compile(
    r"\b(?:mon|tues|wednes|thurs|fri|satur|sun)day's\b"  # "after Friday's rehearsal"
    r"|(?:\b(?:on|since|from|by|until|till|last|this|next|every|before|after)\s+)?"
    r"\b(?:mon|tues|wednes|thurs|fri|satur|sun)days?\b(?!')"
    r"(?:\s+(?:morning|afternoon|evening|night))?",
    re.IGNORECASE,
)
# A verb and particle joined before a noun: "walk-in cooler", "built-in shelves",
# "pull-out couch".
_PARTICLE_COMPOUND = re.compile(
    r"\b([A-Za-z]+)-(in|out|up|down|on|off|over|through|away)\s+([A-Za-z]+)", re.IGNORECASE
)
# A colour said with the word "colour": "cream colour", "rust-coloured", "wine colored".
_COLOUR_WORD = re.compile(r"\b([A-Za-z]+)[ -](colou?r(?:ed)?)\b", re.IGNORECASE)
# "wall mounted", "ceiling-mounted": how a thing is fixed, written before its name.
_MOUNTED = re.compile(r"\b(?:wall|ceiling)[- ](mounted|hung)\b", re.IGNORECASE)


def colour_or_material(word: str) -> bool:
    """Whether ``word`` names a colour or a material ("brown", "wooden"), not a thing."""
    from inherit_sg.vocab.colours import colour_words
    from inherit_sg.vocab.lexicon import lexicon

    return word in colour_words() or word in lexicon().materials


def _without_ish(match: re.Match[str]) -> str:
    """ "brownish" → "brown", "reddish" → "red", "bluish" → "blue", "wooden-ish" →
    "wooden": the hedged colour or material; a word merely ending in "ish" ("dish",
    "polish") stays."""
    stem, hyphen = match.group(1), match.group(2)
    low = stem.lower()
    for guess in (low, low[:-1] if len(low) > 2 and low[-1] == low[-2] else "", low + "e"):
        if guess and colour_or_material(guess):
            return guess
    return stem if hyphen else match.group(0)


def _without_weekday(match: re.Match[str]) -> str:
    """The text without a day of the week, unless the day tells one thing from another
    ("not the one from Tuesday")."""
    before = match.string[: match.start()].lower().rstrip()
    if before.endswith((" one", " ones", "the one from", "the ones from")):
        return match.group(0)
    return " "


_SHADE_COMPARATIVES = frozenset({"lighter", "darker", "brighter", "paler", "deeper"})


def _colour_said(match: re.Match[str]) -> str:
    """ "cream colour" → "cream", "light blue coloured" → "light blue": the colour itself;
    a word that names no colour ("rust-coloured") says one all the same, as an -ish hedge
    would ("rustish"); other words before "colour" stay ("the same colour")."""
    word = match.group(1)
    if colour_or_material(word.lower()) or word.lower() in _SHADE_COMPARATIVES:
        return word  # "cream colour", "the lighter-coloured of the two rugs"
    if match.group(0)[len(word)] == "-":
        return f"{word}ish"
    return match.group(0)


def _particle_compound(match: re.Match[str]) -> str:
    """ "walk-in cooler door" → "cooler door", "built-in shelves" → "shelves": a verb and
    particle before a noun say how the thing is built, which the parser would otherwise
    read as a verb or as the thing itself; a name the vocabulary knows whole ("pull-out
    couch", "walk-in shower") stays."""
    from inherit_sg.vocab.objects import canonical_label, labels_for
    from inherit_sg.vocab.rooms import room_type

    stem, particle, noun = match.groups()
    whole = f"{stem} {particle} {noun}"
    if canonical_label(whole.lower()) is not None or room_type(whole.lower()) is not None:
        return whole  # "pull-out couch", "walk-in closet"
    if known_lemma(noun.lower(), "noun") or labels_for(noun.lower()):
        return noun
    return match.group(0)


def _participle_compound(match: re.Match[str]) -> str:
    """ "glass-topped table" → "glass table", "heart-shaped pillow" → "shaped pillow": a
    colour or material before a participle made from a noun says what the thing is made
    of; a noun ("heart", "star") says its shape, which the parser would otherwise take for
    the thing itself. Adjectives and numbers ("high-backed", "three-legged") and letters
    ("l-shaped") stay."""
    first, participle = match.group(1), match.group(2)
    low = first.lower()
    if colour_or_material(low):
        return first
    noun = known_lemma(low, "noun") and not known_lemma(low, "adj")
    if len(low) > 1 and low not in _NUMBER_WORDS and noun:
        return participle
    return match.group(0)


_NUMBER_WORDS = frozenset(
    {"one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "single",
     "double", "triple", "multi"}
)  # fmt: skip


# Words written on a thing, quoted or in capitals after a word of writing: "the binder
# that says 'TAXES'", "the whiteboard that has DO NOT ERASE written on it".
_SINGLE_QUOTED = re.compile(r"(?<![A-Za-z])'([^'\n]{1,40})'(?![A-Za-z])")
_CAPITALS_WRITTEN = re.compile(
    r"\b(says?|saying|reads?|reading|labell?ed|marked|has|have|with)\s+"
    r"((?:[A-Z][A-Z']+\s+)+[A-Z][A-Z']+)\b"
)


# A word written on a label after the word for labelling: "the box labeled kitchen", "the
# ones marked for isolation", "tagged as broken".
_LABEL_WORD = re.compile(
    r"(?<!\bthe\s)(?<!\ba\s)(?<!\ban\s)(?<!\bany\s)(?<!\ball\s)(?<!\bthose\s)"
    r"\b(labell?ed|marked|tagged)\s+(?:(?:as|for|with)\s+)?(?:(?:do\s+not|don't|dont|no)\s+)?"
    r"(?!(?:the|a|an|on|in|by|at|and|or|but|not|with|near|next|under|above|behind|to|from|"
    r"one|ones|it|them)\b)"
    r"[a-z0-9]+\b",
    re.IGNORECASE,
)


def _without_written_words(text: str) -> str:
    """``text`` without the words written on a thing (see ``_CAPITALS_WRITTEN``), so
    that "DO NOT ERASE" rules nothing out; a request typed all in capitals keeps its
    words."""
    text = _SINGLE_QUOTED.sub(" ", text)
    if not any(c.islower() for c in text):
        return text
    text = _LABEL_WORD.sub(r"\1", text)
    return _CAPITALS_WRITTEN.sub(lambda m: f"{m.group(1)} ", text)


def normalise(text: str) -> str:
    """The text spaCy is given (see the module docstring)."""
    text = unicodedata.normalize("NFKC", text).translate(_QUOTES)
    text = _WH_DID.sub(r"\1 did", text)
    text = plain_sayings(text)
    text = _NO_SUBJECT_PAST.sub(lambda m: f"i {m.group(1) or m.group(2)} ", text)
    text = _WHICH_IS_TARGET.sub(", that is the target", text)
    text = _without_written_words(text)
    text = _BRACKETED_DOUBT.sub(" ", text)
    text = _ISH.sub(_without_ish, text)
    text = _MOUNTED.sub(r"\1", text)  # (the surface is no thing sought)
    text = _COLOUR_WORD.sub(_colour_said, text)
    text = _PACES_AWAY.sub(" ", text)
    text = _WEEKDAY.sub(_without_weekday, text)
    text = _HYPHEN_PARTICIPLE.sub(_participle_compound, text)
    text = _PARTICLE_COMPOUND.sub(_particle_compound, text)
    text = _MENTION.sub(" ", text)
    text = _CAMEL.sub(" ", text)
    text = _SPACED_DASH.sub(" \u2014", text)
    text = _SEPARATORS.sub(" ", text)
    text = _LETTER_DIGIT.sub(" ", text)
    text = _GLUED_STOP.sub(r"\1 ", text)
    return _SPACES.sub(" ", text).strip()


def _word(tok_text: str, lemma: str, pos: str, tag: str, dep: str) -> Word | None:
    low = tok_text.lower()
    if low in _CONTRACTED and (low.startswith("'") or low in ("n't", "nt") or tag == "MD"):
        full = _CONTRACTED[low]
        return Word(full, "not" if full == "not" else lemma.lower(), pos, tag, dep)
    if low in ("'s", "s") and tag == "VBZ":
        return Word("is", "be", pos, tag, dep)
    if low == "'s" and lemma.lower() == "us":
        return Word("us", "us", pos, tag, dep)
    if tag == "POS" or low in ("'", "'s"):
        return None  # possessive: "the kid's bed" -> "the kid bed"
    if pos == "PUNCT" or all(c in _CLAUSE_PUNCT for c in low):
        return COMMA if any(c in _CLAUSE_PUNCT for c in low) else None
    if not any(c.isalnum() for c in low):
        return None  # quotes, symbols
    lemma = lemma.lower() if lemma.strip() else low
    if tag in ("NNS", "NNPS") and singular_read_as_plural(low, lemma):
        return Word(low, low, pos, "NN", dep)  # "the atlas": spaCy's lemma "atla"
    return Word(low, lemma, pos, tag, dep)


# "where does the milk go?", "where should these books go", "where do the towels belong":
# a question about the place a thing goes, asked as "where should I put ..." (the thing
# named is not what is sought; a pronoun subject, "where do I go", is not such a question)
_WHERE_IT_GOES = re.compile(
    r"\bwhere(?: is| are)? (?:do|does|should|would|shall|will|must|can|could|ought to) "
    r"(?!(?:i|we|you|they|he|she|it|one)\b)"
    r"((?:\w+ ){0,5}?\w+) (?:go|goes|go back|belong|belongs|live|lives|get put|get stored|be put|be kept|be stored)\b",
    re.IGNORECASE,
)


def where_it_goes(text: str) -> str:
    """A question about where a thing goes ("where does the milk go") as the request for
    a place to put it that it means ("where should I put the milk"); other text as is."""
    return _WHERE_IT_GOES.sub(lambda m: f"where should I put {m.group(1)}", text)


# "the picture that does not hang above the couch": a verb of position negated with "do"
# says where the thing is not, as "is not hanging above" does
_POSITION_ING = {
    "hang": "hanging", "sit": "sitting", "stand": "standing", "rest": "resting",
    "lie": "lying", "lean": "leaning", "stay": "staying",
}  # fmt: skip
_DO_NOT_POSITION = re.compile(
    r"\b(that|which|who) (?:does|do|did)(?: not|n't|n’t|nt) (hang|sit|stand|rest|lie|lean|stay)\b",
    re.IGNORECASE,
)


def negated_position(text: str) -> str:
    """ "… that does not hang above" as "… that is not hanging above" (the negation then
    reaches the place that follows); other text ("I don't sit there") as is."""
    return _DO_NOT_POSITION.sub(
        lambda m: f"{m.group(1)} is not {_POSITION_ING[m.group(2).lower()]}", text
    )


# "there is no lamp on the desk", "no monitors are on the table", "the room has no trash
# can near the door": a thing said to be absent from a place is, for finding it, a
# thing that is not there. Absence from the scene itself ("there is no microwave in
# this kitchen") says that nothing is sought, and rules nothing out.
_PLACE_WORDS = (
    r"on|in|inside|near|next to|by|beside|under|underneath|below|above|over|behind|"
    r"in front of|between|against|at|close to|around"
)
_ABSENT_FROM = re.compile(
    r"\b(?:there (?:is|are|was|were) no|(?:the|this) room (?:has|contains) no|^no) "
    r"(?!(?:doubt|question|need|way|problem|rush|hurry|chance|matter|idea|reason|no|the|a|an|other)\b)"
    r"((?:\w+ ){0,3}?\w+) (?:(?:is|are) )?(" + _PLACE_WORDS + r") (?!this\b|these\b|here\b)",
    re.IGNORECASE,
)


# "this is a nightstand. there is no lamp on it.": the thing described has none on it
_NONE_ON_IT = re.compile(
    r"\bthere (?:is|are) no ((?:\w+ ){0,3}?\w+) (on|in|inside|on top of) (it|them)\b",
    re.IGNORECASE,
)


# "the table that has nothing on it", "a hanger with nothing on it": bare of anything
_NOTHING_ON_IT = re.compile(
    r"\b(?:(?:that|which) (?:has|have)|with|having) nothing (on|in|inside|on top of) (it|them)\b"
    r"(?! (?:besides|except|but|other than|apart from)\b)",
    re.IGNORECASE,
)


def absent_from(text: str) -> str:
    """ "there is no lamp on the desk" as "the lamp that is not on the desk" (also "no
    monitors are on …", "the room has no … near …"), "there is no lamp on it" as "it
    has no lamp on it", and "… that has nothing on it" as "… without anything on it";
    other text as is."""
    text = _NOTHING_ON_IT.sub(lambda m: f"without anything {m.group(1)} {m.group(2)}", text)
    text = _NONE_ON_IT.sub(
        lambda m: f"{m.group(3)} has no {m.group(1)} {m.group(2)} {m.group(3)}", text
    )
    return _ABSENT_FROM.sub(_thing_not_there, text)


# "there's no ice left in the freezer": the thing has run out, it is not elsewhere
_RUN_OUT = frozenset({"left", "remaining", "more"})


def _thing_not_there(match: re.Match[str]) -> str:
    if _RUN_OUT & set(match.group(1).lower().split()):
        return match.group(0)
    return f"the {match.group(1)} that is not {match.group(2)} "


# "the glass vase is NOT the one", "the car keys aren't the ones I want": a thing said not
# to be the one meant is a thing ruled out ("not the glass vase")
_NOT_THE_ONE = re.compile(
    r"(^|[.,;!?] *)(the (?:\w+ ){0,3}?\w+) (?:is|are)(?: not|n't|n’t|nt) the ones?"
    r"(?: (?:i|we) (?:want|need|mean|meant|asked for))?\b",
    re.IGNORECASE,
)
# "don't grab the one on top, grab the one underneath": an errand denied, then the same
# errand for another thing
_NOT_THIS_ERRAND = re.compile(
    r"\b(?:do not|don't|don’t|dont) (grab|get|take|bring|use|fetch|pick) "
    r"((?:\w+ ){0,6}?\w+),? (?:just |but )?\1\b",
    re.IGNORECASE,
)


def not_the_one(text: str) -> str:
    """ "the glass vase is not the one" as "not the glass vase", and "don't grab the one on
    top, grab …" as "not the one on top, grab …"; other text as is."""
    text = _NOT_THE_ONE.sub(lambda m: f"{m.group(1)}not {m.group(2)}", text)
    return _NOT_THIS_ERRAND.sub(lambda m: f"not {m.group(2)}, {m.group(1)}", text)


def analyse_text(text: str) -> tuple[list[list[Word]], list[tuple[str, str]]]:
    """Sentences of :class:`Word` s (clause punctuation as ``","``; empty sentences
    dropped), and the spelling corrections made first. ``text`` must have passed
    :func:`check_query_text`."""
    from inherit_sg.retrieval.rules.spelling import correct_spelling

    corrected, fixes = correct_spelling(normalise(text))
    doc = analyse(absent_from(negated_position(not_the_one(where_it_goes(corrected)))))
    out: list[list[Word]] = []
    for sent in doc.sents:
        words: list[Word] = []
        for tok in sent:
            word = _word(tok.text, tok.lemma_, tok.pos_, tok.tag_, tok.dep_)
            if word is None or (word is COMMA and (not words or words[-1] is COMMA)):
                continue
            words.append(word)
        while words and words[-1] is COMMA:
            words.pop()
        if words:
            words = _shades_named_by_things(_nouns_read_as_verbs(_owners_of_areas(words)))
            out.append(_its_is(words))
    return out, fixes


# Areas a possessor names rather than owns: "the children's section", "the staff area".
_OWNED_AREAS = frozenset({"section", "area", "zone", "nook", "bay", "quarter", "wing"})


def _owners_of_areas(words: list[Word]) -> list[Word]:
    """A possessor before an area ("the children's section", "the kids' area") as part
    of the area's name, not its owner (an owner is dropped like a determiner)."""
    out = list(words)
    for i, word in enumerate(words[:-1]):
        if (
            word.dep == "poss"
            and word.pos in ("NOUN", "PROPN")
            and words[i + 1].text in _OWNED_AREAS
        ):
            out[i] = Word(word.text, word.lemma, word.pos, word.tag, "compound")
    return out


_NOT_NOUN = ("verb", "adj", "adv")


def _no_verb_after(words: list[Word], i: int) -> bool:
    """Whether no verb follows ``words[i]`` (a modal needs one): the end, a preposition,
    a conjunction or a clause break."""
    return i + 1 == len(words) or words[i + 1].pos in ("ADP", "CCONJ", "PUNCT", "SCONJ")


def _nouns_read_as_verbs(words: list[Word]) -> list[Word]:
    """Nouns of a compound that spaCy tagged as a verb or a comparative, read as nouns
    again: a present-tense verb after a noun or a determiner whose lemma is no English
    verb ("the printer cartridges", "the kids lunchboxes"), and a comparative after a noun
    that comes from no adjective ("the bird feeder"). The lemmatiser's word lists decide,
    so a word that is a verb ("the kids play") stays one."""
    out = list(words)
    for i in range(1, len(words)):
        word, prev = words[i], words[i - 1]
        if word.pos == "VERB" and word.tag in ("VBZ", "VBP", "VB"):
            if prev.pos not in ("NOUN", "PROPN", "DET") or prev.tag == "WDT":
                continue
            if any(known_lemma(w, pos) for w in (word.lemma, word.text) for pos in _NOT_NOUN):
                continue  # "the kids play", "my slippers dear"
            plural = word.text.endswith("s") and not word.text.endswith("ss")
            lemma = lemma_phrase(word.text) if plural else word.text
            out[i] = Word(word.text, lemma, "NOUN", "NNS" if plural else "NN", word.dep)
        elif (
            word.text == "can"
            and word.tag == "MD"
            and prev.pos == "NOUN"
            and _no_verb_after(words, i)
        ):
            out[i] = Word("can", "can", "NOUN", "NN", word.dep)  # "the gas can by the mower"
        elif word.tag == "JJR" and prev.pos == "NOUN" and known_lemma(word.text, "noun"):
            if known_lemma(word.lemma, "adj") or known_lemma(word.text, "adj"):
                continue
            out[i] = Word(word.text, word.text, "NOUN", "NN", word.dep)
    return out


def _shades_named_by_things(words: list[Word]) -> list[Word]:
    """A noun that names the shade of the colour after it ("mustard yellow", "sky blue",
    "forest green"), before the thing's name: an adjective, not the thing sought."""
    from inherit_sg.vocab.colours import colour_words

    colours = colour_words()
    out = list(words)
    for i in range(len(words) - 2):
        word = words[i]
        if word.pos not in ("NOUN", "PROPN") or word.text in colours:
            continue
        if words[i + 1].text not in colours or words[i + 2].pos not in ("NOUN", "PROPN"):
            continue
        if words[i + 1].pos == "NOUN":
            continue  # "ice cream scoop": the colour word is a noun of a name
        out[i] = Word(word.text, word.text, "ADJ", "JJ", word.dep)
    return out


def _its_is(words: list[Word]) -> list[Word]:
    """ "its" written for "it's" before what describes it ("its tall and stainless
    steel", "its pretty short") or before "not": "it is". Before a noun it stays a
    possessive ("its wooden legs"), except before a material ("its black metal")."""
    if not any(w.text == "its" for w in words):
        return words
    from inherit_sg.vocab.lexicon import lexicon

    materials = lexicon().materials
    out: list[Word] = []
    for i, word in enumerate(words):
        if word.text != "its" or word.tag != "PRP$":
            out.append(word)
            continue
        if i + 1 < len(words) and words[i + 1].text == "not":
            out += [IT, IS]  # "its not hard", "its not the red one"
            continue
        j = i + 1
        while j < len(words) and words[j].pos == "ADV":
            j += 1
        described = j < len(words) and words[j].pos == "ADJ"
        while j < len(words) and (words[j].pos in ("ADJ", "CCONJ", "ADV") or words[j] is COMMA):
            j += 1
        if described and (j == len(words) or words[j].pos != "NOUN" or words[j].text in materials):
            out += [IT, IS]
        else:
            out.append(word)
    return out


def tokenize(text: str) -> list[str]:
    """The request's words in order, sentences joined by ``","`` (for display and for
    the function guesser): ``"Where's the TV-stand? I can't see it"`` → ``where is the tv
    stand , i can not see it``."""
    out: list[str] = []
    for sentence in analyse_text(check_query_text(text))[0]:
        if out:
            out.append(",")
        out.extend(w.text for w in sentence)
    return out
