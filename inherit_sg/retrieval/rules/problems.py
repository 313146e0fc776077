"""Problem statements that imply a need: "My hands are dirty. Is there something that
could help?" → ``wash hands`` (sink); "It's too dark in here" → ``light``.

The first sentence of a request (its first clause when it is one sentence) is read as a
problem when it is a statement (it opens with a subject and neither asks nor seeks) and
names a state of the vocabulary's problems (``functions.toml``), with its subject where
one is needed. The statement is then taken out of the request: its nouns are not the
target ("hands") and its adjectives are not attributes ("dark"); the rest ("is there
something in the kitchen that could help") is parsed as usual and gets the function.
A statement that names no problem of the vocabulary ("I wonder how much I weigh. Is
there something that could help?") gives a function in its own words when the rest asks
for nothing more than something that helps (:func:`open_problem`); retrieval then
matches it by meaning.
"""

from __future__ import annotations

from functools import lru_cache
from itertools import pairwise

from inherit_sg.retrieval.constraints import FunctionConstraint
from inherit_sg.retrieval.rules.cursor import weighted
from inherit_sg.retrieval.rules.tokens import COMMA, Word
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab.colours import colour_words
from inherit_sg.vocab.functions import problems
from inherit_sg.vocab.lexicon import lexicon


@lru_cache(maxsize=1)
def _problem_subjects() -> frozenset[str]:
    """Nouns a statement may open with ("books are piling up", "dishes are stacked")."""
    return frozenset(s for p in problems() for s in p.subjects)


# Dependencies of words that modify a noun: "the dark cabinets" names cabinets, it does
# not state that something is dark.
_MODIFIERS = frozenset({"amod", "compound", "nmod", "det", "poss", "nummod"})


def _denied(words: list[Word], k: int) -> bool:
    """Whether word ``k`` is a state the sentence denies ("I'm not hungry", "not very
    cold"): "not" / "never" just before it, or before one adverb before it."""
    if k > 0 and words[k - 1].lemma in ("not", "never"):
        return True
    return k > 1 and words[k - 2].lemma in ("not", "never") and words[k - 1].pos == "ADV"


def _terms(words: list[Word], heads_only: bool) -> set[str]:
    """Words and their lemmas (only those that do not modify a noun when ``heads_only``:
    "the dark cabinets" states nothing dark, nor does "dark brown", a shade), every pair
    of words ("upper floor") and every run of three to five ("sun is in my eyes")."""
    colours = colour_words()
    heads = [
        w
        for k, w in enumerate(words)
        if not heads_only
        or (
            w.dep not in _MODIFIERS
            and not (k + 1 < len(words) and words[k + 1].text in colours)
            and not _opens_object_name(words, k)
        )
    ]
    terms = {w.text for w in heads} | {w.lemma for w in heads}
    texts = [w.text for w in words]
    lemmas = [w.lemma for w in words]
    runs = {" ".join(texts[i : i + n]) for n in (3, 4, 5) for i in range(len(texts) - n + 1)}
    return (
        terms
        | {f"{a} {b}" for a, b in pairwise(texts)}
        | {f"{a} {b}" for a, b in pairwise(lemmas)}
        | runs
    )


def _opens_object_name(words: list[Word], k: int) -> bool:
    """Whether word ``k`` and the next name a kind of object together ("fire
    extinguisher", "smoke alarm"): the first word is part of a name, not a state, even
    where the parser takes it for the head."""
    if k + 1 >= len(words):
        return False
    pair = (f"{words[k].text} {words[k + 1].text}", f"{words[k].text} {words[k + 1].lemma}")
    return any(object_vocab.canonical_label(p) for p in pair)


def _is_statement(words: list[Word]) -> bool:
    if not words:
        return False
    lx = lexicon().problems
    first = words[0]
    if first.text not in lx["subjects"] and first.lemma not in _problem_subjects():
        return False
    if first.pos in ("VERB", "AUX"):
        return False  # "head to the gym" asks; it states no problem
    if first.pos == "DET" and not any(w.pos in ("VERB", "AUX") for w in words):
        return False  # "the treadmill closest to the window in the gym": a thing named
    if any(w.dep == "ROOT" and w.pos in ("NOUN", "PROPN") for w in words) and any(
        w.dep == "acl" for w in words
    ):
        return False  # "the books stacked on the floor": a thing described, not a state
    asks = lx["request_words"] - ({"need"} if first.text not in lx["speaker"] else set())
    return not any(w.text in asks or w.lemma in asks for w in words)


