"""How a later sentence of a request relates to the first one when it names another
thing: the thing of the first sentence, or the other one, is the target.

- A first sentence that states how things are, followed by a request for another named
  thing ("The wifi is down. Can you check the router?"): the request's object.
- A first sentence that sets the scene with "there is", followed by another thing placed
  by it and described in its own right ("there is a desk in the corner. the chair in
  front of it is black and has wheels."): that thing, the first one its landmark.
- A later sentence that says which thing is meant ("the recycling bin on its left is
  the one", "the cabinet we want is the one above the sink"): that thing, whatever the
  first sentence was.
- Otherwise a later sentence describes the first sentence's target ("… It is white.").
"""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    Constraint,
    Landmark,
    RelationConstraint,
    Superlative,
)
from inherit_sg.retrieval.rules.clause import Clause
from inherit_sg.retrieval.rules.cursor import weighted
from inherit_sg.retrieval.rules.grammar import Grammar
from inherit_sg.retrieval.rules.phrase import ANAPHOR, FLOOR, NP, OBJECT, ONE, ROOM
from inherit_sg.retrieval.rules.rewording import ends_with_thing
from inherit_sg.retrieval.rules.sentences import FINITE, IT_WORDS, QUESTION_OPENERS
from inherit_sg.retrieval.rules.tokens import COMMA, Word
from inherit_sg.vocab.lexicon import lexicon
from inherit_sg.vocab.objects import canonical_label, is_kind_of, labels_for
from inherit_sg.vocab.rooms import room_type

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
    # a run-on split off a statement keeps the dependency of the whole ("so bring …": conj)
    split_off = verb.dep in ("conj", "dep", "ccomp", "parataxis", "advcl", "xcomp")
    return verb.pos == "VERB" and verb.tag == "VB" and (verb.dep == "ROOT" or modal or split_off)


_FINITE_OR_MODAL = FINITE | {"MD"}  # "it won't turn on": a modal is finite too


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
    ) or (  # "the coffee machine isn't working": the finite word is the root's auxiliary
        any(w.pos == "AUX" and w.tag in _FINITE_OR_MODAL and w.dep == "aux" for w in sentence)
        and any(w.dep == "ROOT" and w.pos == "VERB" for w in sentence)
    )  # not "The plant that we never water.": a phrase with a relative clause
    return finite and not _is_request(sentence)


def statement_then_request(
    clause: Clause, first: list[Word], more: Clause, later: list[Word]
) -> bool:
    """Whether a first sentence that states something ("The wifi is down.", "The desk is
    by the window.") is followed by a request for another named thing ("Can you check
    the router?", "Bring me the chair next to it."): the request's object is sought."""
    head = clause.head
    if head is None or not asks_for_object(more):
        return False
    if head.kind != OBJECT and not (head.kind == ANAPHOR and not head.labels):
        return False  # "it won't turn on, bring me a spare battery": "it" is left as said
    if clause.head_negated and not states_absence(first):
        return False
    assert more.head is not None
    if _object_is_it(later):
        return False  # "The charger is in the conference room, can you bring it to my desk"
    asks = _is_request(later) or (later[0].text in QUESTION_OPENERS and later[0].text != "is")
    return _is_statement(first) and asks and not same_thing(head, more.head)


def states_absence(sentence: list[Word]) -> bool:
    """Whether a sentence says that a thing is not there ("there's no milk left", "no ice
    left in the freezer"): the thing is missing, not ruled out of what is asked next."""
    return any(w.text == "no" and w.dep == "det" for w in sentence) and not any(
        w.text in ("not", "except", "but") for w in sentence
    )


def _object_is_it(sentence: list[Word]) -> bool:
    """Whether a request's verb takes "it" / "them" as its object ("bring it to my
    desk"): the errand is about the thing said before."""
    i = _after_openers(sentence)
    rest = [w.text for w in sentence[i + 1 : i + 3]]
    return bool(rest) and (rest[0] in IT_WORDS or (rest[-1] in IT_WORDS and rest[0] == "me"))


def _has_finite_verb(words: list[Word]) -> bool:
    """Whether ``words`` hold a finite verb (by spaCy: a verb or auxiliary in the present
    or past tense), so that they make a clause rather than a bare phrase."""
    return any(w.tag in FINITE and w.pos in ("VERB", "AUX") for w in words)


