"""How a later sentence of a request relates to the first one when it names another
thing: the thing of the first sentence, or the other one, is the target.

- A first sentence that states how things are, followed by a request for another named
  thing ("The wifi is down. Can you check the router?"): the request's object.
- A first sentence that sets the scene with "there is", followed by another thing placed
  by it and described in its own right ("there is a desk in the corner. the chair in
  front of it is black and has wheels."): that thing, the first one its landmark.
- Otherwise a later sentence describes the first sentence's target ("… It is white.").
"""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.retrieval.constraints import AttributeConstraint, Constraint, RelationConstraint
from inherit_sg.retrieval.rules.clause import Clause
from inherit_sg.retrieval.rules.phrase import ANAPHOR, NP, OBJECT, ONE
from inherit_sg.retrieval.rules.sentences import FINITE, IT_WORDS, QUESTION_OPENERS
from inherit_sg.retrieval.rules.tokens import Word
from inherit_sg.vocab.objects import is_kind_of

# Dependencies of a clause's own verb (a run-on's first verb hangs off the second: ccomp)
_MAIN_VERB = frozenset({"ROOT", "ccomp", "conj", "parataxis"})
# Words that may come before a request's verb: politeness, discourse openers and the
# modal of a question put as a request ("so could you please check …").
_REQUEST_OPENERS = frozenset(
    {"please", "so", "and", "then", "now", "just", "ok", "okay", "hey", "can", "could",
     "would", "will", "you", "kindly", ","}
)  # fmt: skip


def _after_openers(sentence: list[Word]) -> int:
    """Where a request's verb would stand: the first word after its openers."""
    i = 0
    while i < len(sentence) and sentence[i].text in _REQUEST_OPENERS:
        i += 1
    return i


def _is_request(sentence: list[Word]) -> bool:
    """Whether a sentence asks for something to be done ("Can you check the router?",
    "Grab the flashlight from the drawer.", "Please pick up the toys."): after any
    openers, the sentence's root verb in its base form, with no subject but "you"."""
    i = _after_openers(sentence)
    if i == len(sentence):
        return False
    verb = sentence[i]
    modal = any(w.text in ("can", "could", "would", "will") for w in sentence[:i])
    if modal and not any(w.text == "you" for w in sentence[:i]):
        return False  # "can I …" asks leave, it gives no errand
    # after "can you" the verb is the errand however spaCy attached a run-on's parts
    return verb.pos == "VERB" and verb.tag == "VB" and (verb.dep == "ROOT" or modal)


def _is_statement(sentence: list[Word]) -> bool:
    """Whether a sentence states how things are ("The wifi is down.", "There is a
    bookshelf next to the TV."): its root is a verb, and it is no question and no
    request (a bare phrase, "The plant we never water.", is none)."""
    if not sentence or sentence[0].tag == "MD" or sentence[0].text in QUESTION_OPENERS:
        return False
    if sentence[0].pos == "AUX" and sentence[0].lemma in ("be", "do", "have"):
        return False  # "Is the stove off?"
    finite = any(
        w.pos in ("VERB", "AUX") and w.tag in FINITE and w.dep in _MAIN_VERB for w in sentence
    )  # not "The plant that we never water.": a phrase with a relative clause
    return finite and not _is_request(sentence)


def statement_then_request(
    clause: Clause, first: list[Word], more: Clause, later: list[Word]
) -> bool:
    """Whether a first sentence that states something ("The wifi is down.", "The desk is
    by the window.") is followed by a request for another named thing ("Can you check
    the router?", "Bring me the chair next to it."): the request's object is sought."""
    head = clause.head
    if head is None or head.kind != OBJECT or clause.head_negated or not asks_for_object(more):
        return False
    assert more.head is not None
    if _object_is_it(later):
        return False  # "The charger is in the conference room, can you bring it to my desk"
    return _is_statement(first) and _is_request(later) and not same_thing(head, more.head)


