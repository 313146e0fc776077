"""Sentences said in a form the grammar does not read, put in the plain form it reads.

- A side that belongs to a thing ("the lamp to its right", "the bin on the desk's left
  side") is a side of that thing ("to the right of it"), not the speaker's left or
  right, and not the leftmost of a row.
- "nothing else on that shelf but the tissue box", "nothing much in this room except a
  mattress" say that only that thing is there: the thing, in that place ("on that shelf,
  the tissue box"); the place is not ruled out.
- A remark on what the speaker did not notice or see ("never noticed it before, but …",
  "I don't see any other plants, it's the tall one …") rules nothing out: it is dropped.
- So does a remark that the target is the only one of its kind or that little else is
  there ("no other chair in the room has wheels", "None of the other lamps are this
  tall.", "there is nothing else on the desk", "There isn't much in the hallway",
  "It's not a big room."): it is dropped when the request says more.
- "never mind the first message, find my wallet instead", "nvm, found it": what is
  called off is no longer asked for; it is dropped, not ruled out.
- "move the bike away from the car", "the chair pushed away from the table": where a
  thing is moved to, not a place it is not near.
- "no clue where the flashlight is", "no idea where my keys went": the thing asked
  about, with nothing ruled out.
- "no ice left in the freezer so grab the cold pack", "there's nothing in the fridge so
  can you check the freezer": what has run out before a request for another thing is
  no thing ruled out; the opening is dropped.
- "can I have another towel" asks for one more, not for a different one.
- "non-stick", "non-slip": one adjective of its own; "non-wooden" still negates a
  material.
- "the sign that says no smoking": the words on a thing are no negation.
- "besides" written for "beside" between two things ("the magazine rack besides the
  armchair") places the first by the second; "any chair besides the red one" still
  rules one out.
- "the wardrobe whose doors aren't mirrored": a part and its quality ("without mirrored
  doors").
- "leave the heavy box and bring the small box", "forget the kitchen, check the grill":
  what is set aside before the errand is ruled out.
- "the shelf the TV sits on", "the box that the keys are in": a relative clause whose
  object is the thing sought, its preposition left at the end, reads as "the shelf with
  the TV on it".
- "the thing that plays the sound", "the machine that washes them": something to play
  the sound, something to wash them (a purpose, not the thing its verb acts on).
"""

from __future__ import annotations

from itertools import pairwise

from inherit_sg.nlp import known_lemma
from inherit_sg.retrieval.rules.functions import knows_verb
from inherit_sg.retrieval.rules.tokens import COMMA, IN, THE, A, Word
from inherit_sg.vocab.colours import colour_words
from inherit_sg.vocab.lexicon import lexicon
from inherit_sg.vocab.objects import canonical_label
from inherit_sg.vocab.rooms import room_type

_SIDE_PREPOSITIONS = frozenset({"to", "on", "at", "by"})
_SIDES = frozenset({"left", "right"})
_SIDE = Word("side", "side", "NOUN", "NN", "pobj")
_OF = Word("of", "of", "ADP", "IN", "prep")
_IT = Word("it", "it", "PRON", "PRP", "pobj")
_THEM = Word("them", "them", "PRON", "PRP", "pobj")
_OWNER_WORDS = frozenset({"DET", "ADJ", "NOUN", "PROPN", "NUM"})


def owner_side(sentence: list[Word]) -> list[Word]:
    """ "to its right", "on its left side", "to the bed's right" as "to the right side of
    it" / "… of the bed" (the words come with "its" read as "it is" and the possessive
    "'s" dropped, see :mod:`inherit_sg.retrieval.rules.tokens`)."""
    out: list[Word] = []
    i = 0
    while i < len(sentence):
        found = _owned_side_at(sentence, i)
        if found is None:
            out.append(sentence[i])
            i += 1
            continue
        owner, side, end = found
        out += [sentence[i], THE, side, _SIDE, _OF, *owner]
        i = end
    return out


def _owned_side_at(sentence: list[Word], i: int) -> tuple[list[Word], Word, int] | None:
    """The owner, the side word and the end of an owned side that starts with the
    preposition at ``i``; None when none starts there."""
    if sentence[i].text not in _SIDE_PREPOSITIONS or sentence[i].pos != "ADP":
        return None
    rest = sentence[i + 1 : i + 7]
    texts = [w.text for w in rest]
    if texts[:2] == ["it", "is"] and len(rest) > 2 and texts[2] in _SIDES:
        owner, k = [_IT], 2  # "on its left" (at times read as "on it is left")
    elif texts[:1] in (["its"], ["their"]) and len(rest) > 1 and texts[1] in _SIDES:
        owner, k = [_IT if texts[0] == "its" else _THEM], 1
    else:
        poss = next((j for j, w in enumerate(rest) if w.dep == "poss"), None)
        if poss is None or poss + 1 >= len(rest) or texts[poss + 1] not in _SIDES:
            return None
        if rest[poss].pos not in ("NOUN", "PROPN"):
            return None  # "to your right", "on my left": the speaker's side
        if any(w.pos not in _OWNER_WORDS for w in rest[:poss]):
            return None
        owner, k = [*rest[:poss], _as_object(rest[poss])], poss + 1
    side = rest[k]
    end = i + 1 + k + 1
    if end < len(sentence) and sentence[end].text == "hand":
        end += 1
    if end < len(sentence) and sentence[end].text == "side":
        end += 1
    return owner, side, end


def _as_object(word: Word) -> Word:
    """``word``, the owner in "the bed's right", as the object of "of"."""
    return Word(word.text, word.lemma, word.pos, word.tag, "pobj")


_NOTHING_ELSE = frozenset({"else", "much"})
_BUT = frozenset({"but", "except"})
_CLAUSE_ENDS = frozenset({",", ";", "and"})