def scene_then_target(
    clause: Clause, first: list[Word], more: Clause, later: list[Word], fronted: bool = False
) -> bool:
    """Whether a first sentence that sets the scene ("there is a desk in the corner.",
    "sink under the mirror.") is followed by another thing placed by the first one and
    described in its own right ("the chair in front of it is black and has wheels.",
    "pillow on the left side of it, white", "keyboard in front of the right monitor") or
    put first by its place (``fronted``: "to the right of it is a paper cutter"): that
    thing is the target, and the first one its landmark.

    Otherwise the first thing stays the target, as most descriptions name it first: a
    first sentence that says which thing is meant ("this is a wooden chair.", "find the
    lamp"), a later sentence that only places another thing by it ("a round table is
    beside it", "there are papers pinned on it"), and any description after one that
    said more of the first thing (the caller checks that)."""
    head, other = clause.head, more.head
    if head is None or other is None or head.kind != OBJECT or other.kind != OBJECT:
        return False
    if not other.labels or clause.head_negated or more.head_negated or same_thing(head, other):
        return False
    if _sets_scene(first) is None or not later:
        return False
    by_it = [c for c in other.constraints if isinstance(c, RelationConstraint) and _by_it(c)]
    named = set(head.labels) | {
        label
        for c in head.constraints
        if isinstance(c, RelationConstraint)
        for label in c.landmark.target.labels
    }  # "a desk with two monitors on it. keyboard in front of the right monitor"
    by_name = any(
        isinstance(c, RelationConstraint) and set(c.landmark.target.labels) & named
        for c in other.constraints
    )  # "the range hood above the stove is stainless steel"
    if not (by_it or by_name):
        return False
    if fronted:
        return True
    several = any(w in ("and", "or") for w in head.words)  # "there's a couch and a TV."
    if several and later[0].text == "the" and _sets_scene(later) == "statement":
        return True  # "… The remote is on the couch."
    if not _has_finite_verb(later):
        return True  # "pillow on the left side of it, white"
    said = [*other.constraints, *(d for c in by_it for d in c.landmark.constraints)]
    described = any(_describes(c) for c in said) or _says_what_it_is(later)
    # "the chair …" or, typed, "coffee table in front of it …" (not "a table is beside it")
    named_first = later[0].text == "the" or later[0].pos in ("NOUN", "PROPN", "ADJ")
    return described and named_first and (by_name or _it_in_subject(later))


def _says_what_it_is(sentence: list[Word]) -> bool:
    """Whether a sentence's subject is said to be a kind of thing ("the picture on the
    wall above it is a landscape painting", "the desk in front of it is the teachers
    desk"): a finite "be" followed by a determiner and, later, a noun."""
    for k, word in enumerate(sentence[:-2]):
        if word.lemma == "be" and word.tag in FINITE:
            after = sentence[k + 1 :]
            return after[0].text in ("a", "an", "the") and any(w.pos == "NOUN" for w in after)
    return False


def _describes(constraint: Constraint) -> bool:
    """Whether a constraint describes its thing in its own right: an attribute
    ("is black") or a thing it has ("has a lamp on it")."""
    if isinstance(constraint, AttributeConstraint):
        return True
    return isinstance(constraint, RelationConstraint) and constraint.predicate == "with"


# First words of a sentence that says which thing is meant ("this is …", "it's the …").
_IDENTIFYING = frozenset({"this", "that", "it", "its", "these", "those", "here"})


def split_scene(sentence: list[Word]) -> list[list[Word]]:
    """A first sentence that sets the scene and runs on after a comma into a sentence of
    its own ("theres a fridge in the kitchen, the microwave next to it is silver", "tall
    cabinet in the corner, on top of it theres a box") as two sentences."""
    for j, word in enumerate(sentence):
        if word.text != "," or j < 2 or j + 3 >= len(sentence):
            continue
        after = sentence[j + 1 :]
        asks = after[0].text in ("how", "what", "which", "where")  # ", how many chairs …"
        if after[0].text != "the" and after[0].pos != "ADP" and not asks:
            continue
        own_verb = _has_finite_verb(after)
        scene = _sets_scene(sentence[:j])
        if own_verb and (scene == "there" or (scene == "fragment" and not asks)):
            return [sentence[:j], after]
    return [sentence]