def _object_subject(words: list[Word]) -> set[str]:
    """The statement's subject (with its compound and its head alone) when it names a
    kind of object: "the wardrobe is tall and dark brown" describes a wardrobe, it
    states no problem."""
    for k, w in enumerate(words):
        if w.dep not in ("nsubj", "nsubjpass") or w.pos not in ("NOUN", "PROPN"):
            continue
        j = k
        while j > 0 and words[j - 1].dep == "compound":
            j -= 1
        forms = {
            " ".join(x.text for x in words[j : k + 1]),
            " ".join(x.lemma for x in words[j : k + 1]),
            w.text,
            w.lemma,
        }
        if any(object_vocab.canonical_label(f) for f in forms):
            return forms
        return set()
    return set()


def _speaker_has(words: list[Word]) -> bool:
    """Whether the sentence says the speaker has something ("I've got some dirty
    plates", "we have muddy boots")."""
    speaker = lexicon().problems["subjects"]
    return any(
        w.dep == "ROOT"
        and w.lemma in ("have", "get")
        and any(s.dep == "nsubj" and s.text in speaker for s in words)
        for w in words
    )


def match_problem(words: list[Word]) -> tuple[str, tuple[str, ...]] | None:
    """The (function, likely kinds) a problem sentence implies, or None. A statement
    about a kind of object is a problem only where the problem names that subject
    ("the dishes are dirty"), not otherwise ("the laundry basket is by the washer")."""
    # "I've got some dirty plates": what the speaker has is in the state its adjective says
    states = _terms(words, heads_only=not _speaker_has(words))
    subjects = _terms(words, heads_only=True)  # "a laundry basket on the floor": no laundry
    thing = _object_subject(words)
    # a thing that does something ("the cable runs along the wall") states no problem
    # of the speaker's: with a noun subject, a problem with no subjects of its own needs
    # its state in a word other than the verb ("the room is too dark")
    noun_subject = any(w.dep == "nsubj" and w.pos in ("NOUN", "PROPN") for w in words) or any(
        w.pos == "NOUN" and object_vocab.canonical_label(w.text) for w in words
    )  # "I left the tap running": the tap's state, not the speaker's
    # a state the sentence denies is no problem of the speaker's ("I'm not hungry"); a
    # problem about a thing may lie in the denial itself ("I don't know what time it is")
    kept = [w for k, w in enumerate(words) if not _denied(words, k)]
    loose_states = _terms([w for w in kept if w.pos != "VERB"] if noun_subject else kept,
                          heads_only=True)  # fmt: skip
    loose: tuple[str, tuple[str, ...]] | None = None
    for problem in problems():
        if not states.intersection(problem.states):
            continue
        if thing and not thing.intersection(problem.subjects):
            continue
        if problem.subjects and subjects.intersection(problem.subjects):
            return problem.function, problem.kinds
        if not problem.subjects and loose is None and loose_states.intersection(problem.states):
            loose = (problem.function, problem.kinds)
    return loose


# Interjections a spoken statement opens with ("oh my nose is running", "um I'm cold").
_INTERJECTIONS = frozenset(
    {"oh", "ooh", "um", "umm", "uh", "erm", "er", "hmm", "ah", "ahh", "ugh", "oops", "ow", "ouch"}
)
# Words that open a sentence before a comma without stating anything ("well, I'm cold").
_OPENERS = frozenset({"well", "so", "okay", "ok", "right", "hey", "listen", "look", "honestly"})


def _without_opening_fillers(words: list[Word]) -> list[Word]:
    """The sentence without the interjections and fillers it opens with ("oh my nose is
    running", "um, I'm a bit chilly", "well I'm cold"), which state nothing."""
    k = 0
    while k < len(words) and (
        words[k].text == ","
        or words[k].text in _INTERJECTIONS
        or (words[k].text in _OPENERS and k + 1 < len(words) and words[k + 1].text == ",")
    ):
        k += 1
    return words[k:] if k < len(words) else words


# Words that open a question run on after a statement with no comma.
_QUESTION_WORDS = frozenset({"what", "where", "which", "anything", "something"})


def _question_starts(words: list[Word], i: int) -> bool:
    """Whether an unpunctuated question starts at word ``i`` of a statement ("too bright
    in the den what can i pull down"), not a clause a verb takes ("i don't know what time
    it is")."""
    return i > 2 and words[i].text in _QUESTION_WORDS and words[i - 1].pos not in ("VERB", "AUX")


# Words that open a trailing statement of what stands in the way ("… but it's too dark").
_OBSTACLE_OPENERS = frozenset({"but"})
# Words that make "it is …" a complaint, not a description ("it's getting dark", "it's
# too cold", "it's boiling in here"; not "it is round and dark wood").
_DEGREE = frozenset({"too", "so", "getting", "really", "very", "bit", "boiling", "freezing",
                     "pitch", "awfully", "quite", "rather"})  # fmt: skip