def only_thing(sentence: list[Word]) -> list[Word]:
    """ "(there is) nothing else on that shelf but the tissue box, …" as "on that shelf,
    the tissue box, …": the one thing there, in its place."""
    texts = [w.text for w in sentence]
    if "nothing" not in texts:
        return sentence
    start = texts.index("nothing")
    after = start + 1
    while after < len(texts) and texts[after] in _NOTHING_ELSE:
        after += 1
    but = next((j for j in range(after, min(len(texts), after + 9)) if texts[j] in _BUT), None)
    if but is None or any(t in _CLAUSE_ENDS for t in texts[after:but]):
        return sentence
    skip = but + 2 if but + 1 < len(texts) and texts[but + 1] == "for" else but + 1
    before = sentence[:start]
    if [w.text for w in before[-2:]] == ["there", "is"]:
        before = before[:-2]  # "there's nothing … but X": X is there
    place = sentence[after:but]
    return [*before, *place, *([COMMA] if place else []), *sentence[skip:]]


_NOTICING = frozenset({"see", "notice", "spot", "remember", "know", "realise", "realize"})
_NEGATIONS = frozenset({"not", "never", "n't"})
_GONE = frozenset({"be", "go", "visit"})
_REMARK_OBJECTS = frozenset({"it", "them", "that", "this", "any", "anything", "another"})
_REMARK_ENDS = frozenset({",", "but", "so", ";"})


def without_noticing_remark(sentence: list[Word]) -> list[Word]:
    """The sentence without an opening remark on what the speaker did not notice or see
    ("never noticed it before but there's a small fan …", "I don't see any other
    plants, it's the tall one …") or where they have never been ("I've never been up in
    the attic, is there …"); unchanged when nothing follows the remark."""
    texts = [w.text for w in sentence]
    k = 1 if texts[:1] in (["i"], ["we"]) else 0
    while k < len(texts) and texts[k] in ("do", "did", "have", "had", "can", "could"):
        k += 1
    if k >= len(texts) or texts[k] not in _NEGATIONS:
        return sentence
    k += 1
    if k + 1 >= len(texts):
        return sentence
    # "I've never been up in the attic, is there a rocking horse up there?": where the
    # speaker has never been is no place ruled out
    been = k > 0 and sentence[k].lemma in _GONE and texts[0] in ("i", "we")
    if not been and (sentence[k].lemma not in _NOTICING or texts[k + 1] not in _REMARK_OBJECTS):
        return sentence
    if not been and texts[k + 1] == "any" and texts[k + 2 : k + 3] != ["other"]:
        return sentence  # "I don't see any towels": the towels are what is missing
    end = next((j for j in range(k + 2, len(texts)) if texts[j] in _REMARK_ENDS), None)
    if end is None:
        return sentence
    rest = sentence[end + 1 :]
    while rest and rest[0].text in _REMARK_ENDS:
        rest = rest[1:]
    return rest or sentence


# Openings of a remark on the other things there ("no other chair …", "nothing else …").
_OTHERS_REMARKS = (
    ("no", "other"), ("none", "of", "the", "other"), ("none", "of", "the", "others"),
    ("nothing", "else"), ("nothing", "much"), ("not", "much"), ("not", "a", "lot"),
)  # fmt: skip
_ROOM_WORDS = frozenset({"room", "space", "place", "area"})


def _remarks_on_others(clause: list[Word]) -> bool:
    """Whether a clause only remarks that the target is the one of its kind there or
    that little else is there ("no other chair in the room has wheels", "there is
    nothing else on the desk", "there isn't much in the hallway", "it's not a big room")."""
    texts = [w.text for w in clause]
    if texts[:2] == ["there", "is"] or texts[:2] == ["there", "are"]:
        texts = texts[2:]
        if texts[:1] == ["nothing"] and len(texts) > 1 and clause[3].pos == "ADP":
            return True  # "there is nothing on the desk"
    if any(tuple(texts[: len(o)]) == o for o in _OTHERS_REMARKS):
        return True
    if texts[:3] == ["it", "is", "not"] and texts[-1:] and texts[-1] in _ROOM_WORDS:
        return len(texts) <= 7  # "it's not a very big room"
    return False


def _after_room_remark(clause: list[Word]) -> int:
    """Where a clause goes on after a remark on the room's size that it opens with ("it's
    not a big room so the water cooler is easy to find"): the word after "so" / "but" /
    "and"; 0 when it opens otherwise."""
    texts = [w.text for w in clause]
    if texts[:3] != ["it", "is", "not"]:
        return 0
    end = next((k for k, t in enumerate(texts) if t in ("so", "but", "and")), len(texts))
    if end > 7 or end + 1 >= len(texts) or texts[end - 1] not in _ROOM_WORDS:
        return 0
    return end + 1