def _sets_scene(sentence: list[Word]) -> str | None:
    """How a first sentence sets the scene: "there" ("there is a desk …", "you see the
    big window?", "see the washing machine?", "do you see the microwave?"), "fragment" (a
    thing and its place, no verb: "sink under the mirror", or a thing that stands
    somewhere: "a couch sits under the window"), "statement" ("the bed is in the middle
    of the room"), or None for a sentence that says which thing is meant ("this is a
    chair", "find the lamp", "the chair is brown")."""
    words = [w for w in sentence if w.text != ","]
    if len(words) < 2 or words[0].text in _IDENTIFYING:
        return None
    if words[0].text == "there" and words[1].lemma == "be":
        return "there"
    if words[0].text == "you" and words[1].lemma == "see":
        return "there"  # "you see the desk facing the wall?"
    texts = [w.text for w in words[:3]]
    if texts[:1] == ["see"] or texts in (["do", "you", "see"], ["can", "you", "see"]):
        return "there"  # "See the washing machine? The detergent bottle on top of it."
    if words[0].pos == "VERB" and words[0].tag == "VB" and canonical_label(words[0].text) is None:
        return None  # "find the copier", "select the chair" (not "sink under the mirror")
    verbs = [w for w in words if w.tag in FINITE and w.pos in ("VERB", "AUX")]
    if not verbs:  # a thing and its place ("from the couch, …" is a viewpoint)
        placed = words[0].pos != "ADP" and any(w.pos == "ADP" for w in words)
        return "fragment" if placed else None  # a bare description names the target
    k = words.index(verbs[0])
    subject = " ".join(w.text for w in words[:k] if w.pos != "DET")
    if verbs[0].lemma in _HOLDING and subject and room_type(subject) is not None:
        return "there"  # "The bathroom has a sink, a toilet and a bathtub."
    if verbs[0].lemma != "be":
        thing_stands = k > 0 and words[k - 1].pos in ("NOUN", "PROPN")
        return "fragment" if verbs[0].lemma in _STANDING and thing_stands else None
    after = words[words.index(verbs[0]) + 1 :]
    return "statement" if after and after[0].pos == "ADP" else None


# Verbs by which a room sets the scene ("the bathroom has a sink and a tub").
_HOLDING = frozenset({"have", "contain", "hold", "feature"})
# Verbs that say where a thing stands ("a couch sits under the window").
_STANDING = frozenset({"sit", "stand", "hang", "lean", "lie", "rest"})


def _it_in_subject(sentence: list[Word]) -> bool:
    """Whether "it" stands inside the sentence's subject, before its verb ("the toilet
    paper on the wall next to it is a big roll"): the subject is placed by the thing said
    before and described in its own right. After the verb ("the table is in front of
    it") the sentence places the thing said before."""
    verb = next((i for i, w in enumerate(sentence) if w.dep == "ROOT"), len(sentence))
    return any(w.text == "it" for w in sentence[:verb])


def _by_it(relation: RelationConstraint) -> bool:
    """Whether a relation places its thing by "it", directly ("next to it") or through
    its landmark ("on the counter next to it")."""
    if relation.landmark.target.anaphor:
        return True
    return any(
        isinstance(c, RelationConstraint) and c.landmark.target.anaphor
        for c in relation.landmark.constraints
    )


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
    head.constraints = _pointed(head.constraints, context.landmark(), context.noun)


def point_it_at_view(clause: Clause) -> None:
    """Relations of the target placed by "it" that nothing before explained take the
    thing the speaker faces or stands at ("when looking at the whiteboard, the door to
    its right", "facing the sofa, the side table on its left")."""
    view, head = clause.viewpoint, clause.head
    if view is None or head is None or not view.landmark.target.labels:
        return
    head.constraints = _pointed(head.constraints, view.landmark, view.landmark.target.noun)


def _pointed(constraints: list[Constraint], landmark: Landmark, noun: str) -> list[Constraint]:
    """``constraints`` with "it" as a landmark, here or one landmark down ("on the counter
    next to it"), read as ``landmark`` (named ``noun``)."""
    out: list[Constraint] = []
    for c in constraints:
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor:
            # "at the end of it closest to the fridge": "it" is one thing, the choice
            # among several is the target's
            out += [d for d in c.landmark.constraints if isinstance(d, Superlative)]
            c = replace(c, landmark=landmark, text=c.text.replace(ANAPHOR, noun))
        elif isinstance(c, RelationConstraint) and any(
            isinstance(d, RelationConstraint) and d.landmark.target.anaphor
            for d in c.landmark.constraints
        ):
            inner = tuple(_pointed(list(c.landmark.constraints), landmark, noun))
            c = replace(c, landmark=replace(c.landmark, constraints=inner))
        out.append(c)
    return out


