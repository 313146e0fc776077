"""Preparing a request's sentences before they are parsed: what people write around a
request is set aside, and a run-on is split.

- A statement run on into a request with no stop between them ("the wifi is down can
  you check the router", as speech is transcribed) becomes two sentences.
- A name called at the start ("mommy I can't find my toothbrush"), the greeting and
  sign-off of a message ("Hi Sam, … Cheers, Mark") and asides that open a request ("No
  signature needed.", "Don't worry about the paperwork; …") are dropped.
- "Is it not the blue bowl?" asks whether it is: its "not" rules nothing out.
"""

from __future__ import annotations

from itertools import pairwise

from inherit_sg.retrieval.rules.asides import without_personal_asides
from inherit_sg.retrieval.rules.rewording import (
    another_as_one_more,
    besides_as_beside,
    chore_at_place,
    end_toward,
    floor_asked,
    from_then_look,
    need_after_deed,
    non_words,
    only_thing,
    ordinal_along,
    owner_side,
    set_aside_first,
    stranded_relative,
    thing_that_does,
    which_of_is,
    whose_as_with,
    without_failed_condition,
    without_manner,
    without_moved_away,
    without_no_idea,
    without_no_longer,
    without_noticing_remark,
    without_remarks_on_others,
    without_run_out,
    without_sign_negation,
    without_trailing_caution,
)
from inherit_sg.retrieval.rules.tokens import COMMA, IS, IT, Word, colour_or_material
from inherit_sg.vocab.lexicon import lexicon
from inherit_sg.vocab.objects import canonical_label
from inherit_sg.vocab.rooms import room_type

# Finite verb tags (a clause of its own, not a participle or an infinitive).
FINITE = frozenset({"VBZ", "VBP", "VBD"})
# Words that point back at the thing said before.
IT_WORDS = frozenset({"it", "them", "this", "that", "those", "these"})
QUESTION_OPENERS = frozenset({"where", "which", "what", "who", "how", "whose", "when", "why"})
_NEEDING = frozenset({"need", "require", "want"})
# Words that open a correction ("no wait, I mean …").
CORRECTION_WORDS = frozenset(
    {
        "no",
        "wait",
        "sorry",
        "actually",
        "i",
        "mean",
        "meant",
        "rather",
        "correction",
        ",",
        "oh",
        "oops",
        "um",
    }
)


def prepare(sentences: list[list[Word]]) -> list[list[Word]]:
    """``sentences`` with run-ons split and what is said around the request set aside
    (see the module docstring)."""
    sentences = [from_then_look(ordinal_along(end_toward(need_after_deed(s)))) for s in sentences]
    sentences = [non_words(without_run_out(without_no_idea(floor_asked(s)))) for s in sentences]
    sentences = [without_failed_condition(without_manner(without_no_longer(s))) for s in sentences]
    sentences = [set_aside_first(without_trailing_caution(which_of_is(s))) for s in sentences]
    sentences = [owner_side(only_thing(without_noticing_remark(s))) for s in sentences]
    sentences = [thing_that_does(stranded_relative(chore_at_place(s))) for s in sentences]
    sentences = [besides_as_beside(s) for s in without_remarks_on_others(sentences)]
    sentences = [
        whose_as_with(without_sign_negation(another_as_one_more(without_moved_away(s))))
        for s in sentences
    ]
    sentences = [_instrument_asked(_errand_of_caution(sentence)) for sentence in sentences]
    sentences = [_after_but_it_is(_without_hedged_guess(sentence)) for sentence in sentences]
    sentences = [_without_contact_clause(_view_then_it(sentence)) for sentence in sentences]
    sentences = [part for sentence in sentences for part in _split_run_on(sentence)]
    sentences = [part for sentence in sentences for part in _split_placed_by_it(sentence)]
    sentences = [_without_rhetorical_not(_without_vocative(s)) for s in sentences]
    sentences = _without_cautions(_without_asides(_without_letter_frame(sentences)))
    return without_personal_asides(sentences)


# Verbs of choosing or fetching: "don't bring the red bag" rules a thing out; any other
# verb after "don't" ("don't wake the baby", "don't drop the vase") is a caution.
_CHOOSING = frozenset({"want", "need", "like", "use", "mean", "choose", "pick"})
# Words that open the errand a caution goes with ("… when you grab the diaper bag").
_WHEN = frozenset({"when", "after", "before", "while", "as", "once"})
_ERRAND_OF_CAUTION = frozenset({"move", "carry", "put", "clean", "pick", "bring", "get", "grab",
                                "fetch", "take"})  # fmt: skip


# Words that ask for a thing in "what can I use to …", "anything I could use to …".
_ASKING_WORDS = frozenset({"what", "anything", "something", "is", "there", "can", "could",
                           "should", "would", "might", "do", "i", "we", "one", "you"})  # fmt: skip
_SOMETHING = Word("something", "something", "PRON", "NN")