def trailing_problem(
    sentences: list[list[Word]],
) -> tuple[FunctionConstraint | None, list[list[Word]]]:
    """A problem stated after what the speaker wants to do, as what stands in the way
    ("I want to read in bed but it's too dark", "I'd like to read. It's too dark.",
    "switch on the lamp, it's getting dark"):
    the function it implies, and the sentences without it; (None, sentences) else."""
    if not sentences:
        return None, sentences
    last = [w for w in sentences[-1] if w.text != "."]
    cut = max((i for i, w in enumerate(last) if w.text in _OBSTACLE_OPENERS), default=-1)
    if cut < 0:  # "switch on the lamp, it's getting dark": a last clause of its own
        cut = max((i for i, w in enumerate(last) if w.text == ","), default=-1)
    tail = last[cut + 1 :] if cut >= 0 else last
    if (cut < 0 and len(sentences) < 2) or not tail or not _is_statement(tail):
        return None, sentences
    if tail[0].text not in ("it", "i", "we") or any(w.text == "," for w in tail):
        return None, sentences  # "… but the lamp is too dim": a thing, not the speaker's
    if tail[0].text == "it" and not any(w.text in _DEGREE for w in tail):
        return None, sentences  # "…, it is round and dark wood": the thing described
    if any(w.pos in ("NOUN", "PROPN") and object_vocab.canonical_label(w.text) for w in tail):
        return None, sentences  # "it is between the two armchairs …": a thing placed
    sense = match_problem(tail)
    if sense is None:
        return None, sentences
    made = FunctionConstraint(
        function=sense[0],
        labels=sense[1],
        weight=weighted("function", None),
        text=" ".join(w.text for w in tail),
    )
    rest = last[:cut] if cut > 0 else []
    return made, [*sentences[:-1], *([rest] if rest else [])]


def split_problem(
    sentences: list[list[Word]],
) -> tuple[FunctionConstraint | None, list[list[Word]]]:
    """A leading problem statement as a function, and the sentences left to parse."""
    if not sentences:
        return None, sentences
    words = _without_opening_fillers(sentences[0])
    # the statement ends at a comma, or where an unpunctuated question starts ("too
    # bright in the den what can i pull down")
    cut = next(
        (i for i, w in enumerate(words) if w.text == "," or _question_starts(words, i)), len(words)
    )
    first = words[:cut]
    if not _is_statement(first):
        return None, sentences
    sense = match_problem(first)
    if sense is None:
        return None, sentences
    function, labels = sense
    made = FunctionConstraint(
        function=function,
        labels=labels,
        weight=weighted("function", None),
        text=" ".join(w.text for w in first),
    )
    rest = words[cut + 1 :]
    place = _place_part(first)
    if place:  # "it is stuffy in the bedroom": the place stays a constraint
        rest = [*place, COMMA, *rest] if rest else place
    return made, ([rest] if rest else []) + sentences[1:]


def open_problem(sentences: list[list[Word]]) -> FunctionConstraint | None:
    """A leading statement that names no problem of the vocabulary ("I wonder how much I
    weigh."), as a function in its own words (no kinds listed), for a request that then
    asks only for "something that could help"; None when the request opens otherwise or
    the statement is a single clause of a longer sentence."""
    if len(sentences) < 2 or not sentences[0]:
        return None
    first = [w for w in sentences[0] if w.text != "."]
    if not _is_statement(first) or _object_subject(first) or match_problem(first) is not None:
        return None
    text = " ".join(w.text for w in first)
    return FunctionConstraint(function=text, weight=weighted("function", None), text=text)


def _place_part(words: list[Word]) -> list[Word]:
    """The words of a statement from its first place word on ("in the bedroom",
    "upstairs"), or none."""
    places = lexicon().problems["place_words"]
    for i, w in enumerate(words):
        if w.text in places and (w.pos in ("ADP", "ADV") or w.text.endswith("stairs")):
            tail = words[i:]
            if w.text.endswith("stairs"):
                return tail
            if len(tail) > 1 and not _body_part(tail):
                return tail
    return []


# "The sun is in my eyes": a place on the speaker, not in the building.
_BODY_PARTS = frozenset({"eye", "eyes", "face", "ear", "ears", "nose", "head", "back", "hand"})


def _body_part(place: list[Word]) -> bool:
    """Whether a place phrase is on the speaker's body ("in my eyes")."""
    return len(place) > 2 and place[1].text in ("my", "our") and place[2].text in _BODY_PARTS