def _scope_left_open(context: Clause, more: Clause) -> list[Constraint]:
    """The room and floor a stating sentence set ("In the family room there is a
    bookshelf …") for a request that names none of its own ("Put the DVD on the top
    shelf.")."""
    assert more.head is not None
    own = {c.kind for c in [*more.places, *more.head.constraints]}
    return [c for c in context.places if c.kind in ("room", "floor") and c.kind not in own]


# Verbs of the speaker's choice in "the cabinet we want", "the one I mean".
_PICKING = frozenset({"want", "need", "mean", "look", "talk", "refer", "after"})
_CHOOSERS = frozenset({"i", "we", "you"})


def picks_out(sentence: list[Word]) -> bool:
    """Whether a sentence says that the thing it opens with is the one meant: "the
    recycling bin on its left side is the one", "the kitchen cabinet we want is …",
    "the lamp by the door is the one I mean" ("this is the one" names nothing new)."""
    if _names_the_object(sentence):
        return True  # a short closing "it is the floor lamp", "the object is the projector"
    if _speaker_means(sentence):
        return True  # "I'm talking about the vise", "I mean the one with the lid"
    if _denies_then_names(sentence):
        return True  # "not the bench tho, the metronome sitting on the piano"
    if not sentence or sentence[0].text in _IDENTIFYING:
        return False
    if sentence[0].pos not in ("DET", "ADJ", "NOUN", "PROPN"):
        return False
    texts = [w.text for w in sentence]
    for j in range(1, len(sentence) - 2):
        if sentence[j].lemma == "be" and texts[j + 1 : j + 3] == ["the", "one"]:
            # a thing named before "is the one"; a material is none ("…, black metal, and
            # it is the one on the far right")
            materials = lexicon().materials
            return any(w.pos in ("NOUN", "PROPN") and w.text not in materials for w in sentence[:j])
    for j in range(1, len(sentence) - 2):  # "the cart is what I want"
        if sentence[j].lemma == "be" and texts[j + 1] == "what" and texts[j + 2] in _CHOOSERS:
            k = j + 4 if texts[j + 3 : j + 4] in (["am"], ["are"]) else j + 3
            if k < len(sentence) and sentence[k].lemma in _PICKING:
                # the subject's thing, before any place it has ("the bench in front of it")
                cut = next((m for m in range(1, j) if sentence[m].pos == "ADP"), j)
                return ends_with_thing(sentence[:cut])
    for i in range(1, len(sentence) - 1):  # "the cabinet (that) we want …"
        j = i + 1 if texts[i] in ("that", "which") else i
        if j + 1 >= len(sentence) or texts[j] not in _CHOOSERS:
            continue
        k = j + 2 if texts[j + 1] in ("are", "am") and j + 2 < len(sentence) else j + 1
        if sentence[k].lemma in _PICKING and ends_with_thing(sentence[:i]):
            return True
    return False


# Openings of a short sentence that names the object meant: "it is the …", "the object
# is the …", "the target is the …".
_NAMING_OPENINGS = (
    ("it", "is", "the"),
    ("the", "object", "is", "the"),
    ("the", "target", "is", "the"),
)
# Openings that can only name the thing meant, however long what follows ("this
# description is for the basket on top of the fridge").
_DESCRIBED = tuple(
    (*first, "is", word, "the")
    for first in (("this", "description"), ("the", "description"), ("this", "text"))
    for word in ("for", "about", "of")
)
_DESCRIPTION_OPENINGS = (
    *_DESCRIBED,
    ("the", "object", "is", "the"),
    ("the", "target", "is", "the"),
    ("the", "target", "object", "is", "the"),
)


def _names_the_object(sentence: list[Word]) -> bool:
    """Whether ``sentence`` is only "it is the X" / "the object is the X" (at most three
    words after the opening, ending on a noun): it says which thing is meant."""
    texts = tuple(w.text for w in sentence)
    long_opening = next((o for o in _DESCRIPTION_OPENINGS if texts[: len(o)] == o), None)
    if long_opening is not None:  # "this description is for the basket on the fridge"
        after = sentence[len(long_opening) : len(long_opening) + 3]
        return any(w.pos in ("NOUN", "PROPN") for w in after)
    opening = next((o for o in _NAMING_OPENINGS if texts[: len(o)] == o), None)
    if opening is None:
        return False
    rest = sentence[len(opening) :]
    return 1 <= len(rest) <= 3 and rest[-1].pos in ("NOUN", "PROPN")