def _instrument_asked(sentence: list[Word]) -> list[Word]:
    """ "what can I use to open this bottle of wine", "is there anything I could use to
    reach the top shelf" as "something to open this bottle of wine": the thing used is
    sought, not the thing it acts on."""
    for k in range(1, min(len(sentence) - 2, 7)):
        if sentence[k].lemma != "use" or sentence[k + 1].text != "to":
            continue
        if sentence[k + 2].tag != "VB" or not all(w.text in _ASKING_WORDS for w in sentence[:k]):
            return sentence
        if not any(w.text in ("what", "anything", "something") for w in sentence[:k]):
            return sentence
        return [_SOMETHING, *sentence[k + 1 :]]
    return sentence


def _caution_verb(sentence: list[Word]) -> int | None:
    """Where the verb of a caution that opens ``sentence`` is ("don't wake the baby",
    "please never drop the vase"), or None when it opens otherwise or the verb chooses
    or fetches ("don't bring the red bag" rules the red bag out)."""
    i = 1 if sentence and sentence[0].text == "please" else 0
    texts = [w.text for w in sentence]
    if texts[i : i + 2] == ["do", "not"]:
        i += 2
    elif texts[i : i + 1] == ["never"]:
        i += 1
    else:
        return None
    if i >= len(sentence) or sentence[i].pos not in ("VERB", "AUX"):
        return None
    if sentence[i].lemma in _CHOOSING or sentence[i].lemma in FETCH_VERBS:
        return None
    return i


def _errand_of_caution(sentence: list[Word]) -> list[Word]:
    """A caution said with the errand it goes with ("don't wake the baby when you grab
    the diaper bag", "don't forget to close the fridge after you take the juice") as the
    errand alone; "it" in the errand is the caution's thing ("please don't drop the vase
    when you bring it" → "bring the vase")."""
    verb = _caution_verb(sentence)
    if verb is None:
        return sentence
    for j in range(verb + 1, len(sentence) - 2):
        if sentence[j].text not in _WHEN or sentence[j + 1].text not in ("you", "u", "i"):
            continue
        k = j + 2
        while k < len(sentence) and sentence[k].pos == "ADV":
            k += 1
        if k >= len(sentence) or sentence[k].lemma not in _ERRAND_OF_CAUTION:
            return sentence
        errand = sentence[k:]
        if len(errand) > 1 and errand[1].text in IT_WORDS:
            thing = _thing_of(sentence[verb + 1 : j])
            if not thing:
                return sentence
            return [errand[0], *thing, *errand[2:]]
        return errand
    return sentence


def _thing_of(words: list[Word]) -> list[Word]:
    """The noun phrase a caution's verb takes ("the vase" of "drop the vase"): from its
    first determiner, adjective or noun to its last noun."""
    start = next((k for k, w in enumerate(words) if w.pos in ("DET", "ADJ", "NOUN")), None)
    if start is None:
        return []
    end = max((k for k, w in enumerate(words) if w.pos in ("NOUN", "PROPN")), default=-1)
    return words[start : end + 1] if end >= start else []