def without_remarks_on_others(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request without the clauses and sentences that only remark on the other
    things there (see :func:`_remarks_on_others`), where something else is said."""
    out: list[list[Word]] = []
    if sentences:
        sentences = [_only_one_there(sentences[0]), *sentences[1:]]
    for sentence in sentences:
        clauses = comma_parts(sentence)
        kept = [c[_after_room_remark(c) :] for c in clauses if not _remarks_on_others(c)]
        if kept == clauses:
            out.append(sentence)
        elif kept:
            out.append(joined_parts(kept))
    return out if any(out) else sentences


def _only_one_there(sentence: list[Word]) -> list[Word]:
    """A request that opens "there is no other coat rack in the room. It is the tall …"
    names its target's kind there: read as "there is a coat rack in the room"."""
    texts = [w.text for w in sentence[:4]]
    if (
        texts[:1] != ["there"]
        or texts[1:2] not in (["is"], ["are"])
        or texts[2:] != ["no", "other"]
    ):
        return sentence
    return [*sentence[:2], A, *sentence[4:]]


def comma_parts(sentence: list[Word]) -> list[list[Word]]:
    """A sentence's parts between commas."""
    parts: list[list[Word]] = [[]]
    for w in sentence:
        if w.text == ",":
            parts.append([])
        else:
            parts[-1].append(w)
    return [p for p in parts if p]


def joined_parts(parts: list[list[Word]]) -> list[Word]:
    """Parts of a sentence (:func:`comma_parts`) joined again, a comma between each."""
    return [w for k, part in enumerate(parts) for w in ([COMMA] if k else []) + part]


_BESIDES = Word("beside", "beside", "ADP", "IN", "prep")
_ANY_WORDS = frozenset({"any", "anything", "other", "another", "else", "everything", "all"})


def ends_with_thing(words: list[Word]) -> bool:
    """Whether ``words`` end with a thing's name: spaCy's noun, or a kind the vocabulary
    knows in the last one or two words ("magazine rack", "trash can", which spaCy may
    read as a verb)."""
    if words[-1].pos in ("NOUN", "PROPN"):
        return True
    texts = [w.text for w in words[-2:]]
    return any(canonical_label(" ".join(texts[-n:])) is not None for n in (1, 2))


def besides_as_beside(sentence: list[Word]) -> list[Word]:
    """ "the magazine rack besides the armchair": "beside" (see the module docstring)."""
    texts = [w.text for w in sentence]
    if "besides" not in texts:
        return sentence
    i = texts.index("besides")
    if i == 0 or not ends_with_thing(sentence[:i]) or _ANY_WORDS & set(texts[:i]):
        return sentence
    j = i + 1
    while j < len(sentence) and sentence[j].pos in ("DET", "ADJ", "NUM"):
        j += 1
    if j >= len(sentence) or j == i + 1 or sentence[j].pos not in ("NOUN", "PROPN"):
        return sentence
    if texts[j] in ("one", "ones"):
        return sentence
    return [*sentence[:i], _BESIDES, *sentence[i + 1 :]]


_INTERJECTIONS = frozenset({"nope", "no", "ok", "okay", "oh", "oops", "ah", "sorry", ","})


def called_off(sentences: list[list[Word]]) -> list[list[Word]]:
    """The sentences without an opening "never mind …" / "forget it" and what it calls
    off, up to a comma or the next command ("never mind the first message find my
    wallet instead" → "find my wallet instead"). When nothing else is said ("nvm, found
    it") only the opening words go."""
    cut = [_after_called_off(s) for s in sentences]
    kept = [s[k:] for s, (_, k) in zip(sentences, cut, strict=True) if s[k:]]
    if kept:
        return kept
    return [
        [*s[:i], *s[i + 2 :]] if i >= 0 else s for s, (i, _) in zip(sentences, cut, strict=True)
    ]


def _after_called_off(sentence: list[Word]) -> tuple[int, int]:
    """Where a "never mind" / "forget it" opening starts and where what follows what it
    calls off starts; (-1, 0) when the sentence has none."""
    texts = [w.text for w in sentence]
    i = 0
    while i < len(texts) and texts[i] in _INTERJECTIONS:
        i += 1
    if texts[i : i + 2] != ["never", "mind"] and texts[i : i + 2] not in (
        ["forget", "it"],
        ["forget", "that"],
    ):
        return -1, 0
    k = i + 2
    while k < len(sentence) and sentence[k].text != "," and not _command_at(sentence, k):
        k += 1
    while k < len(sentence) and texts[k] in _INTERJECTIONS:
        k += 1
    return i, k


def _command_at(sentence: list[Word], k: int) -> bool:
    """Whether a new command starts at word ``k`` ("… find my wallet instead")."""
    word = sentence[k]
    base = word.tag in ("VB", "VBP") and word.text == word.lemma  # "find" (spaCy: VBP too)
    return word.pos == "VERB" and base and k > 0 and sentence[k - 1].pos in ("NOUN", "PROPN")


_MOVING = frozenset({"move", "push", "pull", "slide", "drag", "roll", "shift", "keep", "put",
                     "take", "carry", "turn", "set", "place"})  # fmt: skip


def without_moved_away(sentence: list[Word]) -> list[Word]:
    """The sentence without "away from X" where X is where a thing is moved from ("move
    the bike away from the car", "the chair pushed away from the table")."""
    texts = [w.text for w in sentence]
    for i in range(1, len(texts) - 2):
        if texts[i : i + 2] != ["away", "from"]:
            continue
        if not any(w.lemma in _MOVING and w.pos == "VERB" for w in sentence[max(0, i - 6) : i]):
            continue
        end = i + 2
        while end < len(sentence) and sentence[end].pos in ("DET", "ADJ", "NUM", "PRON"):
            end += 1
        while end < len(sentence) and sentence[end].pos in ("NOUN", "PROPN"):
            end += 1
        return [*sentence[:i], *sentence[end:]]
    return sentence


_ASKING_FOR = frozenset({"have", "get", "bring", "grab", "fetch", "need", "want", "give"})


def another_as_one_more(sentence: list[Word]) -> list[Word]:
    """ "can I have another towel", "bring me another blanket": one more, "a"."""
    out = list(sentence)
    for i, word in enumerate(sentence):
        if word.text != "another" or i == 0:
            continue
        j = i - 1
        if sentence[j].text in ("me", "us") and j > 0:
            j -= 1
        if sentence[j].lemma in _ASKING_FOR and sentence[j].pos in ("VERB", "AUX"):
            out[i] = A
    return out


_SAYING = frozenset({"say", "read"})
_NO_WORDS = frozenset({"no", "not", "do"})


def without_sign_negation(sentence: list[Word]) -> list[Word]:
    """ "the sign that says no smoking", "the label that reads do not stack": the words
    written on the thing, without their "no" / "do not"."""
    for i, word in enumerate(sentence[:-2]):
        if word.lemma not in _SAYING or word.pos != "VERB" or sentence[i + 1].text not in _NO_WORDS:
            continue
        j = i + 1
        while j < len(sentence) and sentence[j].text in _NO_WORDS:
            j += 1
        return [*sentence[: i + 1], *sentence[j:]]
    return sentence


_WH = frozenset({"where", "what", "which", "how", "when", "why", "if", "whether"})


def without_no_idea(sentence: list[Word]) -> list[Word]:
    """ "no clue where the flashlight is …", "not sure where the pizza cutter went" as
    "where the flashlight is …"."""
    texts = [w.text for w in sentence]
    i = 2 if texts[:2] in (["i", "have"], ["we", "have"], ["i", "am"]) else 0
    if texts[i : i + 2] not in (["no", "idea"], ["no", "clue"], ["not", "sure"]):
        return sentence  # "not sure where the pizza cutter went"
    rest = sentence[i + 2 :]
    if rest and rest[0].text == "where" and (hinted := _place_hinted(rest)) is not None:
        return hinted  # "not sure where the stapler went, maybe the box room?"
    if any(w.text in ("but", "so", "just", ",") for w in rest):
        return sentence  # "no idea which aisle but find the batteries": the request follows
    if texts[i] == "not":  # "not sure which floor it's on, but …": only the place is unsure
        return rest if rest and rest[0].text == "where" else sentence
    return rest if rest and rest[0].text in _WH else sentence


# Words before a guessed place after "not sure where X is,": "maybe", "can you look".
_GUESS_OPENERS = frozenset({"maybe", "probably", "perhaps", "possibly", "try", "can", "could",
                            "you", "u", "please", "pls", "look", "check", "i", "think", "it",
                            "is", "might", "be"})  # fmt: skip


def _place_hinted(rest: list[Word]) -> list[Word] | None:
    """ "where the remote is, can you look in the den", "where the stapler went, maybe
    the box room": the thing's clause with the place guessed after the comma ("where the
    remote is in the den"); None when something else follows the comma."""
    k = next((j for j, w in enumerate(rest) if w.text == ","), None)
    if k is None or k < 3:
        return None
    after = rest[k + 1 :]
    while after and after[0].text in _GUESS_OPENERS:
        after = after[1:]
    if not after or any(w.pos == "VERB" or w.text == "," for w in after):
        return None
    nouns = [w.text for w in after if w.pos in ("NOUN", "PROPN")]
    if not nouns:
        return None
    if after[0].pos == "ADP":
        return [*rest[:k], *after]
    if after[0].pos == "DET" and room_type(" ".join(nouns)) is not None:
        return [*rest[:k], IN, *after]
    return None


_RUN_OUT_OPENINGS = (("there", "is", "no"), ("there", "are", "no"), ("there", "is", "nothing"),
                     ("we", "have", "no"), ("we", "are", "out", "of"), ("no",))  # fmt: skip
_REQUEST_LINKS = frozenset({"so", ","})
_ASKING = frozenset({"can", "could", "would", "will", "is", "are", "please"})


def without_run_out(sentence: list[Word]) -> list[Word]:
    """The sentence without an opening that says what has run out or is not there, when
    a request for another thing follows after "so" or a comma ("no ice left in the
    freezer so grab the cold pack")."""
    texts = [w.text for w in sentence]
    opening = next((o for o in _RUN_OUT_OPENINGS if tuple(texts[: len(o)]) == o), None)
    if opening is None or (opening == ("no",) and sentence[0].dep != "det"):
        return sentence
    for j in range(len(opening) + 1, len(sentence) - 2):
        if texts[j] not in _REQUEST_LINKS:
            continue
        rest = sentence[j + 1 :]
        while rest and rest[0].text in _REQUEST_LINKS:
            rest = rest[1:]
        asks = bool(rest) and (
            rest[0].text in _ASKING or (rest[0].pos == "VERB" and rest[0].tag == "VB")
        )
        if asks and any(w.pos in ("NOUN", "PROPN") for w in rest):
            return rest
        return sentence
    return sentence


def non_words(sentence: list[Word]) -> list[Word]:
    """ "non stick" (from "non-stick") as one adjective "non-stick", unless what follows
    "non" is a colour, material or other attribute the vocabulary knows ("non-wooden")."""
    texts = [w.text for w in sentence]
    if "non" not in texts:
        return sentence
    lx = lexicon()
    out: list[Word] = []
    i = 0
    while i < len(sentence):
        word = sentence[i]
        nxt = sentence[i + 1] if i + 1 < len(sentence) else None
        known = nxt is not None and (
            nxt.text in lx.materials or nxt.text in lx.adjectives or nxt.text in colour_words()
        )
        if word.text == "non" and nxt is not None and nxt.text.isalpha() and not known:
            merged = f"non-{nxt.text}"
            out.append(Word(merged, merged, "ADJ", "JJ", "amod"))
            i += 2
            continue
        out.append(word)
        i += 1
    return out


_FLOOR_NOUNS = frozenset({"floor", "level", "storey", "story"})
_IS = frozenset({"is", "are"})
_ON = frozenset({"on", "in"})
_MOST = frozenset({"most", "more", "fewest", "least", "fewer"})


def floor_asked(sentence: list[Word]) -> list[Word]:
    """ "which floor is the laundry room on?", "on what level is the piano", "which
    storey has the sauna": the floor is found by finding the thing, so the request is
    that thing ("the laundry room")."""
    texts = [w.text for w in sentence]
    k = 1 if texts[:1] in (["on"], ["in"]) else 0
    if len(texts) < k + 4 or texts[k] not in ("which", "what") or texts[k + 1] not in _FLOOR_NOUNS:
        return sentence
    verb = texts[k + 2]
    if verb in _IS:
        end = len(texts) - 1 if k == 0 and texts[-1] in _ON else len(texts)
        if k == 0 and end == len(texts):
            return sentence  # "which floor is carpeted": the floor itself
    elif verb in ("has", "have") and k == 0:
        end = len(texts)
    else:
        return sentence
    thing = sentence[k + 3 : end]
    if not any(w.pos in ("NOUN", "PROPN") for w in thing) or _MOST & {w.text for w in thing[:2]}:
        return sentence  # "which floor has the most bedrooms"
    return thing


_CLAUSE_BREAKS = frozenset({",", "but", "so", "and"})
_RELATIVES = frozenset({"that", "which", "who"})


def without_no_longer(sentence: list[Word]) -> list[Word]:
    """ "the tape dispenser isn't on my desk anymore", "the chair that is no longer in
    the office": where a thing used to be tells of a change, not of which thing is
    meant; the clause is dropped ("the tape dispenser")."""
    texts = [w.text for w in sentence]
    for k, text in enumerate(texts):
        longer = texts[k : k + 2] == ["no", "longer"] and texts[k + 2 : k + 3] != ["than"]
        if text not in ("not", "n't") and not longer:
            continue
        end = next((j for j in range(k + 1, len(texts)) if texts[j] in _CLAUSE_BREAKS), len(texts))
        if longer:
            stop = end
        else:
            hit = next((j for j in range(k + 1, end) if _any_more(texts, j)), None)
            if hit is None:
                continue
            stop = hit + 1 if texts[hit] == "anymore" else hit + 2
        start = k
        while start > 0 and sentence[start - 1].pos == "AUX":
            start -= 1  # "is", "does"
        if start > 0 and texts[start - 1] in _RELATIVES:
            start -= 1
        if start == 0 or sentence[start - 1].pos not in ("NOUN", "PROPN", "PRON"):
            return sentence  # "I don't use it anymore": no thing's place
        return [*sentence[:start], *sentence[stop:]]
    return sentence


def _any_more(texts: list[str], j: int) -> bool:
    return texts[j] == "anymore" or (
        texts[j] == "any" and texts[j + 1 : j + 2] in (["more"], ["longer"])
    )


_WITH = Word("with", "with", "ADP", "IN", "prep")
_WITHOUT = Word("without", "without", "ADP", "IN", "prep")
_QUALITY_POS = frozenset({"ADJ", "NOUN", "PROPN", "VERB"})


def whose_as_with(sentence: list[Word]) -> list[Word]:
    """ "the wardrobe whose doors are mirrored" as "the wardrobe with mirrored doors", and
    "the cabinet whose doors aren't glass" as "… without glass doors": what "whose" says
    of a part, as a part with that quality (ruled out where the clause is negated). A
    clause that says more than one or two words of quality ("whose top is covered in
    papers") reads "with" its part and the rest as it stands."""
    for i, word in enumerate(sentence):
        if word.text != "whose" or i == 0:
            continue
        j = i + 1
        while j < len(sentence) and sentence[j].pos in ("ADJ", "NOUN", "PROPN"):
            j += 1
        part = sentence[i + 1 : j]
        if not part or j >= len(sentence) or sentence[j].lemma != "be":
            return sentence
        k = j + 1
        negated = k < len(sentence) and sentence[k].text == "not"
        k += negated
        if sentence[k : k + 2] and [w.text for w in sentence[k : k + 2]] == ["made", "of"]:
            k += 2  # "whose legs are made of metal"
        while k < len(sentence) and sentence[k].pos == "ADV":
            k += 1  # "whose door isn't fully closed"
        end = k
        while end < len(sentence) and sentence[end].pos in _QUALITY_POS and end - k < 2:
            end += 1
        closed = end == len(sentence) or sentence[end].pos in ("PUNCT", "CCONJ")
        if end == k or not closed:
            return [*sentence[:i], _WITH, *part, *sentence[j + 1 :]]
        quality = [Word(w.text, w.text, "ADJ", "JJ", "amod") for w in sentence[k:end]]
        return [*sentence[:i], _WITHOUT if negated else _WITH, *quality, *part, *sentence[end:]]
    return sentence


_NOT = Word("not", "not", "PART", "RB", "neg")
_SETTING_ASIDE = frozenset({"leave", "forget"})


def set_aside_first(sentence: list[Word]) -> list[Word]:
    """ "leave the heavy box and bring the small box", "forget the kitchen, check the
    grill on the deck": a thing or place set aside before the errand is ruled out, as
    "…, not the heavy box" would. Only a bare phrase is set aside: "leave the keys on the
    table and …" says where to put them. ("never mind …" is called off before this, by
    :func:`called_off`.)"""
    if not sentence or sentence[0].text not in _SETTING_ASIDE:
        return sentence
    end = 1
    while end < len(sentence) and sentence[end].pos in ("DET", "ADJ", "NOUN", "PROPN", "NUM"):
        end += 1
    phrase = sentence[1:end]
    if not any(w.pos in ("NOUN", "PROPN") for w in phrase) or end + 1 >= len(sentence):
        return sentence
    if sentence[end].text not in (",", "and"):
        return sentence
    k = end + 1
    if sentence[k].text in (",", "and", "just", "then", "please"):
        k += 1
    if k >= len(sentence) or sentence[k].pos != "VERB" or sentence[k].tag != "VB":
        return sentence
    return [*sentence[k:], COMMA, _NOT, *phrase]


def without_manner(sentence: list[Word]) -> list[Word]:
    """ "you can reach the switch without moving the dresser", "get to it without
    stepping on the rug": "without" and a verb with its object say how something is
    done, not a part the thing lacks; the phrase is dropped up to the next comma ("the
    chair without padding" keeps its part). "without it" names no part either."""
    for i, word in enumerate(sentence[:-1]):
        if word.text == "without" and sentence[i + 1].text in ("it", "them"):
            return [*sentence[:i], *sentence[i + 2 :]]  # "i cant sleep without it"
        if i + 2 >= len(sentence):
            break
        nxt, obj = sentence[i + 1], sentence[i + 2]
        verb = nxt.tag == "VBG" and nxt.pos == "VERB"
        if word.text == "without" and verb and obj.pos in ("DET", "PRON", "ADP"):
            end = next(
                (k for k in range(i + 1, len(sentence)) if sentence[k] is COMMA), len(sentence)
            )
            return [*sentence[:i], *sentence[end:]]
    return sentence


_PRONOUN_SUBJECTS = frozenset({"it", "they", "that", "this", "there"})


def without_failed_condition(sentence: list[Word]) -> list[Word]:
    """ "If it's not on the desk, look in the top drawer for the stapler", "if there
    isn't one in the kitchen, check the garage": where to look should the first place
    fail; the condition rules nothing out and is dropped."""
    if len(sentence) < 4 or sentence[0].text != "if" or sentence[1].text not in _PRONOUN_SUBJECTS:
        return sentence
    comma = next((k for k, w in enumerate(sentence) if w is COMMA), None)
    if comma is None or comma + 1 >= len(sentence):
        return sentence
    neg = next((k for k in range(2, comma) if sentence[k].text == "not"), None)
    if neg is None:
        return sentence
    k = neg + 1
    if k < comma and sentence[k].text in ("one", "any", "anything", "there"):
        k += 1  # "if there isn't one in the kitchen"
    if k >= comma or sentence[k].pos != "ADP" or any(w.pos == "VERB" for w in sentence[k:comma]):
        return sentence  # "if it's not too much trouble could you bring me …": a request
    return sentence[comma + 1 :]


# Verbs by which a "but don't …" after an errand picks among things ("… but don't take
# the blue one"): the choice is kept.
_CHOOSING = frozenset({"take", "grab", "bring", "get", "use", "pick", "choose", "fetch", "want"})


def without_trailing_caution(sentence: list[Word]) -> list[Word]:
    """ "bring me the hand mixer but don't unplug the toaster", "grab the vase, but do not
    wake the baby": a caution after the errand rules nothing out and is dropped; "…
    but don't take the blue one" still chooses, as "but not the blue one"."""
    for j, word in enumerate(sentence[:-3]):
        if word.text != "but" or j < 2:
            continue
        k = j + 1
        if sentence[k].text == "do" and sentence[k + 1].text == "not":
            k += 2
        else:
            continue
        verb = sentence[k] if k < len(sentence) else None
        if verb is None or verb.pos != "VERB":
            return sentence
        if verb.lemma in _CHOOSING:  # "… but don't take the blue one": "but not the blue one"
            return [*sentence[: j + 1], _NOT, *sentence[k + 1 :]]
        end = j - 1 if sentence[j - 1] is COMMA else j
        return sentence[:end]
    return sentence


def which_of_is(sentence: list[Word]) -> list[Word]:
    """ "which of the two couches in the family room is the sofa bed" as "the sofa bed in
    the family room": the thing named after "is" is sought among those named first."""
    texts = [w.text for w in sentence]
    if texts[:2] != ["which", "of"]:
        return sentence
    k = next((j for j in range(3, len(sentence) - 2) if sentence[j].lemma == "be"), None)
    if k is None or sentence[k + 1].pos != "DET":
        return sentence
    picked = sentence[k + 1 :]
    if not any(w.pos in ("NOUN", "PROPN") for w in picked) or any(w.pos == "VERB" for w in picked):
        return sentence
    named = " ".join(w.text for w in picked if w.pos in ("NOUN", "PROPN"))
    if canonical_label(named) is None:
        return sentence  # "which of the bottles … is the whisky": what is in it, not a kind
    place = next(
        (j for j in range(2, k) if sentence[j].pos == "ADP" and sentence[j].text != "of"), k
    )
    return [*picked, *sentence[place:k]]


_WITH = Word("with", "with", "ADP", "IN", "prep")
_IT_AFTER = Word("it", "it", "PRON", "PRP", "pobj")
# Verbs of resting somewhere in a relative clause whose object is the thing sought ("the
# shelf the TV sits on", "the box that the keys are in").
_RESTING = frozenset({"be", "sit", "stand", "rest", "lie", "hang", "go", "live", "belong", "sleep"})
# Prepositions such a clause ends with ("… the TV sits on", "… the lamp is next to").
_STRANDED = ("next to", "in front of", "on top of", "on", "in", "inside", "under",
             "underneath", "beneath", "behind", "beside", "by", "near", "above", "over")  # fmt: skip
_CLAUSE_END = frozenset({",", "and", "but", "."})


def stranded_relative(sentence: list[Word]) -> list[Word]:
    """ "the shelf the TV sits on", "the box that the keys are in", "the table the lamp is
    next to" as "the shelf with the TV on it": a relative clause whose object is the
    thing sought, with its preposition left at the end, says what is on, in or by it."""
    texts = [w.text for w in sentence]
    for k in range(1, len(sentence) - 3):
        if sentence[k - 1].pos not in ("NOUN", "PROPN") or texts[k] not in (
            "the",
            "a",
            "my",
            "that",
            "which",
            "our",
            "your",
        ):
            continue
        j = k + 1 if texts[k] in ("that", "which") else k
        if j >= len(sentence) or texts[j] not in ("the", "a", "my", "our", "your", "his", "her"):
            continue
        n = j + 1
        while n < len(sentence) and n - j <= 4 and sentence[n].pos in ("NOUN", "PROPN", "ADJ"):
            n += 1
        if n == j + 1 or n >= len(sentence) or sentence[n - 1].pos not in ("NOUN", "PROPN"):
            continue
        if sentence[n].lemma not in _RESTING:
            continue
        v = n + 1
        while v < len(sentence) and texts[v] in ("usually", "always", "normally", "now"):
            v += 1
        for prep in _STRANDED:
            words = prep.split()
            end = v + len(words)
            if texts[v:end] == words and (end == len(sentence) or texts[end] in _CLAUSE_END):
                thing = sentence[j:n]
                return [*sentence[:k], _WITH, *thing, *sentence[v:end], _IT_AFTER, *sentence[end:]]
    return sentence


# Words for a thing named by what it does ("the one that …" refers back to a kind named
# before: "the microwave, the one that beeps").
_THING_WORDS = frozenset(
    {"thing", "thingy", "machine", "gadget", "device", "contraption", "appliance"}
)
_SOMETHING_WORD = Word("something", "something", "PRON", "NN", "dobj")
_TO = Word("to", "to", "PART", "TO", "aux")


def thing_that_does(sentence: list[Word]) -> list[Word]:
    """ "the thing that plays the sound", "the machine that washes them" as "something to
    play the sound", "something to wash them": a thing named by what it does is sought
    for that purpose, not the thing its verb acts on."""
    texts = [w.text for w in sentence]
    for k in range(len(sentence) - 2):
        if texts[k] not in _THING_WORDS or texts[k + 1] not in ("that", "which"):
            continue
        verb = sentence[k + 2]
        if verb.tag not in ("VBZ", "VBP") or not knows_verb(verb.lemma):
            continue  # "the thing that beeps": no purpose the vocabulary knows
        start = k - 1 if k > 0 and texts[k - 1] in ("the", "a", "this", "that", "some") else k
        done = Word(verb.lemma, verb.lemma, "VERB", "VB", "xcomp")
        return [*sentence[:start], _SOMETHING_WORD, _TO, done, *sentence[k + 3 :]]
    return sentence


_GO = Word("go", "go", "VERB", "VB", "ROOT")
_BE_WORDS = frozenset({"is", "are", "was", "were", "be"})
_TO_PLACE = Word("to", "to", "ADP", "IN", "prep")
# Words that may open a request before its verb ("please hoover under the sofa").
_REQUEST_OPENERS = frozenset({"please", "pls", "can", "could", "would", "will", "you"})


def chore_at_place(sentence: list[Word]) -> list[Word]:
    """ "Hoover under the sofa", "dust behind the TV" as "go to the sofa" / "the TV": a
    chore done under, behind or around a thing (``lexicon.toml`` ``[verbs] chores``) sends
    the robot to that thing. Not when the sentence says what is sought there ("clean under
    the bed for the lost sock", "…, there is a box")."""
    lx = lexicon()
    k = 0
    while k < len(sentence) and sentence[k].text in _REQUEST_OPENERS:
        k += 1
    if k + 2 >= len(sentence):
        return sentence
    verb, prep = sentence[k], sentence[k + 1]
    if verb.text not in lx.chore_verbs and verb.lemma not in lx.chore_verbs:
        return sentence
    if prep.text not in lx.chore_prepositions:
        return sentence
    rest = [w.text for w in sentence[k:]]
    if "for" in rest or any(a == "there" and b in _BE_WORDS for a, b in pairwise(rest)):
        return sentence  # "… for my slippers", "…, there is a tower": what is sought there
    if sentence[k + 2].pos not in ("DET", "NOUN", "PROPN", "ADJ"):
        return sentence
    return [*sentence[:k], _GO, _TO_PLACE, *sentence[k + 2 :]]


# Parts of speech of the words that name who or what a request quotes ("the owner's
# voice memo", "my sister").
_SOURCE_POS = frozenset({"DET", "NOUN", "PROPN", "ADJ", "PRON", "NUM"})
# Words that may come between the reporting verb and what is said ("it says here that").
_AFTER_REPORT = frozenset({"here", "me", "us", "that", ","})


def without_report_frame(sentence: list[Word]) -> list[Word]:
    """ "The note says the plant needs water", "Owner's memo: 'the toilet keeps running'",
    "the owner says to water the smaller pot", "according to the note, …": the quoted
    request without its frame (``lexicon.toml`` ``report_sources`` and ``report_verbs``,
    or a person of ``seekers``). Other sentences as they are."""
    lx = lexicon()
    texts = [w.text for w in sentence]
    start = 2 if texts[:2] == ["according", "to"] else 0
    j = start
    while j < len(sentence) and j - start < 5 and sentence[j].pos in _SOURCE_POS:
        j += 1
    if j == start or j >= len(sentence) - 1:
        return sentence
    source = " ".join(texts[start:j])
    if texts[start] in ("nobody", "no", "none", "noone"):
        return sentence  # "nobody told me we were out of tape": nothing is quoted
    said_by = texts[j - 1] in lx.report_sources or source in lx.report_sources
    if not said_by and texts[j - 1] in lx.seekers and texts[j - 1] not in _SPEAKERS:
        said_by = start > 0 or texts[j] in lx.report_verbs
    if not said_by:
        return sentence
    if start > 0 or texts[j] == ",":  # "according to the note, …", "Owner's memo: …"
        if texts[j] != "," or (texts[j - 1] == "it" and start == 0):
            return sentence
    elif texts[j] not in lx.report_verbs:
        return sentence
    k = j + 1
    while k < len(sentence) and texts[k] in _AFTER_REPORT:
        k += 1
    if k < len(sentence) - 1 and texts[k] == "to" and sentence[k + 1].tag == "VB":
        k += 1  # "the note says to water the plant": the command
    return sentence[k:] if k < len(sentence) else sentence


# Who speaks or listens: "I said the lamp, not the fan" corrects, it quotes no one.
_SPEAKERS = frozenset({"i", "me", "you", "we", "us", "myself", "yourself", "one"})


_NEAREST = Word("nearest", "near", "ADJ", "JJS", "amod")
# Ends a thing has, one of them named by what it faces ("the hall end of the table").
_END_WORDS = frozenset({"end", "side"})


def end_toward(sentence: list[Word]) -> list[Word]:
    """ "the hall end of the dining table", "the window side of the bed" as "the end of the
    dining table nearest the hall": an end named by the room or thing it faces."""
    texts = [w.text for w in sentence]
    for k in range(len(sentence) - 5):
        if texts[k] != "the" or sentence[k + 1].pos not in ("NOUN", "PROPN"):
            continue
        if texts[k + 2] not in _END_WORDS or texts[k + 3] != "of" or texts[k + 4] != "the":
            continue
        n = k + 5
        while n < len(sentence) and sentence[n].pos in ("NOUN", "PROPN", "ADJ"):
            n += 1
        if n == k + 5 or sentence[n - 1].pos not in ("NOUN", "PROPN"):
            continue
        toward = sentence[k + 1]
        return [*sentence[: k + 1], *sentence[k + 2 : n], _NEAREST, THE, toward, *sentence[n:]]
    return sentence


def ordinal_along(sentence: list[Word]) -> list[Word]:
    """ "the second chair along on your left" as "the second chair on your left": "along"
    between a counted thing and its side says nothing more."""
    out = list(sentence)
    for k in range(len(sentence) - 2, 0, -1):
        if sentence[k].text != "along" or sentence[k - 1].pos not in ("NOUN", "PROPN"):
            continue
        nxt = sentence[k + 1].text
        if nxt in ("on", "from", "to") and any(w.text in ("left", "right") for w in sentence[k:]):
            del out[k]
    return out


_LOOKING = Word("looking", "look", "VERB", "VBG", "advcl")
# Who looks, in "from the door you look at the sofa".
_LOOKERS = frozenset({"you", "i", "we"})


def from_then_look(sentence: list[Word]) -> list[Word]:
    """ "From the door you look at the sofa" as "From the door, looking at the sofa": a
    standpoint, then what the speaker looks at from it (not "the door you look at")."""
    if not sentence or sentence[0].text != "from":
        return sentence
    facing = lexicon().facing_verbs
    for k in range(2, min(len(sentence) - 1, 10)):
        word, verb = sentence[k], sentence[k + 1]
        if word.text == ",":
            return sentence
        if word.text in _LOOKERS and verb.lemma in facing and verb.tag in ("VBP", "VB"):
            return [*sentence[:k], COMMA, _LOOKING, *sentence[k + 2 :]]
    return sentence


_I = Word("i", "i", "PRON", "PRP", "nsubj")
_THING_POS = frozenset({"DET", "PRON", "ADJ", "NOUN", "PROPN", "NUM"})


def need_after_deed(sentence: list[Word]) -> list[Word]:
    """ "I've washed my hands in the bathroom and need something to dry them on" as "I need
    something to dry my hands on in the bathroom": what the speaker did says what "them"
    is, and the need that follows is the request (not the hands, the deed's object)."""
    texts = [w.text for w in sentence]
    for a, word in enumerate(sentence):
        if word.text != "and":
            continue
        b = a + 1 + (a + 1 < len(sentence) and texts[a + 1] in ("i", "so", "now"))
        if b >= len(sentence) or sentence[b].lemma not in ("need", "want"):
            continue
        k = next(
            (
                j
                for j in range(b + 1, min(len(sentence) - 2, b + 5))
                if texts[j] == "to"
                and sentence[j + 1].tag == "VB"
                and texts[j + 2] in ("it", "them")
            ),
            None,
        )
        deed = next(
            (
                j
                for j in range(a)
                if sentence[j].tag in ("VBD", "VBN") and sentence[j].pos == "VERB"
            ),
            None,
        )
        if k is None or deed is None:
            return sentence
        end = deed + 1
        while end < a and sentence[end].pos in _THING_POS and texts[end] not in ("it", "them"):
            end += 1
        thing = sentence[deed + 1 : end]
        if not any(w.pos in ("NOUN", "PROPN") for w in thing):
            return sentence
        return [_I, *sentence[b : k + 2], *thing, *sentence[k + 3 :], *sentence[end:a]]
    return sentence


# Words after which a new errand starts in a list of them ("…, but first go to …").
_ERRAND_BREAKS = frozenset({",", "and", "but", "so"})
# Words that open what is done before or after the errand ("after lunch, …").
_TIME_OPENERS = frozenset({"after", "before"})
# Prepositions that put a time clause somewhere ("after you're in the office, …"): the
# place is the request's, so the clause stays.
_PLACING_WORDS = frozenset({"in", "into", "at", "on", "by", "inside"})


def errand_now(sentence: list[Word]) -> list[Word]:
    """Of several errands said at once, the one to do now: "the laundry needs folding,
    but first go to the oven", "Lunch, then homework, but before that go and straighten
    the couch", "Sort the recycling, but go to the desk first and clear it", "after the
    dishes, fix the cushion", "Kids to bed at eight and the laundry can wait - the thing
    you press …" (``lexicon.toml`` ``errand_markers``). Other sentences as they are."""
    out = _after_time_clauses(sentence)
    out = _marked_errand(out)
    return _without_waiting(out)


def _marked_errand(sentence: list[Word]) -> list[Word]:
    """The errand a marker picks ("but first …", "before that …", "now …", "… first and
    …"), from the marker on; the sentence when no marker picks one."""
    texts = [w.text for w in sentence]
    markers = sorted((m.split() for m in lexicon().errand_markers), key=len, reverse=True)
    for s in range(1, len(sentence) - 1):
        if texts[s - 1] not in _ERRAND_BREAKS:
            continue
        for marker in markers:
            end = s + len(marker)
            if texts[s:end] != marker or end >= len(sentence):
                continue
            if marker[-1] in ("first", "now") and not _errand_opens_at(sentence, end):
                continue  # "…, first floor", "and now the lamp is on"
            rest = sentence[end:]
            while rest and rest[0].text == ",":
                rest = rest[1:]
            return rest or sentence
    for s in range(2, len(sentence) - 1):
        # "Coats up, shoes away, then hoover the armchair": chores said without a verb,
        # then the one errand the sentence gives a verb
        then = 2 if texts[s : s + 2] == ["and", "then"] else 1 if texts[s] == "then" else 0
        listed = not any(w.pos in ("VERB", "AUX") for w in sentence[:s])
        if then and listed and texts[s - 1] == "," and _errand_opens_at(sentence, s + then):
            return sentence[s + then :]
    for f in range(2, len(sentence)):
        after = texts[f + 1] if f + 1 < len(sentence) else None
        if texts[f] != "first" or sentence[f].tag != "RB" or after not in (None, ",", "and"):
            continue
        start = max((k + 1 for k in range(f) if texts[k] == "but"), default=0)
        if start > 0:  # "…, but go to the desk first and clear the clutter off it"
            return [*sentence[start:f], *sentence[f + 1 :]]
    return sentence


def _opens_command(word: Word) -> bool:
    """Whether ``word`` can open a command after "first" / "now": a comma, or a verb
    (spaCy's, or an English verb it took for a noun: "but first dust the shelf")."""
    if word.text == "," or word.tag in ("VB", "VBP"):
        return True
    return word.pos in ("NOUN", "PROPN") and word.tag == "NN" and known_lemma(word.text, "verb")


def _errand_opens_at(sentence: list[Word], k: int) -> bool:
    """Whether a command opens at ``k``: a verb, or an English verb spaCy took for a noun
    with its object's determiner after it ("dust the highest shelf", not "floor:")."""
    if k >= len(sentence):
        return False
    if sentence[k].text == "," or sentence[k].tag in ("VB", "VBP"):
        return True
    nxt = sentence[k + 1] if k + 1 < len(sentence) else None
    return _opens_command(sentence[k]) and nxt is not None and nxt.pos == "DET"


def _after_time_clauses(sentence: list[Word]) -> list[Word]:
    """The sentence without the clauses before its first comma that say when ("after the
    dishes and the homework, …", "before dinner and after the bins, …")."""
    out = sentence
    while len(out) > 2:
        k = 1 if out[0].text == "and" else 0
        if out[k].text not in _TIME_OPENERS:
            break
        comma = next((j for j in range(k + 1, min(len(out), k + 12)) if out[j].text == ","), None)
        if comma is None or not _errand_opens_at(out, comma + 1):
            break  # "after the call i walked off without my laptop, was it …": no errand
        if any(w.text in _PLACING_WORDS for w in out[k:comma]):
            break
        out = out[comma + 1 :]
    return out


def _without_waiting(sentence: list[Word]) -> list[Word]:
    """The sentence without an errand said to wait ("the laundry can wait - …", "…, the
    dishes can wait")."""
    texts = [w.text for w in sentence]
    for k in range(1, len(sentence) - 1):
        if texts[k] != "can" or texts[k + 1] != "wait":
            continue
        before = max((j for j in range(k) if texts[j] == ","), default=-1)
        after = next((j for j in range(k + 2, len(sentence)) if texts[j] == ","), None)
        if after is not None and before < 0:
            return sentence[after + 1 :]  # "the laundry can wait - the thing you press …"
        if after is None and before > 0:
            return sentence[:before]  # "…, put it back straight - the dishes can wait"
    return sentence