def _denies_then_names(sentence: list[Word]) -> bool:
    """Whether ``sentence`` opens "not the X, the Y …": it rules X out and names Y."""
    if len(sentence) < 5 or sentence[0].text != "not" or sentence[1].pos != "DET":
        return False
    comma = next((k for k, w in enumerate(sentence) if w is COMMA), None)
    if comma is None or comma + 2 >= len(sentence) or sentence[comma + 1].pos != "DET":
        return False
    return sentence[comma + 2].text not in ("one", "ones")  # "…, the one for the AC": same kind


# Verbs after "I'm" that say which thing the speaker means: "I'm talking about the vise".
_MEANING = (("talking", "about"), ("referring", "to"), ("thinking", "of"))


def _speaker_means(sentence: list[Word]) -> bool:
    """Whether ``sentence`` opens "I'm talking about …", "I am referring to …", "I mean
    the …", "I need the …", followed by a thing."""
    texts = [w.text for w in sentence]
    if texts[:1] != ["i"]:
        return False
    k = 2 if texts[1:2] == ["am"] else 1
    if texts[k : k + 1] == ["mean"]:
        k += 1
    elif texts[k : k + 1] in (["need"], ["want"]):
        k += 1  # a thing, not "I need a nap"
        if not any(canonical_label(w.lemma) for w in sentence[k:] if w.pos == "NOUN"):
            return False
    elif tuple(texts[k : k + 2]) in _MEANING:
        k += 2
    else:
        return False
    return k < len(sentence) and sentence[k].pos == "DET" and ends_with_thing(sentence[k:])


# Where a sentence may run on into a part that says which thing is meant, and the words
# that may follow the break (", and the thing I mean is …").
_RUN_ON_BREAKS = frozenset({",", ";", "-"})
_RUN_ON_LINKS = frozenset({"and", "but", "so"})


def split_at_pick(sentence: list[Word], errands: bool = False) -> list[list[Word]]:
    """A sentence that runs on after a comma (and "and") into a part that says which
    thing is meant ("in the kitchen there's a counter …, the kitchen cabinet we want is the one
    above the sink, …", "… with a diaper pail beside it, and the thing I mean is the
    diaper pail") as two sentences."""
    for j, word in enumerate(sentence):
        if word.text not in _RUN_ON_BREAKS or j < 2:
            continue
        k = j + 1
        while k < len(sentence) and sentence[k].text in _RUN_ON_LINKS:
            k += 1
        if [w.text for w in sentence[k : k + 2]] == ["the", "one"]:
            continue  # "…, and the one I mean is the one with …": says more of the same
        if k < len(sentence) and sentence[k].text == "not":
            continue  # "the remote, not the tv one, the one for the AC": read whole
        rest = sentence[k:]
        pointing = _closing_pointer(rest) or (errands and points_back(rest))
        if k < len(sentence) and (picks_out(rest) or pointing):
            return [sentence[:j], sentence[k:]]  # "… a fruit bowl, that's what I mean"
    return [sentence]


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


def thing_the_room_holds(clause: Clause, sentence: list[Word], notes: list[str]) -> None:
    """ "which room has the piano?", "which bedroom has the crib?", "which room is the
    recycling bin in", "does the bathroom have a hair dryer": the question is answered by
    finding the thing, so the thing is the target and a room kind the question names
    ("bedroom") places it. A room asked for by what it lacks ("which bathroom doesn't
    have a bathtub") stays the target. In place."""
    head = clause.head
    if head is None or head.kind != ROOM or clause.head_negated or not sentence:
        return
    asks = sentence[0].pos == "AUX" and sentence[0].lemma in ("do", "have")
    if sentence[0].text not in ("which", "what") and not asks:
        return  # a question: "which room has …", "does the bathroom have a hair dryer"
    if any(
        isinstance(c, Superlative) and c.measure in ("most", "fewest") for c in head.constraints
    ):
        return  # "which room has the most chairs": the room is asked for
    held = [
        c
        for c in head.constraints
        if isinstance(c, RelationConstraint) and c.predicate == "contains"
    ]
    if len(held) != 1 or held[0].negated or not held[0].landmark.target.labels:
        return
    target = held[0].landmark.target
    if not any(canonical_label(label) for label in target.labels):
        return  # "which room gets the most sun": no thing to find
    thing = NP(
        kind=OBJECT,
        labels=list(target.labels),
        words=target.noun.split(),
        constraints=list(held[0].landmark.constraints),
        plural=target.plural,
        known=True,
    )
    rest = [c for c in head.constraints if c is not held[0] and c.kind != "label"]
    room = [Grammar.room_place(head)] if head.labels else []
    places = [c for c in rest if c.kind in ("room", "area", "floor")]
    # what else the room's phrase said ("… in on monday") stays with the thing
    thing.constraints += [c for c in rest if c.kind not in ("room", "area", "floor")]
    thing.places = [*room, *places, *head.places]
    notes.append(f"'{sentence[0].text} {head.noun} …': found by finding {target.noun!r}")
    clause.head = thing