def _without_cautions(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request without a caution before an errand about another thing ("don't wake
    the baby, just get her bottle", "don't be shy, bring the whole box"): the caution
    rules nothing out, and "it" in the errand is the caution's thing ("… get the remote
    off it"). Kept when the errand names the caution's thing again or says "one" ("don't
    touch the blue mug, take the red one")."""
    out: list[list[Word]] = []
    sentences = list(sentences)  # (a next sentence may be reworded below)
    for n, sentence in enumerate(sentences):
        verb = _caution_verb(sentence)
        nxt = sentences[n + 1] if n + 1 < len(sentences) else []
        if verb is not None and nxt and _errand_of_another(nxt, sentence[verb + 1 :]):
            sentences[n + 1] = _it_as_cautioned(nxt, sentence[verb + 1 :])
            continue
        if verb is not None and (errand := _errand_run_on(sentence, verb)) is not None:
            out.append(errand)  # "dont worry about the dishes just find the cat food"
            continue
        out.append(_without_trailing_caution(sentence))
    return out


def _errand_run_on(sentence: list[Word], verb: int) -> list[Word] | None:
    """The errand a caution runs on into ("don't worry about the dishes just find the
    cat food" → "find the cat food"), or None. Not after a verb of going ("don't go into
    the garage, get …" keeps out of the garage), nor when the errand takes "one" or the
    cautioned thing again ("don't touch the blue mug, take the red one")."""
    if sentence[verb].lemma in lexicon().viewpoint_verbs:
        return None
    for j in range(verb + 2, len(sentence) - 1):
        if sentence[j].text not in _ERRAND_LINKS and sentence[j] is not COMMA:
            continue
        k = j + 1
        while k < len(sentence) and sentence[k].text in _ERRAND_LINKS:
            k += 1
        if _it_is_the(sentence, k):
            return sentence[k:]  # "dont mind the mess, its the desk by the window"
        if k >= len(sentence) - 1 or sentence[k].lemma not in _SEEKING:
            continue
        errand = sentence[k:]
        if sentence[k].tag not in ("VB", "VBP"):
            return None
        cautioned = sentence[verb + 1 : j]
        return _it_as_cautioned(errand, cautioned) if _names_another(errand, cautioned) else None
    return None


def _it_as_cautioned(errand: list[Word], cautioned: list[Word]) -> list[Word]:
    """``errand`` with "it" / "them" after a preposition read as the thing the caution
    named ("don't bump the table, just get the remote off it" → "… off the table")."""
    thing = _thing_of(cautioned)
    if not thing:
        return errand
    out: list[Word] = []
    for k, word in enumerate(errand):
        if word.text in ("it", "them") and k > 0 and errand[k - 1].pos == "ADP":
            out.extend(thing)
        else:
            out.append(word)
    return out


def _it_is_the(sentence: list[Word], k: int) -> bool:
    """Whether "it is the …" / "it is a …" starts at ``k``."""
    texts = [w.text for w in sentence[k : k + 3]]
    return texts[:2] == ["it", "is"] and len(texts) == 3 and texts[2] in ("the", "a", "an")


def _negated_verb(sentence: list[Word], k: int) -> bool:
    """Whether "not" at ``k`` negates a verb after an auxiliary ("can not see")."""
    return (
        sentence[k].text == "not"
        and sentence[k - 1].pos == "AUX"
        and sentence[k + 1].pos in ("VERB", "AUX")
    )


def _after_but_it_is(sentence: list[Word]) -> list[Word]:
    """A remark of what cannot be seen or told, then "but it's the …" ("you cant see its
    legs from here but its the table in the middle", "I cant tell what color it is but
    its the pillow on the left"): the description after "but" alone."""
    for j, word in enumerate(sentence):
        if word.text == "but" and _it_is_the(sentence, j + 1):
            if any(_negated_verb(sentence, k) for k in range(1, j - 1)):
                return sentence[j + 1 :]
            return sentence
    return sentence


# Openings of a guess at what a thing is made of or coloured, after a comma: "…, might be
# laminate", "…, or maybe acrylic idk".
_GUESSES = (("might", "be"), ("may", "be"), ("could", "be"), ("or", "maybe"), ("maybe",),
            ("probably",), ("possibly",), ("or", "possibly"), ("or", "probably"))  # fmt: skip
_UNSURE = frozenset({"idk", "dunno", "not", "sure", "i", "think", "guess", "or", "something"})


def _without_hedged_guess(sentence: list[Word]) -> list[Word]:
    """A thing named, then a guess at its material or colour after a comma ("the
    wooden-ish stool, might be laminate", "the glass-topped table, or maybe acrylic
    idk"): the guess is left out (up to the next comma), so that its word is not read
    as the thing sought."""
    for k, word in enumerate(sentence):
        if word is not COMMA or not any(w.pos == "NOUN" for w in sentence[:k]):
            continue
        texts = [w.text for w in sentence[k + 1 :]]
        opening = next((g for g in _GUESSES if tuple(texts[: len(g)]) == g), None)
        if opening is None:
            continue
        end = next((j for j, t in enumerate(texts) if t == ","), len(texts))
        guess = sentence[k + 1 + len(opening) : k + 1 + end]
        if guess and all(
            w.pos in ("ADJ", "ADV", "CCONJ") or w.text in _UNSURE or colour_or_material(w.text)
            for w in guess
        ):
            return sentence[:k] + sentence[k + 1 + end :]
    return sentence


def _view_then_it(sentence: list[Word]) -> list[Word]:
    """ "from the doorway it's the far left cabinet": the place seen from, then the
    thing, with no comma between them; a comma is put in, as "from the doorway, it's …"
    reads."""
    if len(sentence) < 5 or sentence[0].text != "from" or sentence[1].pos != "DET":
        return sentence
    for k in range(2, min(len(sentence) - 1, 6)):
        word = sentence[k]
        if word.text in ("it", "there") and sentence[k + 1].lemma == "be":
            return [*sentence[:k], COMMA, *sentence[k:]] if k > 2 else sentence
        if word.text == "its" and sentence[k + 1].pos == "DET" and k > 2:
            return [*sentence[:k], COMMA, IT, IS, *sentence[k + 1 :]]  # "its teh …"
        if word.pos not in ("ADJ", "NOUN", "PROPN"):
            return sentence
    return sentence


def _without_contact_clause(sentence: list[Word]) -> list[Word]:
    """ "the one the kids use", "the one my dad sits in": a relative clause without "that"
    after "one", whose subject someone else is, says whose or what for, not what the
    thing is; left out (up to the next comma), so that its subject is not read as the
    thing sought. "the one I mean" stays (it says which is meant)."""
    for k, word in enumerate(sentence[:-2]):
        if word.text not in ("one", "ones"):
            continue
        j = k + 1
        if sentence[j].text in _SUBJECT_DETERMINERS:
            j += 1
        if j >= len(sentence) or sentence[j].pos not in ("NOUN", "PROPN"):
            continue
        j += 1
        if j >= len(sentence) or sentence[j].pos != "VERB" or sentence[j].tag not in FINITE:
            continue
        end = next((i for i in range(j, len(sentence)) if sentence[i] is COMMA), len(sentence))
        clause = sentence[j + 1 : end]
        if any(w.pos == "ADP" and n.pos in ("DET", "NOUN", "PROPN") for w, n in pairwise(clause)):
            continue  # "the red one Dave left in the garage": where it is
        return sentence[: k + 1] + sentence[end:]
    return sentence


# Determiners of the subject of a relative clause without "that" ("the one the kids
# use", "the one my dad sits in"); not "any" ("the red one any umbrella works").
_SUBJECT_DETERMINERS = frozenset({"the", "my", "our", "his", "her", "their", "your"})


def _without_trailing_caution(sentence: list[Word]) -> list[Word]:
    """A thing named, then a caution after a comma ("chainsaw on the top shelf of the
    shed, dont touch the chain", "the snow shovel is by the side door, dont trip over
    it"): the caution rules nothing out and is left out, up to the next comma. Kept when
    it says "one" ("…, don't touch the red one")."""
    for k, word in enumerate(sentence):
        if word is not COMMA or not any(w.pos == "NOUN" for w in sentence[:k]):
            continue
        rest = sentence[k + 1 :]
        verb = _caution_verb(rest)
        if verb is None or any(w.text in ("one", "ones") for w in rest):
            continue
        end = next((j for j in range(verb, len(rest)) if rest[j] is COMMA), len(rest))
        return sentence[:k] + rest[end:]
    return sentence


def _errand_of_another(errand: list[Word], cautioned: list[Word]) -> bool:
    """Whether ``errand`` fetches a thing other than the ``cautioned`` words name."""
    i = 0
    while i < len(errand) and (errand[i].text in _ERRAND_LINKS or errand[i].text == ","):
        i += 1
    if i >= len(errand) or errand[i].lemma not in FETCH_VERBS:
        return False
    return _names_another(errand[i:], cautioned)


def _names_another(errand: list[Word], cautioned: list[Word]) -> bool:
    """Whether an errand (from its verb) names a thing other than the ``cautioned`` words
    name, and says no "one" ("take the red one" is the cautioned kind again)."""
    if any(w.text in ("one", "ones") for w in errand):
        return False
    head = _first_head(errand[1:])
    return head is not None and head != _first_head(cautioned)


def _first_head(words: list[Word]) -> str | None:
    """The lemma of the last noun of the first run of nouns in ``words`` ("monitor" of
    "the baby monitor from the nursery")."""
    head = None
    for w in words:
        if w.pos in ("NOUN", "PROPN") or (w.pos == "ADJ" and canonical_label(w.text)):
            head = w.lemma  # ("remote" is tagged an adjective)
        elif head is not None:
            break
    return head


# Verbs between a place put first and the thing it places ("to the right of it is a
# paper cutter", "on the desk there's a laptop").
_INVERTED_VERBS = frozenset({"be", "sit", "stand", "hang", "lie", "rest"})


def place_after_thing(sentence: list[Word]) -> list[Word]:
    """A later sentence that puts the place first ("to the right of it is a paper
    cutter", "under it the radiator, painted white", "on top of it there's a box") in the
    order the grammar reads: the thing, then its place ("a paper cutter to the right of
    it"). Only where the place points back at something said before ("it") or names a
    thing ("above the counter on the wall is the paper towel dispenser"). A participle of
    position may open it ("hanging from it is an umbrella")."""
    first = 1 if len(sentence) > 1 and _position_participle(sentence[0]) else 0
    if len(sentence) < 4 + first or sentence[first].pos != "ADP":
        return sentence
    k = first + 1
    while k < len(sentence):
        word, before = sentence[k], sentence[k - 1]
        if word.text == "there" or (word.lemma in _INVERTED_VERBS and word.pos in ("AUX", "VERB")):
            break
        if word.text in ("a", "an") or (
            word.text == "the" and before.pos in ("PRON", "NOUN", "PROPN")
        ):
            break
        if word.text == ",":
            return sentence
        k += 1
    place = sentence[:k]
    if k >= len(sentence) - 1 or not any(w.pos in ("PRON", "NOUN") for w in place):
        return sentence
    start = k
    while start < len(sentence) and (
        sentence[start].text == "there"
        or (sentence[start].lemma in _INVERTED_VERBS and sentence[start].pos in ("AUX", "VERB"))
    ):
        start += 1
    end = start
    while end < len(sentence) and sentence[end].text not in (",", "and"):
        end += 1
    thing = sentence[start:end]
    if not any(w.pos in ("NOUN", "PROPN") for w in thing):
        return sentence
    return [*thing, *place, *sentence[end:]]


def _position_participle(word: Word) -> bool:
    """ "hanging", "sitting", "stacked", "mounted": how a thing is placed."""
    return word.tag in ("VBG", "VBN") and word.lemma in _POSITION_LEMMAS


_POSITION_LEMMAS = _INVERTED_VERBS | {"mount", "stack", "prop", "tuck", "lean", "perch", "pin"}


# Words that may open a spoken correction before its "not" ("no no not the kettle …").
_CORRECTION_FILLERS = frozenset(
    {"no", "nope", "nah", "wait", ",", "uh", "um", "umm", "oh", "ugh", "hmm", "ah", "er", "erm",
     "oops", "ok", "okay"}
)  # fmt: skip
# Words of a noun phrase between its determiner and the next one.
_NP_POS = frozenset({"ADJ", "NOUN", "PROPN", "NUM", "ADV"})


def comma_after_denied_thing(sentence: list[Word]) -> list[Word]:
    """A spoken correction with no comma ("not the kettle the toaster", as speech is
    transcribed) with the comma put back after the thing denied: "not the kettle, the
    toaster"."""
    i = 0
    while i < len(sentence) and sentence[i].text in _CORRECTION_FILLERS:
        i += 1
    if i + 2 >= len(sentence) or sentence[i].text != "not" or not _opens_phrase(sentence[i + 1]):
        return sentence
    j = i + 2
    while j < len(sentence) and sentence[j].pos in _NP_POS:
        j += 1
    if (
        j < len(sentence)
        and j > i + 2
        and _opens_phrase(sentence[j])
        and sentence[j - 1].pos in ("NOUN", "PROPN", "NUM")
    ):
        return [*sentence[:j], COMMA, *sentence[j:]]
    return sentence


def _opens_phrase(word: Word) -> bool:
    """Whether a word opens a noun phrase: a determiner or a possessive ("the", "my"), or
    "that" / "this" however spaCy read them ("not this bottle that bottle")."""
    return (word.pos in ("DET", "PRON") and word.tag in ("DT", "PRP$")) or word.text in (
        "this",
        "that",
        "these",
        "those",
    )


def denies_first(sentence: list[Word]) -> bool:
    """Whether a sentence opens by denying a thing ("not the lamp by the door", "anything
    but the mug with the chip"), not by a question or a statement that holds a "not"."""
    i = 0
    while i < len(sentence) and sentence[i].text in _CORRECTION_FILLERS:
        i += 1
    rest = sentence[i:]
    if len(rest) >= 2 and rest[0].text == "not" and _opens_phrase(rest[1]):
        return True
    return (
        len(rest) >= 3
        and rest[0].text in ("anything", "everything", "any")
        and rest[1].text in ("but", "except")
        and _opens_phrase(rest[2])
    )


def denial_then_choice(sentences: list[list[Word]]) -> list[list[Word]]:
    """A denied thing said on its own, then the thing meant ("NO. not the blue pen. the
    black pen.") as one sentence: "not the blue pen, the black pen"."""
    out: list[list[Word]] = []
    for sentence in sentences:
        if out and _only_denial(out[-1]) and sentence and _opens_phrase(sentence[0]):
            out[-1] = [*out[-1], COMMA, *sentence]
        else:
            out.append(sentence)
    return out


def _only_denial(sentence: list[Word]) -> bool:
    """Whether a sentence only denies a thing ("not the blue pen"): "not", a noun phrase,
    no verb."""
    i = 0
    while i < len(sentence) and sentence[i].text in _CORRECTION_FILLERS:
        i += 1
    rest = sentence[i:]
    return (
        len(rest) >= 3
        and rest[0].text == "not"
        and _opens_phrase(rest[1])
        and all(w.pos not in ("VERB", "AUX") for w in rest)
        and COMMA not in rest
    )


# What a speaker says before repeating the thing meant ("i said the thermometer").
_REPEATING = frozenset({"said", "mean", "meant", "asked", "wanted"})


# Words that may come before "I meant": apologies and fillers ("oops typo i meant …").
_BEFORE_REPEATING = _CORRECTION_FILLERS | {"sorry", "actually", "oops", "typo", "correction"}


def without_repeating(sentence: list[Word]) -> list[Word]:
    """A first sentence without the "I said" / "I meant" that opens it before the thing
    ("i said the thermometer not the blood pressure cuff", "sorry i meant the
    thermometer", "oops typo i meant mouse pad")."""
    i = 0
    while i < len(sentence) and sentence[i].text in _BEFORE_REPEATING:
        i += 1
    rest = sentence[i:]
    repeating = len(rest) > 2 and rest[0].text == "i" and rest[1].text in _REPEATING
    if repeating and (_opens_phrase(rest[2]) or rest[2].pos in ("NOUN", "ADJ", "PROPN")):
        return rest[2:]
    return sentence


# Verbs whose object is a thing to carry to the speaker ("bring the juice").
FETCH_VERBS = frozenset({"bring", "get", "grab", "fetch", "pass", "hand", "take"})
# Verbs of an errand that may follow a caution in the same sentence.
_SEEKING = FETCH_VERBS | {"find", "locate", "check"}
# Words before a noun that make it one particular thing ("the juice", "my tea").
PARTICULAR = frozenset({"the", "my", "your", "our", "his", "her", "their", "this", "that"})


def fetches_particular(sentence: list[Word], noun: str) -> bool:
    """Whether ``sentence`` asks to fetch one particular ``noun`` ("bring me the juice",
    "so grab the tea", "get a soda from the fridge"), not a kind of thing for a purpose
    ("get a drink"): a verb of fetching, then "the" / a possessive, or a source after."""
    last = noun.split()[-1] if noun.strip() else ""
    at = next((k for k, w in enumerate(sentence) if w.text == last), None)
    if at is None:
        return False
    k = at - len(noun.split())
    while (
        k >= 0 and sentence[k].pos in ("ADJ", "NUM", "ADV") and sentence[k].text not in PARTICULAR
    ):
        k -= 1
    opener = sentence[k].text if k >= 0 else ""
    k -= 1
    if k >= 0 and sentence[k].text in ("me", "us"):
        k -= 1
    if k < 0 or sentence[k].lemma not in FETCH_VERBS:
        return False
    return opener in PARTICULAR or any(w.text == "from" for w in sentence[at + 1 :])


def _split_run_on(sentence: list[Word]) -> list[list[Word]]:
    """A statement run on into a request with no stop between them ("the wifi is down
    can you check the router", as speech is transcribed) as two sentences: split before
    "can / could / would / will you" where a finite verb came before."""
    for j in range(2, len(sentence) - 2):
        word = sentence[j]
        if word.tag != "MD" or sentence[j + 1].text != "you" or sentence[j - 1] is COMMA:
            continue
        before = sentence[:j]
        if before[0].text in QUESTION_OPENERS or before[-1].text in QUESTION_OPENERS:
            continue  # "where can you …", "the place where can you …"
        if _has_clause(before):
            return [before, sentence[j:]]
    return _split_before_errand(sentence)


def _split_placed_by_it(sentence: list[Word]) -> list[list[Word]]:
    """Two statements joined by "and", the second placing another thing by "it" ("the
    sink is in the middle of it and the stove is to its right"), as two sentences: each
    thing is placed by "it" on its own. Not after "there is …" ("there's a printer and
    the shredder is to the left of it"), which sets the scene for either thing."""
    if sentence[0].text == "there":
        return [sentence]
    for j in range(2, len(sentence) - 3):
        if sentence[j].text != "and" or sentence[j + 1].text not in ("the", "a", "an"):
            continue
        after = sentence[j + 1 :]
        verb = next((k for k, w in enumerate(after) if w.tag in FINITE), None)
        if verb is None or not any(w.pos in ("NOUN", "PROPN") for w in after[:verb]):
            continue
        before = sentence[:j]
        fragment = not any(w.tag in FINITE or w.tag == "MD" for w in before) and any(
            w.pos == "ADP" for w in before[1:]
        )  # "shower in the corner of the bathroom and the towel … next to it is blue"
        if any(w.text in ("it", "them") for w in after) and (_has_clause(before) or fragment):
            return [before, after]
    return [sentence]


def _has_clause(words: list[Word]) -> bool:
    """Whether ``words`` hold a clause of their own: a finite verb, or a modal after its
    subject ("it won't turn on", "the kids can't reach the cereal"; not "can you")."""
    for k, w in enumerate(words):
        if w.pos in ("VERB", "AUX") and w.tag in FINITE:
            return True
        if w.tag == "MD" and k > 0 and words[k - 1].dep == "nsubj" and words[k - 1].text != "you":
            return True
    return False


# Verbs of an errand that may follow a statement with no stop ("there's no milk left so
# bring the juice", "don't worry about the mess bring the vacuum").
_ERRAND_VERBS = frozenset({"bring", "get", "grab", "fetch", "take", "find", "use", "check"})
# Words that join a statement to the errand that follows it.
_ERRAND_LINKS = frozenset({"so", "just", "then", "instead"})


def _split_before_errand(sentence: list[Word]) -> list[list[Word]]:
    """A statement run on into an errand ("the coffee machine isn't working so bring the
    kettle", "it won't turn on bring me a spare battery") as two sentences: split before
    the errand's verb (and "so" / "just" before it) where a finite verb came before."""
    for j in range(2, len(sentence) - 1):
        word = sentence[j]
        if word.lemma not in _ERRAND_VERBS or word.tag != "VB" or word.text != word.lemma:
            continue
        k = j
        while k > 0 and sentence[k - 1].text in _ERRAND_LINKS | {"um", "uh", "like"}:
            k -= 1
        if k < 2 or sentence[k - 1].text in (",", "and", "or", "to", "please", "you", "not"):
            continue  # "to get", "and bring", "could you just grab"
        if sentence[k - 1].tag == "MD" or sentence[k - 1].lemma in ("go", "come", "do"):
            continue  # "can bring", "go get", "do get"
        if sentence[j + 1].text in IT_WORDS:
            continue  # "… need washing, so bring that one": the errand is about what was said
        before = sentence[:k]
        if before[0].text in QUESTION_OPENERS or any(w.lemma in _ERRAND_VERBS for w in before):
            continue  # "don't bring the red bag bring the black one": one errand, corrected
        if _has_clause(before):
            return [before, sentence[k:]]
    return [sentence]


def _without_vocative(sentence: list[Word]) -> list[Word]:
    """The sentence without a name it opens by calling, with no comma after it ("mommy
    I can't find my toothbrush", "honey can you grab the towel"): a bare noun that names
    no known thing or room, followed by "I" / "we" or "can you"."""
    if len(sentence) < 3 or sentence[0].pos not in ("NOUN", "PROPN"):
        return sentence
    nxt, after = sentence[1], sentence[2]
    if not (nxt.text in ("i", "we") or (nxt.tag == "MD" and after.text == "you")):
        return sentence
    word = sentence[0].text
    if canonical_label(word) is not None or room_type(word) is not None:
        return sentence  # "kitchen can you …" keeps its room
    return sentence[1:]


def _aside(part: list[Word]) -> bool:
    """Whether words that open a request only set something aside ("No towels
    required.", "No price changes today", "Don't worry about the paperwork"): "no"
    and a noun with no finite verb after, or "do not worry about …"."""
    texts = [w.text for w in part]
    if texts[:4] == ["do", "not", "worry", "about"]:
        return True
    if len(part) < 2 or texts[0] != "no" or part[0].pos != "DET" or part[1].pos != "NOUN":
        return False
    if texts[1] in CORRECTION_WORDS or texts[1] in ("one", "ones"):
        return False  # "no wait, the blue one" corrects; "no one's using the projector"
    return not any(
        w.tag in FINITE and w.lemma not in _NEEDING for w in part[2:]
    )  # "No towels required."


# How a speaker opens by saying what they do not know or mind ("no idea which aisle but
# find the batteries", "it doesn't matter which colour, just get a pen").
_UNSURE_OPENERS = (
    ("no", "idea"), ("no", "clue"), ("not", "sure"), ("i", "am", "not", "sure"),
    ("i", "do", "not", "know"), ("dunno",), ("it", "does", "not", "matter"),
    ("no", "worries"), ("on", "second", "thought"),
    ("can", "not", "miss", "it"), ("you", "can", "not", "miss", "it"),
    ("it", "is", "not", "hard"), ("it", "is", "not", "difficult"),
)  # fmt: skip
# Words that only strengthen an opening ("not 100% sure", "not entirely sure").
_INTENSIFIERS = frozenset({"100", "%", "percent", "totally", "entirely", "completely", "quite",
                           "really", "exactly", "too", "so"})  # fmt: skip
# Nouns of a request that name no thing ("can you have a look").
_LIGHT_NOUNS = frozenset({"look", "try", "go", "check", "hand", "favour", "favor", "sec", "minute"})
# Words after which the request itself begins.
_REQUEST_RESUMES = frozenset({"but", "just", "so", ","})


def _after_unsure(sentence: list[Word]) -> int | None:
    """Where the request starts after an opening that says what the speaker does not
    know or mind, up to "but" / "just" / "so" / a comma ("not sure if it's still there
    but check the counter for my watch"); "on second thought" needs none. None when the
    sentence opens otherwise or nothing follows."""
    texts = [w.text for w in sentence]
    found = _unsure_opening(sentence)
    if found is None:
        return None
    opener, after = found
    if opener == ("on", "second", "thought"):
        start = after + (texts[after : after + 1] == [","])
        return start if start < len(sentence) else None
    for j in range(after, len(sentence) - 1):
        if texts[j] in _REQUEST_RESUMES:
            rest = sentence[j + 1 :]
            # the request names its own thing ("… but find the batteries"), not one the
            # opening named ("no idea where the tv remote went, help", "… can you find it")
            own = any(w.pos in ("NOUN", "PROPN") and w.text not in _LIGHT_NOUNS for w in rest)
            return j + 1 if own and not _points_back(rest) else None
    return None


_ONE = frozenset({"one", "ones"})


def _unsure_opening(sentence: list[Word]) -> tuple[tuple[str, ...], int] | None:
    """The opening of :data:`_UNSURE_OPENERS` a sentence starts with, read past words
    that only strengthen it ("not 100% sure"), and where the words after it start."""
    kept = [j for j, w in enumerate(sentence) if j == 0 or w.text not in _INTENSIFIERS]
    opening = tuple(sentence[j].text for j in kept)
    opener = next((o for o in _UNSURE_OPENERS if opening[: len(o)] == o), None)
    return None if opener is None else (opener, kept[len(opener) - 1] + 1)


def _only_unsure(sentence: list[Word], following: list[Word]) -> bool:
    """Whether a sentence only says what the speaker is unsure of ("not 100% sure.",
    "not sure of the colour" before "but it's the lamp …")."""
    found = _unsure_opening(sentence)
    if found is None:
        return False
    if all(w.text in _INTENSIFIERS for w in sentence[found[1] :]):
        return True
    if not following or following[0].text not in ("but", "so", "just"):
        return False
    # the request names its own thing ("… but it's the lamp by the bed"), not only "the
    # wooden one" after "not sure if it's a dresser or a cabinet"
    head = next((w for w in following if w.pos in ("NOUN", "PROPN") or w.text in _ONE), None)
    return head is not None and head.text not in _ONE and head.text not in _LIGHT_NOUNS


def _points_back(words: list[Word]) -> bool:
    """Whether ``words`` speak of a thing said before ("can you find it", "it's on the
    round table"); "it is the tall lamp" names its own."""
    for k, w in enumerate(words):
        if w.text not in IT_WORDS:
            continue
        if not (k + 1 < len(words) and words[k + 1].lemma == "be"):
            return True
        j = k + 2
        while j < len(words) and words[j].pos == "ADV":
            j += 1  # "it's right next to …"
        if j < len(words) and words[j].pos == "ADP":
            return True  # placed, not named: the thing is the one said before
    return False


def _without_asides(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request without the asides that open it, as a sentence of their own ("No
    signature needed. Take the post trolley …") or before a comma ("No price changes
    today; only move the A-board …"), when a request follows."""
    out: list[list[Word]] = []
    for n, sentence in enumerate(sentences):
        cut = next((j for j, w in enumerate(sentence) if w is COMMA), None)
        unsure = _after_unsure(sentence)
        if unsure is not None:
            out.append(sentence[unsure:])
        elif cut is not None and cut + 1 < len(sentence) and _aside(sentence[:cut]):
            out.append(sentence[cut + 1 :])
        elif n + 1 < len(sentences) and (
            _aside(sentence) or _only_unsure(sentence, sentences[n + 1])
        ):
            continue  # "No signature needed.", "not 100% sure. but …"
        else:
            out.append(sentence)
    return out


_GREETINGS = frozenset({"hi", "hello", "hey", "dear", "morning", "afternoon", "evening", "good"})
_SIGN_OFFS = frozenset(
    {"thanks", "thank", "cheers", "regards", "best", "many", "kind", "ta", "love"}
)


def _introduction_end(sentence: list[Word]) -> int | None:
    """Where a speaker's opening self-introduction ends (the comma after it): "sam here,
    …", "mum here, …", "hi robot its maria the cleaner, …", "hey, this is dan, …";
    None when the sentence opens otherwise or nothing follows the comma."""
    texts = [w.text for w in sentence]
    cut = next((j for j, t in enumerate(texts[:9]) if t == ","), None)
    if cut is None or cut + 1 >= len(sentence):
        return None
    head = texts[:cut]
    if 1 <= len(head) <= 2 and head[-1] == "here" and sentence[0].pos in ("PROPN", "NOUN"):
        return cut  # "sam here,"
    i = next((j for j, t in enumerate(head) if t not in _GREETINGS and t != "robot"), len(head))
    opening = 1 if head[i : i + 1] == ["its"] else 2
    if i and (opening == 1 or head[i : i + 2] in (["it", "is"], ["this", "is"], ["i", "am"])):
        named = sentence[i + opening : cut]
        if named and (_a_name(named[0]) or named[0].text in lexicon().seekers):
            return cut  # "hi robot its maria the cleaner,"
    return None


def _a_name(word: Word) -> bool:
    """Whether ``word`` reads as a person's name: a proper noun, or a noun that names no
    kind of thing ("maria" lower case)."""
    return word.pos == "PROPN" or (word.pos == "NOUN" and canonical_label(word.text) is None)


def _without_letter_frame(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request without the greeting and sign-off of a message ("Hi Sam, can you grab
    the laptop from my desk? Cheers, Mark"): a greeting and up to three words before a
    comma, and a short last sentence of thanks."""
    if not sentences:
        return sentences
    first = sentences[0]
    if (cut := _introduction_end(first)) is not None:
        sentences = [first[cut + 1 :], *sentences[1:]]  # "sam here, …", "hi, it's maria, …"
    elif first and first[0].text in _GREETINGS:
        cut = next((j for j, w in enumerate(first[:5]) if w is COMMA), None)
        if cut is not None and cut + 1 < len(first):
            sentences = [first[cut + 1 :], *sentences[1:]]
        elif cut is None and len(first) <= 3 and len(sentences) > 1:
            sentences = sentences[1:]  # "Hi team." / "Good morning."
    last = sentences[-1]
    if len(sentences) > 1 and last and last[0].text in _SIGN_OFFS and len(last) <= 6:
        sentences = sentences[:-1]  # "Thanks, Jen", "Many thanks, Sister Adeyemi"
    return sentences


# Auxiliaries that open a question asking for a yes ("doesn't the bathroom have …",
# "shouldn't there be …"), and the subjects after their "not".
_ASKING_AUX = frozenset({"do", "should", "would", "could", "can", "will", "have", "shall", "must"})
_ASKED_SUBJECTS = frozenset({"the", "there", "we", "you", "they", "my", "our", "this", "that"})


def _without_rhetorical_not(sentence: list[Word]) -> list[Word]:
    """A question that asks for a yes ("Is it not the blue bowl?", "Was that not the
    lamp by the window?", "isn't this the washing machine?", "is the stove not turned
    off?", "isn't there a fire extinguisher in the garage", "isn't the cereal in the
    pantry?", "doesn't the bathroom have a hair dryer", "shouldn't there be a fire
    blanket", "don't we have a ladder") without its "not": "is it not X" asks whether it
    is X."""
    asking = len(sentence) >= 4 and sentence[0].pos == "AUX" and sentence[0].lemma in _ASKING_AUX
    if asking and sentence[1].text == "not" and sentence[2].text in _ASKED_SUBJECTS:
        return [sentence[0], *sentence[2:]]  # "doesn't the bathroom have …"
    if len(sentence) < 4 or sentence[0].lemma != "be" or sentence[0].pos != "AUX":
        return sentence
    if sentence[1].text in IT_WORDS and sentence[2].text == "not":
        return [*sentence[:2], *sentence[3:]]
    if sentence[1].text == "not" and sentence[2].text in IT_WORDS | {"there"}:
        return [sentence[0], *sentence[2:]]  # "isn't it the lamp …?", "isn't there a …"
    placed = any(w.pos == "ADP" for w in sentence[3:])
    if sentence[1].text == "not" and sentence[2].text == "the" and len(sentence) > 4 and placed:
        return [sentence[0], *sentence[2:]]  # "isn't the cereal in the pantry?"
    k = 1  # "is the stove not turned off?": the thing, then "not"
    while k < min(len(sentence), 6) and sentence[k].pos in ("DET", "ADJ", "NOUN", "PROPN"):
        k += 1
    if 2 < k < len(sentence) - 1 and sentence[k].text == "not":
        return [*sentence[:k], *sentence[k + 1 :]]
    return sentence