def _object_is_it(sentence: list[Word]) -> bool:
    """Whether a request's verb takes "it" / "them" as its object ("bring it to my
    desk"): the errand is about the thing said before."""
    i = _after_openers(sentence)
    rest = [w.text for w in sentence[i + 1 : i + 3]]
    return bool(rest) and (rest[0] in IT_WORDS or (rest[-1] in IT_WORDS and rest[0] == "me"))


def scene_then_target(clause: Clause, first: list[Word], more: Clause, later: list[Word]) -> bool:
    """Whether a first sentence that sets the scene ("there is a desk in the corner.")
    is followed by a description of another thing placed by it ("the chair in front of
    it is black and has wheels."): that thing, described in its own right, is the
    target, and the first one its landmark."""
    head, other = clause.head, more.head
    if head is None or other is None or head.kind != OBJECT or other.kind != OBJECT:
        return False
    if not other.labels or clause.head_negated or more.head_negated or same_thing(head, other):
        return False
    if len(first) < 2 or first[0].text != "there" or first[1].lemma != "be":
        return False
    if not later or later[0].text != "the":
        return False
    by_it = [
        c
        for c in other.constraints
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor
    ]
    by_name = any(
        isinstance(c, RelationConstraint) and set(c.landmark.target.labels) & set(head.labels)
        for c in other.constraints
    )  # "the range hood above the stove is stainless steel"
    said = [*other.constraints, *(d for c in by_it for d in c.landmark.constraints)]
    return bool(by_it or by_name) and any(isinstance(c, AttributeConstraint) for c in said)


def description_after_it(head: NP) -> list[Constraint]:
    """What "… next to it is black and has wheels" says after "it": spaCy's parse gives
    it to "it", the sentence says it of its subject."""
    return [
        d
        for c in head.constraints
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor
        for d in c.landmark.constraints
        if isinstance(d, AttributeConstraint)
    ]


def hand_over(context: Clause, more: Clause) -> None:
    """Make ``more``, a later sentence that took the target over, carry what the first
    sentence said of the place: its "it" points at the first sentence's thing, and the
    room and floor that sentence set hold unless ``more`` names its own."""
    assert more.head is not None and context.head is not None
    _point_it_at(more.head, context.head)
    more.places += _scope_left_open(context, more)


def _point_it_at(head: NP, context: NP) -> None:
    """Relations of ``head`` placed by "it" ("the chair next to it") take the thing the
    sentence before named as their landmark."""
    landmark = context.landmark()
    head.constraints = [
        replace(c, landmark=landmark, text=c.text.replace(ANAPHOR, context.noun))
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor
        else c
        for c in head.constraints
    ]


def _scope_left_open(context: Clause, more: Clause) -> list[Constraint]:
    """The room and floor a stating sentence set ("In the family room there is a
    bookshelf …") for a request that names none of its own ("Put the DVD on the top
    shelf.")."""
    assert more.head is not None
    own = {c.kind for c in [*more.places, *more.head.constraints]}
    return [c for c in context.places if c.kind in ("room", "floor") and c.kind not in own]


def same_thing(head: NP, other: NP) -> bool:
    """Whether a later sentence's subject is the target again ("it", "the one", "the
    chair" after "a chair")."""
    if other.kind in (ANAPHOR, ONE):
        return True
    if other.kind != OBJECT:
        return False
    if set(other.labels) & set(head.labels):
        return True
    # "a kitchen cabinet. It is the cabinet above …", "a rolling chair … the chair …":
    # the same thing named more or less exactly
    return any(
        is_kind_of(mine, theirs) or is_kind_of(theirs, mine)
        for mine in head.labels
        for theirs in other.labels
    )


def asks_for_object(more: Clause) -> bool:
    """Whether a later sentence asks for a named object of its own ("Which chair is
    closest to my right hand?", "Is the radiator behind me?")."""
    head = more.head
    return head is not None and head.kind == OBJECT and bool(head.labels) and not more.head_negated