# Words that count: "the shelf with the most books", "the desk with the fewest monitors".
_COUNT_MEASURES = {"most": "most", "fewest": "fewest", "least": "fewest"}


def count_superlative(clause: Clause, words: list[Word], notes: list[str]) -> None:
    """ "the shelf with the most books", "which room has the fewest chairs", "the floor
    with the most bedrooms": the head holds things of the kind a relation of it names
    (its landmark), and "the most" / "the fewest" before that kind ranks the candidates by
    how many they hold: a ``most`` / ``fewest`` superlative on that landmark. A storey
    noun ("which floor has the most bedrooms") then names a storey, not the floor one
    walks on. In place."""
    head = clause.head
    if head is None or clause.head_negated:
        return
    texts = [w.text for w in words]
    for k, text in enumerate(texts):
        measure = _COUNT_MEASURES.get(text)
        if measure is None or k == 0 or texts[k - 1] != "the":
            continue
        j = k + 1
        if texts[j : j + 2] == ["number", "of"]:
            j += 2  # "the most number of chairs"
        counted = next((w for w in words[j : j + 3] if w.pos in ("NOUN", "PROPN")), None)
        if counted is None or not (canonical_label(counted.lemma) or room_type(counted.lemma)):
            continue  # "which room gets the most sun": nothing to count
        for con in head.constraints:
            if (
                isinstance(con, RelationConstraint)
                and not con.negated
                and con.predicate in ("with", "contains", "supports", "on", "near", "next_to")
                and con.landmark.target.noun.split()[-1:] == [counted.text]
            ):
                head.constraints.append(
                    Superlative(
                        measure=measure,
                        landmark=con.landmark,
                        weight=weighted("superlative", None),
                        text=f"the {text} {con.landmark.target.noun}",
                    )
                )
                notes.append(f"'the {text} {counted.text}': ranked by how many it holds")
                if (
                    head.kind == OBJECT
                    and head.words[-1:]
                    and head.words[-1] in lexicon().floor_nouns
                ):
                    head.kind, head.labels = FLOOR, ["floor"]
                    head.constraints = [c for c in head.constraints if c is not con]
                return


# Verbs of a closing errand that points back at the last thing named ("Go to that.").
_POINTING_ERRANDS = frozenset({"go", "find", "get", "grab", "bring", "fetch", "pick", "choose"})


# What follows "that's" in a closing sentence that points at the thing named before it.
_POINTING_CLOSERS = (
    ["the", "one"], ["it"], ["what", "i", "mean"], ["what", "i", "want"], ["what", "i", "need"],
    ["what", "i", "am", "after"], ["what", "i", "am", "looking", "for"], ["the", "one", "i", "mean"],
    ["the", "one", "i", "want"], ["what", "we", "need"], ["what", "we", "want"],
    ["the", "object"], ["the", "target"], ["the", "target", "object"], ["our", "target"],
    ["the", "one", "described"], ["the", "object", "described"],
)  # fmt: skip


def last_clause(sentence: list[Word]) -> list[Word]:
    """The last clause of a sentence that names several things in turn ("above the sink
    is a window and on the windowsill sits a small cactus" → "on the windowsill sits a
    small cactus"): what a closing "that is the one" points at."""

    def clause(words: list[Word]) -> bool:
        return _has_finite_verb(words) and any(w.pos == "NOUN" for w in words)

    for k in range(len(sentence) - 2, 0, -1):
        if sentence[k].text == "and" and clause(sentence[k + 1 :]) and clause(sentence[:k]):
            return sentence[k + 1 :]
    return sentence


