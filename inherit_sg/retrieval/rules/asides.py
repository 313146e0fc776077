"""What a speaker says of themselves or of others beside the request.

"check if the dishwasher's finished, I'm up to my elbows in laundry", "hoover the carpet
in the family room, the dog's been on it", "May I sit in the black chair? My back prefers
a firm seat.": a clause whose subject is a person, a pet or the speaker's body, that
states something (a finite verb, no word of asking) and names no need the vocabulary
knows (:func:`~inherit_sg.retrieval.rules.problems.match_problem`: "I'm cold" is one),
is context, not the request. It is dropped when another clause of the request asks for
something; a room it names stays ("baby's napping in the family room, block out the
light" → "in the family room, block out the light").
"""

from __future__ import annotations

from inherit_sg.retrieval.rules.problems import match_problem
from inherit_sg.retrieval.rules.rewording import comma_parts, joined_parts
from inherit_sg.retrieval.rules.tokens import Word
from inherit_sg.vocab.lexicon import lexicon
from inherit_sg.vocab.rooms import room_type

# Finite verb tags; spaCy tags "'s" after a noun as VBZ ("the dog's been on it").
_FINITE = frozenset({"VBZ", "VBP", "VBD", "MD"})
_PETS = frozenset({"dog", "dogs", "cat", "cats", "puppy", "kitten", "pup"})
_BODY = frozenset(
    {"back", "hands", "hand", "feet", "foot", "elbows", "knees", "knee", "arms", "arm",
     "legs", "leg", "head", "neck", "shoulder", "shoulders", "hip", "hips"}
)  # fmt: skip
_OWNERS = frozenset({"my", "our", "the", "his", "her", "their"})
# Words of asking or wanting: a clause with one is part of the request.
_ASKING = frozenset(
    {"need", "needs", "want", "wants", "like", "would", "could", "can", "may", "might",
     "shall", "please", "where", "which", "what", "help", "should", "must", "let", "if",
     "when", "while", "as"}
)  # fmt: skip
# Verbs that open what is asked for ("check", "hoover", "block out …").
_COMMAND_TAGS = frozenset({"VB"})


def _subject_is_someone(clause: list[Word]) -> bool:
    """Whether the clause opens with a person, a pet or the speaker's body as subject
    ("I'm …", "baby's …", "the dog's …", "my back …")."""
    texts = [w.text for w in clause]
    # not "they" / "he" / "she": "they're under the desk" is said of the things sought
    people = lexicon().seekers - _NOT_SOMEONE
    k = 1 if texts[0] in _OWNERS and len(texts) > 1 else 0
    first = texts[k]
    if first in _BODY:
        return k == 1 and texts[0] == "my"
    return first in people or first in _PETS


def _states(clause: list[Word]) -> bool:
    """Whether the clause states something: a finite verb (or a participle right after
    the subject, whose "is" the speaker dropped: "baby's napping") and no word of
    asking."""
    if any(w.text in _ASKING or w.lemma in _ASKING for w in clause):
        return False
    return any(w.tag in _FINITE or (k == 1 and w.text.endswith("ing"))
               for k, w in enumerate(clause[:4]))  # fmt: skip


def _asks(clause: list[Word]) -> bool:
    """Whether a clause asks for something: it opens with a command or has a word of
    asking."""
    if clause[0].tag in _COMMAND_TAGS and clause[0].pos == "VERB":
        return True
    return any(w.text in _ASKING for w in clause)


def _room_phrase(clause: list[Word]) -> list[Word]:
    """The "in the <room>" phrase of a clause, if any ("in laundry" names no room)."""
    for k, w in enumerate(clause):
        if w.text not in ("in", "into"):
            continue
        j = k + 1
        while j < len(clause) and clause[j].text in _OWNERS:
            j += 1
        if j == k + 1:
            continue
        for n in (3, 2, 1):
            words = clause[j : j + n]
            if len(words) == n and room_type(" ".join(x.text for x in words)):
                return clause[k : j + n]
    return []


# The speaker's own statements are asides only when they say where or how the speaker
# is ("I'm up to my elbows in laundry", "I'm on the phone"); what the speaker did or
# thinks often names the thing sought ("I left my badge on my desk", "I believe there's
# a lamp in the lounge").
_SPEAKER = frozenset({"i", "we"})
_BUSY = frozenset({"up", "busy", "slow", "stuck", "covered", "knee", "elbow", "run"})
_CALLS = frozenset({"phone", "call", "line", "zoom", "computer", "laptop"})
_NOT_SOMEONE = frozenset(
    {"one", "anyone", "anybody", "everyone", "everybody", "they", "he", "she", "others",
     "me", "myself", "individual", "group", "person", "people"}
)  # fmt: skip
# Words that point back at a thing named earlier: the clause that named it stays.
_BACK_REFERENCES = frozenset({"it", "them", "they", "one", "that", "those", "these", "this"})


def _speaker_state(clause: list[Word]) -> bool:
    """ "I'm up to my elbows …", "we're on a call": the speaker busy, not where they
    stand ("I'm at the copier …" is a standpoint)."""
    texts = [w.text for w in clause]
    if len(texts) < 3 or clause[1].lemma != "be" or any(w.pos == "VERB" for w in clause[2:]):
        return False
    if texts[2] == "on":
        return any(t in _CALLS for t in texts[3:6])  # "I'm on the phone"
    return texts[2] in _BUSY


def _aside(clause: list[Word]) -> bool:
    if len(clause) < 3 or not _subject_is_someone(clause) or not _states(clause):
        return False
    if clause[0].text in _SPEAKER and not _speaker_state(clause):
        return False
    return match_problem(clause) is None


def without_personal_asides(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request without the clauses that only say something of the speaker or of
    others (see the module docstring), when another clause asks for something."""
    marked = [[(p, _aside(p)) for p in comma_parts(s)] for s in sentences]
    flat = [pair for row in marked for pair in row]
    rest = [p for p, aside in flat if not aside]
    if len(rest) == len(flat) or not any(_asks(p) for p in rest):
        return sentences
    # "nobody uses the treadmill, move it": an aside that may name what "it" points back at
    named = any(aside and not (p[0].text in _SPEAKER and _speaker_state(p)) for p, aside in flat)
    if named and any(w.text in _BACK_REFERENCES for p in rest for w in p):
        return sentences
    out: list[list[Word]] = []
    for row in marked:
        kept = [p if not aside else _room_phrase(p) for p, aside in row]
        kept = [p for p in kept if p]  # an aside keeps only the room it names
        if kept:
            out.append(joined_parts(kept))
    return out or sentences