def _closing_pointer(sentence: list[Word]) -> bool:
    """ "that's the one", "that's what I mean", "this is what I'm after"."""
    texts = [w.text for w in sentence if w.text not in (",", "please", "just", ".", "!")]
    return texts[:2] in (["that", "is"], ["this", "is"]) and texts[2:] in _POINTING_CLOSERS


def points_back(sentence: list[Word]) -> bool:
    """Whether ``sentence`` is only an errand at "that" / "it" / "this one" ("Go to that.",
    "Find that.", "grab that one"): the thing meant is the last one named before it."""
    if _closing_pointer(sentence):
        return True
    texts = [w.text for w in sentence if w.text not in (",", "please", "just", ".", "!")]
    if not texts or sentence[0].lemma not in _POINTING_ERRANDS or len(texts) > 4:
        return False
    rest = texts[1:]
    if rest[:1] in (["to"], ["me"]):
        rest = rest[1:]
    return rest in (["that"], ["this"], ["it"], ["that", "one"], ["this", "one"])


# Verbs that open a sentence picking one thing ("pick the one nearest the fridge").
_PICK_VERBS = frozenset({"pick", "choose", "select", "take", "grab", "get", "find", "want", "need"})


def several_kinds(sentences: list[list[Word]]) -> list[tuple[tuple[str, ...], str]]:
    """The kinds ``sentences`` name as several ("there are baskets", "two nightstands",
    "three glass pendant lights", "lots of plants"), in order: their labels and noun."""
    out: list[tuple[tuple[str, ...], str]] = []
    for sentence in sentences:
        for k, word in enumerate(sentence):
            if word.pos != "NOUN" or (k + 1 < len(sentence) and sentence[k + 1].pos == "NOUN"):
                continue  # only the last noun of a phrase ("pendant lights", not "pendant")
            before = sentence[max(0, k - 4) : k]
            counted = any(w.tag == "CD" and w.text not in ("one", "1") for w in before)
            if word.tag != "NNS" and not counted:
                continue
            named = [w.lemma for w in sentence[max(0, k - 1) : k + 1] if w.pos == "NOUN"]
            for phrase in (" ".join(named), word.lemma):
                labels = labels_for(phrase)
                if labels:
                    out.append((labels, phrase))
                    break
    return out


def _picking_sentence(sentence: list[Word]) -> bool:
    """Whether a sentence only says which one is meant: a bare phrase ("The basket on
    the far left."), "it's the …", or a verb of picking ("Pick the one nearest the
    fridge.", "I need the biggest one")."""
    texts = [w.text for w in sentence if w.pos != "PUNCT"]
    if not texts:
        return False
    if texts[:2] in (["it", "is"], ["that", "is"], ["this", "is"]):
        return True
    if sentence[0].lemma in _PICK_VERBS and sentence[0].tag == "VB":
        return True
    if texts[0] in ("i", "we") and len(sentence) > 1 and sentence[1].lemma in _PICK_VERBS:
        return True
    return not _has_finite_verb(sentence)


def one_of_several(
    kinds: list[tuple[tuple[str, ...], str]], clause: Clause, more: Clause, later: list[Word]
) -> bool:
    """Whether a later sentence picks one of the several things of a kind named before:
    "The mudroom has a row of hooks and a bench. Under the bench there are baskets. The
    basket on the far left.", "… a queen bed and two nightstands. Its the nightstand
    closer to the window.", "… three glass pendant lights. Pick the one nearest the
    fridge.", "The sunroom has lots of plants. I need the biggest one". A bare "one"
    takes the kind named last; ``more`` is made to carry it."""
    head, other = clause.head, more.head
    if head is None or other is None or more.head_negated or not kinds:
        return False
    if not _picking_sentence(later):
        return False
    if not any(w.pos == "NOUN" or w.text == "one" for w in later):
        return False  # "It is round and made of glass": said of the target
    if other.kind == OBJECT and other.labels and not other.plural:
        if head.kind == OBJECT and same_thing(head, other):
            return False
        return any(set(other.labels) & set(k) for k, _ in kinds)
    if other.kind == ONE and not other.labels and head.kind == ROOM:
        # only after a room that sets the scene; after a thing, "the one" is that thing
        labels, noun = kinds[-1]
        other.kind, other.labels, other.words, other.known = (
            OBJECT,
            list(labels),
            noun.split(),
            True,
        )
        return True
    return False
