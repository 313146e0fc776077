"""Top level of a request: find the head noun phrase and attach everything else to it.

Phrases may come in any order ("in the kitchen, the red mug"): place phrases and
relations met before the head wait for it. Verb phrases give functions; a second noun
phrase after the head is a coordination ("a chair or a stool"), an apposition ("the red
one"), or, negated, an excluded label ("a seat but not a stool").
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace

from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    AttributeConstraint,
    Constraint,
    LabelConstraint,
    Landmark,
    PlacementConstraint,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
    Viewpoint,
)
from inherit_sg.retrieval.rules import verbs
from inherit_sg.retrieval.rules.cursor import weighted
from inherit_sg.retrieval.rules.grammar import VIEW_OPENERS as _VIEW_OPENERS
from inherit_sg.retrieval.rules.grammar import Grammar
from inherit_sg.retrieval.rules.phrase import (
    ANAPHOR,
    AREA,
    FLOOR,
    GENERIC,
    GENERIC_AREA,
    NP,
    OBJECT,
    ONE,
    ROOM,
    VAGUE,
)
from inherit_sg.retrieval.rules.tagger import Tok
from inherit_sg.retrieval.rules.tokens import colour_or_material
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab.colours import colour_words, shade_words
from inherit_sg.vocab.lexicon import lexicon

_SKIP = (
    "filler", "wh", "modal", "seeker", "comma", "and", "or", "but", "adv", "than", "overb",
    "be", "rel", "of", "to", "from", "dir", "for", "while", "have", "fverb", "shade", "sub",
    "like", "seek",
)  # fmt: skip
# Subjects of a frame that introduces the target: "this is a bed", "it's the lamp", "there
# are two chairs", "these are the pillows".
_FRAME_SUBJECTS = frozenset({"this", "that", "it", "these", "those", "they", "there", "here"})
# Particles and prepositions after a request verb that lead to its object ("walk over to").
# Particles between a viewpoint verb and its landmark ("come down the stairs").
# Framing words that point at the thing wanted ("take me to the lamp").
# Verbs of searching a place for a thing ("check the counter for my watch").
_SEARCH_VERBS = frozenset({"check", "search", "scan", "inspect", "comb", "try"})
# Verbs whose object is what the request seeks: "can you get the salt", "fetch my keys".
_FETCH_VERBS = frozenset(
    {"get", "fetch", "bring", "grab", "find", "locate", "retrieve", "take", "carry", "move",
     "collect", "deliver", "return"}
)  # fmt: skip
_DIRECTIVES = frozenset({
    "take me to", "take me back to", "show me", "guide me to", "lead me to", "walk me to",
    "point me to", "point me toward", "point me towards", "navigate to", "bring me",
    "get me", "help me find", "help me locate", "help me get to", "i need to find",
    "i want to find", "i want to get to", "i want to go to", "go to", "head to",
    "search for", "look for", "locate", "find me",
})  # fmt: skip
_ENTERING = frozenset({"in", "into", "inside", "through"})
# Words of a heading with no landmark ("looking in", "look to your right").
_HEADING_WORDS = frozenset({"in", "inside", "into", "out", "ahead", "straight", "forward", "to",
                            "towards", "toward", "the", "room", "across"})  # fmt: skip
_PARTICLES = frozenset({
    "down", "up", "in", "into", "through", "out", "from", "of", "to", "toward", "towards",
    "at", "by", "past", "along", "across", "around", "over", "onto", "inside",
})  # fmt: skip
_SWITCH_VERBS = frozenset({"turn", "switch", "shut", "power", "flip", "flick"})
# Verbs of staying somewhere, and the prepositions that then name where ("wait by the
# front door", "stand next to the bookshelf").
_WAIT_VERBS = frozenset({"stand", "wait", "stay", "park", "stop"})
_BESIDE = frozenset({"next to", "by", "near", "beside", "at", "in front of", "close to"})
# Where one is asked to stand or wait: "stand on the rug", "wait behind the sofa" (not
# "a speaker standing on the floor").
_WAIT_PLACES = _BESIDE | {"on", "behind", "under", "beneath", "opposite"}
_TOWARDS = frozenset({"over", "up", "to", "towards", "toward", "at", "on", "back", "across"})


# Prepositions that seat the speaker on what follows ("sitting on the sofa", "in bed").
_SEATS = frozenset({"on", "in", "upon", "onto", "into"})
# "When I'm on the couch, …" (seated), "if you're at the sink, …" (standing there).
_BEING_AT = {"on": "seated", "at": "from"}
_BEING = re.compile(r"\b(i|i'm|im|you|you're|youre|we|we're|were)\b")
# Last words of a viewpoint phrase that needs no landmark ("when you walk in", "as you
# come up"), so that a thing and "is" after it open the main clause.
_COMPLETE_VIEW_ENDS = frozenset({"in", "inside", "enter", "up", "down", "around", "round", "out"})
# "before I head out …": a time clause, context rather than the target.
_TIME_WORDS = frozenset({"before", "after", "once", "until"})
_PEOPLE = frozenset({"i", "we", "you", "they", "he", "she"})
# "counting from the curtains, …": the landmark ordinals are counted from.
_COUNTING = frozenset({"counting", "starting", "going", "numbering", "beginning", "count"})
# Viewpoint verbs that take the place as their object ("enter the kitchen, …"); the others
# name a place through a preposition ("stand at", "come through"), and with an object they
# are errands ("move the ottoman", "get the towel").
_TRANSITIVE_VIEW = frozenset({"enter", "pass", "reach", "climb", "approach"})


# Words that point at a thing shown or named before ("not that chair").
_POINTING = frozenset({"that", "this", "those", "these"})


@dataclass
class Clause:
    """What the top level found."""

    head: NP | None = None
    pending: list[Constraint] = field(default_factory=list)
    places: list[Constraint] = field(default_factory=list)
    functions: list[Constraint] = field(default_factory=list)
    # functions a problem statement implies ("I'm cold"): after any the request names
    implied: list[Constraint] = field(default_factory=list)
    excluded_labels: list[Constraint] = field(default_factory=list)
    exclude_previous: bool = False
    floor_np: NP | None = None
    head_negated: bool = False  # "not the sofa …": replaced by a positive phrase that follows
    # the places the negated head was given ("not the toilet in the WC, …")
    negated_head_places: list[Constraint] = field(default_factory=list)
    # the negated head was pointed at ("not that chair, …"): the thing shown before
    head_pointed: bool = False
    viewpoint: Viewpoint | None = None
    # the head is the object of a verb of fetching ("bring the juice"): a thing to carry,
    # even where its noun also names a purpose
    fetched: bool = False


# Verbs of a second command that say where to look ("remote again, check the couch").
_LOOKING = frozenset({"check", "try", "look", "search"})
# General kinds one looks on or in for a thing.
_FURNITURE_WORDS = ("furniture", "storage", "container", "surface")
# Possessive pronouns that say whose a thing is ("not mine", "not hers").
_OWNER_PRONOUNS = frozenset({"mine", "hers", "his", "yours", "ours", "theirs"})


def _furnishing(np: NP) -> bool:
    """Whether ``np`` names a piece of furniture, storage, a container or a surface."""
    return any(
        object_vocab.is_kind_of(label, general)
        for general in _FURNITURE_WORDS
        for label in np.labels
    )


def _as_placements(head: NP, cons: list[Constraint]) -> list[Constraint]:
    """A contrasting "one in the middle" after a head placed in its room ("the table in the
    corner, not the one in the centre") means the middle of the room, not of a row."""
    if not any(isinstance(c, PlacementConstraint) for c in head.constraints):
        return cons
    return [
        PlacementConstraint(where="centre", negated=c.negated, weight=c.weight, text=c.text)
        if isinstance(c, Superlative)
        and c.measure == "middle"
        and c.landmark is None
        and c.ordinal is None
        else c
        for c in cons
    ]


def _names_kind_of(np: NP, head: NP) -> bool:
    """Whether ``np`` names a thing of the kind ``head`` names."""
    return np.kind == OBJECT and bool(np.labels) and set(np.labels) == set(head.labels)


def _same_kind(out: Clause, np: NP) -> bool:
    """Whether a contrasting phrase names the kind of the negated head again ("not the
    toilet in the WC, the other toilet"), the head having details to negate."""
    head = out.head
    return head is not None and _names_kind_of(np, head) and _has_details(out)


def _described_anew(out: Clause, np: NP) -> bool:
    """Whether a "one" after a negated head only describes ("the winter one", "the big
    over-ear ones"): no place, no "other", and a head that was not pointed at."""
    return (
        bool(np.constraints)
        and all(isinstance(c, AttributeConstraint) for c in np.constraints)
        and not (np.places or np.other or out.head_pointed)
    )


def _has_details(out: Clause) -> bool:
    """Whether the clause's head says more than its kind (details, places), or was
    given places while negated."""
    head = out.head
    assert head is not None
    details = [c for c in head.constraints if c.kind != "label"]
    return bool(details or head.places or out.negated_head_places)


def _pointed_again(out: Clause, np: NP) -> bool:
    """Whether a phrase names again the kind of a negated head that was pointed at ("not
    this bottle, that bottle")."""
    return out.head_pointed and out.head is not None and _names_kind_of(np, out.head)


def turned_round(other: NP) -> list[Constraint]:
    """The relations of a phrase placed by "it" ("books on it", "a window above it", "a
    stool in front of it") seen from what "it" is: it supports the books, is under the
    window, behind the stool; the phrase, as described, is the landmark. Empty when
    nothing in the phrase points at "it"."""
    if other.kind != OBJECT or not other.labels:
        return []
    pointing = [
        c
        for c in other.constraints
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor and not c.negated
    ]
    described = [c for c in other.constraints if c.kind != "relation"]
    landmark = Landmark(target=other.target(), constraints=tuple(described))
    inverse = lexicon().with_inverse
    out: list[Constraint] = []
    for con in pointing:
        predicate = inverse.get(con.predicate, con.predicate)
        if predicate == "between":
            predicate = "near"  # "the sink is in the middle of it": one landmark, near it
        out.append(
            RelationConstraint(
                predicate=predicate, landmark=landmark, weight=con.weight,
                text=f"{predicate.replace('_', ' ')} {other.noun}",
            )
        )  # fmt: skip
    return out


def view_opener(g: Grammar) -> bool:
    """Whether a viewpoint clause opens here: "if you …", "as you walk in …"."""
    tok = g.peek()
    if tok is None or tok.text.split()[0] not in _VIEW_OPENERS:
        return False
    return tok.has("view") or g.at("seeker", k=1)


def _contrast(prev: Tok | None) -> bool:
    """Whether a phrase after ``prev`` can stand for the one a negated phrase ruled out
    ("not the sofa but the armchair", "not the sofa, the armchair"; not "… for the dog")."""
    return (
        prev is None
        or prev.has("but", "comma", "and", "seek", "filler", "be", "overb", "fverb")
        or (prev.text in ("instead", "rather"))
    )


def _ruled_out(cons: list[Constraint]) -> list[Constraint]:
    """What a phrase ruled out said of its thing, each negated. What it said negated
    ("not the trolley outside the kitchen, the one in the corridor") is dropped: it
    described the one not wanted, and the one wanted is described anew."""
    return [replace(c, negated=True) for c in cons if not c.negated]


def parts_of_head(head: NP, cons: list[Constraint]) -> list[Constraint]:
    """``cons`` with each "with X" relation turned into a part where X is a part of the
    head's kind: "the nightstands, the one without drawers" (the "one" could not know)."""
    from inherit_sg.nlp import lemma_phrase
    from inherit_sg.vocab import objects as object_vocab

    out: list[Constraint] = []
    for c in cons:
        noun = c.landmark.target.noun if isinstance(c, RelationConstraint) else ""
        word = lemma_phrase(noun.split()[-1]) if noun else ""
        if (
            isinstance(c, RelationConstraint)
            and c.predicate == "with"
            and word
            and any(object_vocab.is_part(word, label) for label in head.labels)
        ):
            value = " ".join([*c.landmark.target.attributes, word])
            c = AttributeConstraint(
                key="part", value=value, negated=c.negated, weight=weighted("attribute", None),
                text=c.text,
            )  # fmt: skip
        out.append(c)
    return out


def _related(head: NP, other: NP) -> bool:
    """Whether two phrases name related kinds (the same, one a kind of the other, or
    kinds under one general word): "a seat, except the stool"."""
    from inherit_sg.vocab import objects as object_vocab

    a, b = set(head.labels), set(other.labels)
    if a & b or not a:
        return True
    for x in a:
        for y in b:
            if object_vocab.is_kind_of(x, y) or object_vocab.is_kind_of(y, x):
                return True
            if set(object_vocab.is_a(x)) & set(object_vocab.is_a(y)) - {
                "furniture",
                "object",
                "thing",
            }:
                return True
    return False


# Passes over one token without consuming it before the clause walk skips it (a guard:
# every reading consumes what it reads, but a missed case must not hang a request).
_STALL_LIMIT = 4
# Determiners that open the thing sought after an opening "from the door" with no comma.
_OPENING_DETERMINERS = frozenset({"the", "a", "an", "this", "that"})


def _rooms_ruled_out(cons: list[Constraint]) -> list[Constraint]:
    """``cons`` with every room constraint negated."""
    return [replace(c, negated=True) if isinstance(c, RoomConstraint) else c for c in cons]


def _without_last_relation(
    cons: tuple[Constraint, ...],
) -> tuple[tuple[Constraint, ...], Landmark | None]:
    """``cons`` without the relation said last, however deep in its landmarks ("the foot
    of the bed looking at the headboard": the headboard's), and that relation's
    landmark (None when there is no relation)."""
    for k in range(len(cons) - 1, -1, -1):
        con = cons[k]
        if isinstance(con, RelationConstraint) and not con.negated:
            inner, seen = _without_last_relation(con.landmark.constraints)
            if seen is None:
                return cons[:k] + cons[k + 1 :], con.landmark
            deeper = replace(con, landmark=replace(con.landmark, constraints=inner))
            return (*cons[:k], deeper, *cons[k + 1 :]), seen
    return cons, None


class ClauseParser(Grammar):
    """Parses a whole request (after frame detection) into a :class:`Clause`."""

    view_end = -1  # token index just after a viewpoint clause
    framed = False  # "this is …", "it is the …" said which thing is meant
    more_sentences = False  # sentences follow this one (set by the request parser)
    _after_except = False  # the last negation was "except" / "apart from"
    later = False  # a sentence after the one that named the target (set by the parser)
    said_of_it = False  # a later sentence opened "it is …": it describes the target

    def parse(self, refine: bool = False, out: Clause | None = None) -> Clause:
        """Walk the tokens once, building the clause (continuing ``out`` when given)."""
        out = out if out is not None else Clause()
        last, stalled = -1, 0
        while (tok := self.peek()) is not None:
            stalled = stalled + 1 if self.i == last else 0
            last = self.i
            if stalled >= _STALL_LIMIT:  # no branch read this token: never loop on it
                self.notes.append(f"skipped {tok.text!r} (no reading)")
                self.advance()
                continue
            opener = view_opener(self)
            if self._clause_start() and self._counting_origin():
                continue  # "counting from the curtains, the third chair"
            if self._time_clause(out):
                continue  # "… before I head out the front door"
            if (opener or self._clause_start()) and self._viewpoint(out):
                continue  # "… the left one if you're facing the headboard"
            if self._clause_start() and self._frame():
                continue
            if tok.has("seek") and not verbs.is_verb_here(self):
                self._request_verb()
            elif verbs.is_verb_here(self) and not self._what_it_has(out, tok):
                verb_at = self.i
                keep_out = self._neg and verbs.kept_out(tok)
                made, candidate = verbs.parse_vp(self)
                if keep_out:
                    made, candidate = self._kept_out(made, candidate)
                out.functions += [c for c in made if c.kind == "function"]
                self._route(out, [c for c in made if c.kind != "function"])
                if candidate is not None:
                    out.places += candidate.places
                    candidate.places = []
                    if candidate.excluded and out.head is not None:
                        self._exclude(out, candidate)
                    elif out.head_negated and out.head is not None and candidate.kind == ONE:
                        # "avoid the blue bin, use the green one"
                        self._contrast_one(out, candidate)
                    elif out.head is None:
                        out.head = candidate
                        out.head_negated = candidate.excluded
                    elif self._acted_on(out, candidate):
                        pass  # "the kids can't reach the cereal": who acted is not sought
                    elif not (
                        self._replaces_head(out, candidate, False)
                        or self._next_errand(out, candidate, False, verb_at)
                    ):
                        self._second_phrase(out, candidate, False, False)
            elif tok.has("seeker") and self.at("modal", "wh", k=-1):
                self.advance()  # "where would one go"
            elif tok.has("for", "while"):
                self._purpose(out)
            elif tok.has("but") and self.at("det", k=1) and self.at("one", k=2) and out.head:
                self.advance()  # "any throw but the one on the couch"
                self.negate()
                self._after_except = True
            elif tok.has("neg") and out.head is not None and (owner := self._owner_at(1)):
                # "the cup I drank from, not my wife's", "my tablet, not hers": whose it is
                # not (the map may not know whose things are; the trace says it was asked)
                self.i += owner[0] + 1
                self._neg = False
                out.head.constraints.append(
                    AttributeConstraint(
                        key="other", value=owner[1], negated=True,
                        weight=self.weight("attribute"), text=f"not {owner[1]}",
                    )
                )  # fmt: skip
                self.notes.append(f"'not {owner[1]}': whose it is not")
            elif tok.has("neg", "except"):
                self.advance()
                if not self._mental_after():
                    self.negate()  # "I can't remember where I left it": no exclusion
                self._after_except = tok.has("except")
            elif tok.has("emph", "hedge"):
                self.advance()
                self.stress("emph" if tok.has("emph") else "hedge")
            elif tok.has("prep", "away"):
                phrase = self.parse_pp()
                if phrase is not None:
                    self._route(out, phrase)
            elif tok.has("placement") and not tok.has("noun"):
                self.advance()  # "In the corner of the room stands a lamp"
                holder = NP()
                self._placement(holder, tok.tags["placement"], tok.text)
                self._route(out, [*holder.constraints, *holder.places])
            elif tok.has("or") and self.np_start(1) and self._negation_open():
                self.advance()  # "not in the bedroom or the living room"
                self._negated_alternative(out, refine)
            elif tok.has("or") and self.at("prep", k=1) and self._negation_open():
                self.advance()  # "neither in the kitchen nor in the dining room"
                self.negate()
            elif tok.has("super") and out.head is not None:
                self._attach_postmodifiers(out.head)
            elif out.head is not None and tok.has("with", "without", "have"):
                if not self.parse_with(out.head):
                    self._unchecked_feature(out.head)
            elif self.np_start():
                self._noun_phrase(out, refine)
            elif (
                tok.tags.get("view") == "back_to"
                and tok.text.startswith(("with ", "my ", "our "))
                and out.viewpoint is None
                and self._viewpoint(out)
            ):
                pass  # "I'm at the copier with my back to the hallway door"
            else:
                if not tok.has(*_SKIP):
                    self.notes.append(f"skipped {tok.text!r}")
                self.advance()
        return out

    def _what_it_has(self, out: Clause, tok: Tok) -> bool:
        """Whether ``tok`` is "has" after "and", saying what the thing spoken of has ("its
        under the window and has a blanket folded over one arm", "it stands out a bit and
        has a globe on top"): a part or a thing on it, not a thing sought."""
        return (
            out.head is not None
            and tok.lemma == "have"
            and tok.tag == "VBZ"
            and self.at("and", k=-1)
            and self.np_start(1)
        )

    def _owner_at(self, k: int) -> tuple[int, str] | None:
        """The owner named at token ``k`` ahead and how many tokens it takes, when the
        phrase ends there: "my wife('s)", "my daughters", "mine", "hers"."""
        first = self.peek(k)
        if first is None:
            return None
        if first.text in _OWNER_PRONOUNS:
            n, owner = 1, first.text
        else:
            n = 1 if first.tag == "PRP$" else 0
            person = self.peek(k + n)
            if person is None or not person.has("seeker") or person.tag not in ("NN", "NNS"):
                return None
            n, owner = n + 1, f"{person.text.rstrip('s') if person.tag == 'NNS' else person.text}'s"
        if self.at("one", k=k + n):
            n += 1
        after = self.peek(k + n)
        return (n, owner) if after is None or after.has("comma", "and", "but") else None

    def _kept_out(
        self, made: list[Constraint], candidate: NP | None
    ) -> tuple[list[Constraint], NP | None]:
        """ "don't go into the garage", "Don't go in the garage, go to the mudroom": the
        rooms a negated verb of going names are ruled out, and none of them is sought."""
        made = _rooms_ruled_out(made)
        if candidate is None:
            if not made and self.at("prep") and (self.at("room", k=1) or self.at("room", k=2)):
                self.negate()  # "don't go into the garage": the place phrase that follows
            return made, None
        candidate.places = _rooms_ruled_out(candidate.places)
        if candidate.kind == ROOM:
            self.notes.append(f"'not … {candidate.noun}': that room is ruled out")
            return [*made, self._place(candidate, True), *candidate.places], None
        return made, candidate

    def _unchecked_feature(self, head: NP) -> None:
        """A feature a room cannot be checked for ("the bathroom with the blue tiles"):
        the phrase is read and left out, so that it neither stalls the clause nor
        becomes the thing sought."""
        word = self.advance().text
        thing = self._with_object()
        said = thing.noun if thing is not None and thing.noun else "…"
        self.notes.append(f"'{word} {said}' describes the {head.kind}; not checked")

    # ------------------------------------------------------------ clause frames
    def _clause_start(self) -> bool:
        if self.i == self.view_end:
            return True  # "facing the closet doors it is the hamper …"
        j = self.i - 1
        while j >= 0 and self.toks[j].has("filler") and not self.toks[j].has("view"):
            j -= 1  # "okay so if you look at …": filler words open nothing
        prev = self.toks[j] if j >= 0 else None
        return prev is None or prev.has("comma", "and", "but", "sub") or prev.text == "then"

    def _frame(self) -> bool:
        """Skip "this is" / "it's" / "there are" / "the object is" before the phrase that
        names the target (a pronoun subject would otherwise be read as "it")."""
        tok = self.peek()
        assert tok is not None
        k = 1
        described = tok.has("det") and self.text_at(1) in ("description", "text")
        if tok.has("det") and self.at("generic", k=1) and self.text_at(1) in lexicon().meta_nouns:
            k = 2  # "the object is a …", "the item is …"
        elif described and self.text_at(3) in ("for", "about", "of"):
            k = 2  # "this description is for the basket"
        elif tok.text not in _FRAME_SUBJECTS:
            return False
        if not self.at("be", k=k):
            return False
        if described and k == 2:
            k += 1  # the preposition after "is"
        j = k + 1
        while self.at("adv", "emph", "hedge", "neg", k=j) and not self.at("prep", k=j):
            j += 1
        if not self.np_start(j) or (self.at("anaphor", k=j) and not self.at("det", k=j)):
            return False
        if tok.text in ("it", "its") and self._only_described(j):
            return False  # "it is white and has wheels": said of the thing, no new phrase
        words = " ".join(t.text for t in self.toks[self.i : self.i + k + 1])
        self.said_of_it = self.later and tok.text in ("it", "this", "its")
        self.framed = True
        self.notes.append(f"frame: '{words}' introduces the target")
        self.i += k + 1  # "not" stays: "it's not the white cabinet, it's the brown one"
        return True

    def _only_described(self, j: int) -> bool:
        """Whether the words ``j`` tokens ahead are adjectives with no noun after them,
        then "and" + "has" ("it is clear and has a blue lid")."""
        k = j
        while self.at("colour", "material", "adj", "adv", "shade", k=k) or (
            (tok := self.peek(k)) is not None and tok.pos == "ADJ"  # "clear" (by spaCy)
        ):
            k += 1
        return k > j and self.at("and", k=k) and self.at("have", k=k + 1)

    def _request_verb(self) -> None:
        """An imperative that asks to find or act on something ("select", "identify",
        "walk over to", "choose"): its object is the target."""
        tok = self.advance()
        self.notes.append(f"request verb {tok.text!r}: its object is the target")
        if tok.lemma in _SWITCH_VERBS and self.text_at() in ("on", "off"):
            self.advance()  # "turn on the lamp"
        while (nxt := self.peek()) is not None and (nxt.text in _TOWARDS or nxt.tag == "RP"):
            particle = nxt.tag == "RP" and self.np_start(1)  # "push in the chair"
            if (
                nxt.has("prep")
                and nxt.text not in ("to", "towards", "toward", "at", "over to")
                and not particle
            ):
                break
            self.advance()
        nxt = self.peek()
        if (
            tok.lemma in _WAIT_VERBS
            and nxt is not None
            and (nxt.text in _BESIDE or (nxt.text in _WAIT_PLACES and tok.text == tok.lemma))
            and self.np_start(1)
        ):
            self.advance()  # "stand next to the bookshelf": the bookshelf is where to go

    def _viewpoint(self, out: Clause) -> bool:
        """A clause that says where the speaker stands or looks: "if you face the
        windows", "from the door", "as you come through the brown door", "when you come down
        the stairs", "with your back to the TV". Its landmark becomes the request's
        viewpoint; nothing else is taken from it."""
        lx = lexicon()
        k, opener = 0, False
        if self.text_at() in _VIEW_OPENERS:
            k, opener = 1, True
        elif self._asked_of_listener():
            return False  # "can you look at the smoke alarm …": a request, no standpoint
        while self.at("seeker", "be", "modal", "adv", k=k) and k < 5 and not self._view_verb(k):
            k += 1
        lead = self.peek(k)
        if lead is not None and lead.lemma in lx.viewpoint_verbs and self.at("view", k=k + 1):
            k += 1  # "stand with your back to the door"
        cue = self.peek(k)
        if cue is None:
            return False
        # a participle or an imperative opens a viewpoint too: "Looking from the hallway
        # …", "Face the oven and …"
        verb_ok = opener or k > 0 or cue.tag in ("VBG", "VB")
        if cue.has("view"):
            kind = str(cue.tags["view"])
        elif opener and cue.text in _BEING_AT and self._speaker_is(k):
            kind = _BEING_AT[cue.text]  # "when I'm on the couch …", "if you're at the sink"
            k -= 1  # the preposition is read with the landmark
        elif verb_ok and cue.lemma in lx.facing_verbs:
            kind = "facing"
        elif verb_ok and cue.lemma in lx.viewpoint_verbs and cue.pos in ("VERB", "AUX"):
            after = self.peek(k + 1)
            before = self.peek(k - 1) if self.i + k > 0 else None
            if (after is not None and after.pos == "VERB" and after.tag == "VB") or (
                before is not None and before.lemma in ("go", "come") and cue.tag == "VB"
            ):
                return False  # "go get the basket from …": an errand, not a standpoint
            if after is not None and after.has("det") and cue.lemma not in _TRANSITIVE_VIEW:
                return False  # "move the ottoman, …", "get the towel from …": an errand
            if cue.lemma in _SWITCH_VERBS and after is not None and after.text in ("on", "off"):
                return False  # "turn on the TV that's on the stand": a switch, not a turn
            kind = "from"
        else:
            return False
        if cue.text == "from" and not self._from_clause(k):
            return False
        snap = self.state()
        self.i += k + 1
        linked = False
        while (tok := self.peek()) is not None and (
            tok.has("prep", "to", "from") or tok.tag == "RP" or tok.text in _PARTICLES
        ):
            if tok.text in ("to", "toward", "towards") and kind == "from":
                kind = "facing"  # "as you walk towards the window"
            elif tok.text in _SEATS and kind == "from" and cue.lemma in lx.seated_verbs:
                kind = "seated"  # "sitting on the sofa", "lying in bed"
            self.advance()  # "as you come in through the door", "stand at the sink"
            linked = True
            if self.np_start():
                break
        complete = cue.text.split()[-1] in _COMPLETE_VIEW_ENDS
        looked: Landmark | None = None
        if not linked and complete and cue.has("view") and self._subject_follows():
            lm = None  # "when you walk in the bookshelf is straight ahead": the main clause
        else:
            start = self.i
            lm = self.parse_np(landmark=True) if self.np_start() else None
            looked = self._looked_at(lm, start) if lm is not None else None
        if lm is not None and lm.kind == VAGUE:
            lm = self._position_landmark(lm)  # "from the top of the stairs"
        if lm is not None and lm.kind not in (OBJECT, ROOM):
            self.restore(snap)
            return False
        if lm is None and (kind != "from" or not (opener or self._entering(cue, snap[0]))):
            self.restore(snap)  # "where should I go?": no place to stand at
            return False
        if lm is None and opener and not cue.has("view"):
            self._skip_clause()  # "if you stand where the rug ends, …": context only
            return True
        looked_at = lm
        if lm is not None and lm.kind == ROOM and self.at("from") and self.np_start(1):
            here = self.state()
            self.advance()
            origin = self.parse_np(landmark=True)  # "into the bathroom from the front hall"
            if origin is not None and origin.kind == ROOM and not lm.beside:
                lm.beside = origin.room_type or origin.noun
            else:
                self.restore(here)
        if kind == "facing" and self.at("from") and self.np_start(1):
            here = self.state()
            self.advance()
            origin = self.parse_np(landmark=True)  # "looking at the bed from the door"
            if origin is not None and origin.kind == OBJECT:
                kind, lm = "from", origin
            else:
                self.restore(here)
        if kind in ("from", "seated"):
            self._room_after_view()  # "sitting on the sofa in the den looking at the TV"
        seen = self._second_view()  # "standing at the printer looking toward the windows"
        looking = seen.landmark() if seen is not None else looked
        opener = opener or cue.text.split()[0] in _VIEW_OPENERS
        moving = cue.lemma in lx.viewpoint_verbs  # "walk to …", not "face …"
        standing = kind in ("from", "seated")
        if lm is not None and not opener and not self._more_follows(moving, standing):
            self.restore(snap)  # "look at the clock on the wall": the clock is sought
            return False
        landmark = self._viewpoint_landmark(lm)
        group = looked_at
        if group is not None and group.kind == OBJECT and group.plural and group.labels:
            # "looking at the sinks from the door, the one furthest away": the sinks
            self.group = self.group or replace(group, constraints=[], places=[])
        said = " ".join(t.text for t in self.toks[snap[0] : self.i])
        earlier = out.viewpoint
        if (
            earlier is not None
            and kind == "facing"
            and earlier.kind in ("from", "seated", "back_to")
        ):
            # "with my back to the sink, facing the bar": standing at the sink, looking
            # at the bar
            out.viewpoint = Viewpoint(
                kind="from" if earlier.kind == "back_to" else earlier.kind,
                landmark=earlier.landmark,
                text=f"{earlier.text}, {said}",
                toward=landmark,
            )
        else:
            out.viewpoint = Viewpoint(
                kind=kind,
                landmark=landmark,
                text=said,
                toward=looking if standing else None,
            )
        self.notes.append(f"viewpoint: {kind} {landmark.target.describe()}")
        if self.at("comma"):
            self.advance()
        self.view_end = self.i
        return True

    def _speaker_is(self, k: int) -> bool:
        """Whether the ``k`` words here say the speaker (or listener) is somewhere: "I'm",
        "you are", "we're"."""
        said = " ".join(t.text for t in self.toks[self.i : self.i + k])
        return k > 0 and self.at("be", k=k - 1) and bool(_BEING.search(said))

    def _subject_follows(self) -> bool:
        """Whether the words here are a thing and its verb "be" ("the bookshelf is …",
        "the two chairs are …"): the subject of a clause, no landmark."""
        k = 0
        while self.at("det", "num", "colour", "material", "adj", k=k):
            k += 1
        return self.at("noun", "unk", k=k) and self.at("be", k=k + 1)

    def _time_clause(self, out: Clause) -> bool:
        """ "before I head out the front door", "after we get to the kitchen": when the
        speaker does something is context, not the target; a thing it names is where the
        target likely is (a soft "near")."""
        if self.text_at() not in _TIME_WORDS:
            return False
        if self.text_at(1) in _PEOPLE:
            self.i += 2
        elif (
            self.text_at(1) in ("the", "my", "our")
            and self.at("seeker", k=2)
            and self.at("be", "overb", k=3)
        ):
            self.i += 3  # "after the kids were done banging on it"
        else:
            return False
        mark: NP | None = None
        while (tok := self.peek()) is not None and not tok.has("comma", "and", "but"):
            if self.np_start():
                np = self.parse_np(landmark=True)
                if np is not None and np.kind == OBJECT and np.labels:
                    mark = np
                if np is not None or self.peek() is None:
                    continue
            self.advance()
        if mark is not None:
            out.pending.append(
                RelationConstraint(
                    predicate="near", landmark=mark.landmark(), weight=self.weight("relation") / 2,
                    text=f"near {mark.noun}",
                )
            )  # fmt: skip
        self.notes.append("a time clause ('before I …') is context, not the target")
        return True

    def _counting_origin(self) -> bool:
        """ "Counting from the curtains, the third chair …": the landmark an ordinal that
        follows is counted from (kept in ``count_origin``)."""
        if self.text_at() not in _COUNTING or self.text_at(1) != "from":
            return False
        snap = self.state()
        self.i += 2
        mark = self.parse_np(landmark=True) if self.np_start() else None
        if mark is None or mark.kind != OBJECT or not mark.labels:
            self.restore(snap)
            return False
        self.count_origin = mark.landmark()
        self.notes.append(f"ordinals are counted from the {mark.noun}")
        if self.at("comma"):
            self.advance()
        return True

    def _asked_of_listener(self) -> bool:
        """Whether the words just before are a request to the listener ("can you",
        "could you please"), so what follows is the errand."""
        prev = self.peek(-1) if self.i > 0 else None
        return (
            prev is not None
            and prev.has("filler")
            and not prev.has("view")
            and "you" in prev.text.split()
        )

    def _entering(self, cue: Tok, start: int) -> bool:
        """Whether a viewpoint clause with no landmark says the speaker comes in ("as you
        walk in", "when you enter", "coming through, …") or is followed by what it
        places ("from here, …"): then its landmark is the door."""
        moved = {t.text for t in self.toks[start : self.i]}
        return (
            cue.has("view")  # a viewpoint phrase of its own: "as you come in"
            or cue.lemma == "enter"
            or bool(moved & _ENTERING)
            or self.at("comma")
        )

    def _view_verb(self, k: int) -> bool:
        tok = self.peek(k)
        lx = lexicon()
        return tok is not None and (tok.lemma in lx.viewpoint_verbs or tok.lemma in lx.facing_verbs)

    def _looked_at(self, lm: NP, start: int) -> Landmark | None:
        """What the speaker looks at, when the standpoint's phrase (from ``start``) went
        on with a verb of looking that it read as the standpoint's own relation
        ("sitting at the bar facing the kitchen", "at the sink looking at the bar"):
        that relation is taken out of the standpoint."""
        lx = lexicon()
        if not any(
            t.lemma in lx.facing_verbs or t.tags.get("view") == "facing"
            for t in self.toks[start : self.i]
        ):
            return None
        kept, seen = _without_last_relation(tuple(lm.constraints))
        lm.constraints = list(kept)
        return seen

    def _second_view(self) -> NP | None:
        """A second viewpoint phrase after the first ("… looking toward the windows",
        "… facing the monitor") says which way the speaker looks; the first (where they
        stand) is kept and the second is consumed so it is not read as the target. What
        the speaker looks at, when it is a thing or a room."""
        tok = self.peek()
        lx = lexicon()
        if tok is None:
            return None
        looking = str(tok.tags.get("fverb", "")).split(" ")[0]  # "looking out": "look out"
        facing = (
            tok.tags.get("view") == "facing"
            or tok.lemma in lx.facing_verbs
            or looking in lx.facing_verbs
        )
        if not (tok.has("view") or facing):
            return None
        snap = self.state()
        self.advance()
        verb_end = self.i
        while (nxt := self.peek()) is not None and nxt.text in _PARTICLES and not self.np_start():
            self.advance()
        if self._heading_only(self.i > verb_end):
            self.notes.append("second viewpoint phrase: the speaker's heading")
            return None  # "standing in the doorway looking in, …", "… look to your right, …"
        seen = self.parse_np(landmark=True) if self.np_start() else None
        if seen is None:
            self.restore(snap)
            return None
        self.notes.append("second viewpoint phrase: the speaker's heading")
        # "coming into the office from the corridor": where one comes from is behind
        return seen if facing and seen.kind in (OBJECT, ROOM) else None

    def _heading_only(self, particle: bool) -> bool:
        """Whether a second viewpoint phrase says only which way the speaker looks, with
        no landmark, up to a comma ("looking in", "looking straight ahead", "look to your
        right"); consumed when it does."""
        k = 0
        while (tok := self.peek(k)) is not None and not tok.has("comma") and k < 4:
            if not (tok.text in _HEADING_WORDS or tok.has("seeker", "dir", "adv")):
                return False
            k += 1
        if (k == 0 and not particle) or not self.at("comma", k=k):
            return False
        self.i += k
        return True

    def _more_follows(self, moving: bool = False, standing: bool = False) -> bool:
        """Whether the request goes on after a viewpoint phrase (else that phrase names
        the target: "look at the clock"). After a phrase of ``moving`` ("walk to the
        stool") a bare place that follows places its thing: it goes on no further. After a
        phrase of ``standing`` at or sitting on a thing, a room may follow first ("sitting
        on the sofa in the family room the cushion …")."""
        tok = self.peek()
        if tok is None:
            return self.more_sentences  # "Face the radiator. The picture to its left."
        room_end = self._room_after() if moving or standing else 0
        if room_end:
            # "sitting on the sofa in the family room, the cushion …": the room is the
            # request's; what follows it says whether the request goes on (not after a
            # verb of looking: "look at the box under the telly in the lounge and …")
            after = self.peek(room_end)
            return after is not None and (
                after.has("comma", "and", "anaphor", "det", "one") or self.np_start(room_end)
            )
        if tok.has("comma", "and"):
            if moving and self._place_of_it_follows():
                return False  # "walk to the stool, over by the back door"
            if moving and self._it_placed_next():
                return False  # "you can reach the light switch, it's right by the door"
            return self.peek(1) is not None or self.more_sentences
        return tok.has("anaphor", "det", "be", "one") or self.np_start()

    def _room_after_view(self) -> None:
        """ "sitting on the settee in the den looking at the telly, the cushion …": where
        a room phrase stands between the standpoint and what the speaker looks at, the
        room is moved after the phrase of looking, so that the looking is read as the
        standpoint's and the room as the request's."""
        size = self._room_after()
        cue = self.peek(size) if size else None
        if cue is None or not (cue.has("view") or cue.lemma in lexicon().facing_verbs):
            return
        start = self.i
        self.i += size
        seen = self._second_view_end()
        self.i = start
        if seen > start + size:
            room = self.toks[start : start + size]
            self.toks[start : seen - size] = self.toks[start + size : seen]
            self.toks[seen - size : seen] = room

    def _second_view_end(self) -> int:
        """Where a second viewpoint phrase here ends (here when there is none); the
        cursor is left where it was."""
        snap = self.state()
        found = self._second_view()
        end = self.i if found is not None else snap[0]
        self.restore(snap)
        return end

    def _room_after(self) -> int:
        """How many tokens a room phrase here takes ("in the family room", "in the den"),
        0 when none stands here."""
        if not self.at("prep") or self.text_at() not in ("in", "inside"):
            return 0
        k = 1
        while self.at("det", "adj", k=k) and k < 4:
            k += 1
        return k + 1 if self.at("room", k=k) else 0

    def _it_placed_next(self) -> bool:
        """Whether "it is" and a place follow the comma here ("…, it's right by the
        door"): "it" is the thing just named, placed; the phrase named no standpoint."""
        it, be, after = self.peek(1), self.peek(2), self.peek(3)
        if it is None or be is None or after is None or it.text not in ("it", "its"):
            return False
        if after.text in ("right", "just", "directly", "over") and self.at("prep", k=4):
            return be.has("be")  # "it's right by the door"
        return be.has("be") and after.has("prep") and not after.has("det", "one")

    def _place_of_it_follows(self) -> bool:
        """Whether all that follows the comma here is a place with no thing of its own
        ("…, over by the back door", "…, near the island"): it places what came before."""
        if self.more_sentences:
            return False
        rest = self.toks[self.i + 1 :]
        k = 0
        while k < len(rest) and rest[k].text in ("over", "right", "just", "somewhere"):
            k += 1
        if k >= len(rest) or not rest[k].has("prep"):
            return False
        return not any(t.has("comma", "be", "one", "and") or t.pos == "VERB" for t in rest)

    def _skip_clause(self) -> None:
        """Skip to the end of a subordinate clause (a comma, "and", or the end)."""
        while (tok := self.peek()) is not None and not tok.has("comma", "and"):
            self.advance()
        if self.at("comma"):
            self.advance()
        self.view_end = self.i

    @staticmethod
    def _position_landmark(lm: NP) -> NP | None:
        """The object a position phrase is about ("the top of the stairs" → stairs)."""
        for con in lm.constraints:
            if isinstance(con, RelationConstraint):
                target = con.landmark.target
                return NP(kind=OBJECT, labels=list(target.labels), words=target.noun.split())
        return None

    def _from_clause(self, k: int) -> bool:
        """ "from the door, …" opens a viewpoint only at the start and before a comma or a
        verb of looking ("from the doorway of the dining room look to your right, …"), or
        before a second determiner that opens the thing sought ("from the door the third
        shelf")."""
        if k or self.i > 0:
            return False
        j = 1
        while (t := self.peek(j)) is not None and not (t.has("comma") or self._view_verb(j)):
            if j >= 3 and t.text in _OPENING_DETERMINERS and self.at("det", k=j - 2):
                return j <= 7
            j += 1
        return self.peek(j) is not None and j <= 7

    def _viewpoint_landmark(self, lm: NP | None) -> Landmark:
        """The viewpoint's landmark; entering a room (or "walking in") means its door."""
        if lm is None or lm.kind == ROOM:
            room = [self._place(lm, False)] if lm is not None and lm.room_type else []
            door = Target(labels=("door",), noun="door")
            return Landmark(target=door, constraints=tuple(room))
        return lm.landmark()

    def _purpose(self, out: Clause) -> None:
        """ "for a meeting", "while watching TV" at the top level."""
        self.advance()
        made, candidate = verbs.parse_purpose(self)
        if out.head is not None:
            out.head.constraints += made
        else:
            out.functions += [c for c in made if c.kind == "function"]
            out.head = candidate
            self._route(out, [c for c in made if c.kind != "function"])

    def _searched_for(self, out: Clause, thing: NP, prev: Tok | None) -> bool:
        """ "check the counter for my watch", "search the closet for the umbrella": the
        thing searched for is the target, and the place searched its landmark."""
        head = out.head
        if prev is None or prev.text != "for" or head is None or head.kind != OBJECT:
            return False
        if thing.kind != OBJECT or not thing.labels:
            return False
        if not any(t.lemma in _SEARCH_VERBS for t in self.toks[: self.i]):
            return False
        self._sought_near_head(out, thing, "is searched for")
        return True

    def _attach_postmodifiers(self, head: NP) -> None:
        start = self.i
        self._postmodifiers(head, landmark=False)
        if self.i == start:
            self.advance()

    def _route(self, out: Clause, made: list[Constraint]) -> None:
        for con in made:
            if con.kind in ("room", "area", "floor"):
                out.places.append(con)
            elif out.head is not None:
                out.head.constraints.append(con)
            else:
                out.pending.append(con)

    def _mental_after(self) -> bool:
        """Whether a verb of knowing follows ("can't remember", "don't know")."""
        return self._mental_at(self.i)

    def _mental_at(self, k: int) -> bool:
        """Whether token ``k`` is a verb of knowing."""
        return k < len(self.toks) and self.toks[k].lemma in lexicon().mental_verbs

    @staticmethod
    def _negate_head_places(out: Clause) -> None:
        """Negate the places the negated head was given, now that a contrasting phrase
        keeps its kind ("not the toilet in the WC, the other one": not in the WC)."""
        mine = {id(c) for c in out.negated_head_places}
        kept = [c for c in out.places if id(c) not in mine]
        out.places = kept + _ruled_out([c for c in out.places if id(c) in mine])
        out.negated_head_places = []

    def _noun_phrase(self, out: Clause, refine: bool) -> None:
        neg = self.take_neg()
        prev = self.peek(-1) if self.i > 0 else None
        start = self.i
        np = self.parse_np()
        if np is None:
            if self.i == start:
                self.advance()
            return
        flip = neg and np.kind == ONE  # "except the ones in the bedroom"
        if out.head_negated and not neg and out.head is not None and _contrast(prev):
            if (np.kind == OBJECT and np.labels and not _same_kind(out, np)) or (
                np.kind == ONE and _described_anew(out, np) and not _has_details(out)
            ):
                # "not the sofa but the armchair"; "not the raincoat, the winter one" (a
                # one of the kind spoken of before, described anew)
                self._exclude(out, out.head)
                out.head, out.head_negated = None, False
            elif np.kind == ONE or _same_kind(out, np) or _pointed_again(out, np):
                self._contrast_one(out, np)
                return
        own_places = [replace(c, negated=not c.negated) if flip else c for c in np.places]
        out.places += own_places
        np.places = []
        if np.kind == FLOOR:
            if np.floor is not None:
                out.places.append(replace(self._floor(np.floor), negated=neg))
                out.floor_np = out.floor_np or np
            return
        if np.kind in (ROOM, AREA) and (refine or neg or out.head is not None):
            out.places.append(self._place(np, neg))
            return
        if np.kind == ANAPHOR and neg and (out.head is None or out.head.kind == ONE):
            out.exclude_previous = True  # "not that one", "the one on the left, not that one"
            return
        if np.kind == ANAPHOR and neg and out.head is not None and self._pointed_one(start):
            out.exclude_previous = True  # "this cup here, not that one"
            return
        if out.head is None:
            if self._stray_object(out, np, prev, start):
                return
            if flip:  # "not the red one. …": the one excluded, described by negation
                np.constraints = [replace(c, negated=not c.negated) for c in np.constraints]
            self.adopt_group(np)
            out.head = np
            out.head_negated = neg and np.kind == OBJECT and bool(np.labels)
            out.negated_head_places = own_places if out.head_negated else []
            out.head_pointed = out.head_negated and self.toks[start].text in _POINTING
            return
        if self._replaces_head(out, np, neg) or self._asked_for(out, np, neg, prev, start):
            return
        if not neg and self._searched_for(out, np, prev):
            return
        j = start - 1
        while j >= 0 and (self.toks[j].tag == "RP" or self.toks[j].text in _PARTICLES):
            j -= 1  # "grab out the …"
        if self._verb_of_head(out, np, neg, j) or self._next_errand(out, np, neg, j):
            return
        if not neg and j >= 0 and self.toks[j].pos == "VERB" and self._acted_on(out, np):
            return  # "where did the kids put the football"
        definite = self.toks[start].text in ("the", "that", "this")
        coordinated = prev is not None and prev.has("and", "or")
        if not neg and prev is not None and prev.has("comma") and self._narrows_to(out, np, start):
            return
        self._second_phrase(out, np, neg, coordinated, definite=definite)

    def _narrows_to(self, out: Clause, np: NP, start: int) -> bool:
        """A place named first, then the thing in it after a comma ("the wine rack in the
        basement, bottom row, the third bottle from the right", "the shelving unit on
        your right, second shelf, the box labeled halloween"): the last thing named is
        the target, on or in the holder named first. Not a list ("the table, the chairs
        and the bench"), nor a thing said of the head ("…, the lamp is on")."""
        head = out.head
        assert head is not None
        if head.kind != OBJECT or not head.labels or out.head_negated:
            return False
        if np.kind != OBJECT or not np.labels or _names_kind_of(np, head) or _related(head, np):
            return False
        if self.toks[start].text not in ("the", "that", "this"):
            return False  # "my purse, leather, …": a bare word describes the head
        if np.words[-1] in lexicon().quantity_nouns or _level_of(np, head):
            return False  # a row or a shelf of the holder: "bottom row", "top shelf"
        predicate = _holder_predicate(head.labels)
        if predicate is None:
            return False
        nxt = self.peek()
        if nxt is not None and (nxt.has("be", "modal") or nxt.tag in ("VBZ", "VBP", "MD")):
            return False  # a thing said of: "…, the lamp is on"
        if any(t.has("and", "or") for t in self.toks[self.i :]):
            return False
        np.constraints.append(
            RelationConstraint(
                predicate=predicate, landmark=head.landmark(), weight=self.weight("relation"),
                text=f"{predicate} {head.noun}",
            )
        )  # fmt: skip
        self.notes.append(f"{np.noun!r} is the target, {predicate} the {head.noun!r} named first")
        out.head = np
        return True

    def _pointed_one(self, start: int) -> bool:
        """Whether "that one" / "this one" stands at ``start``: a thing pointed at."""
        words = self.toks[start].text.split()
        if words[1:] in (["one"], ["ones"]):
            return words[0] in _POINTING  # one token: "that one"
        nxt = self.toks[start + 1] if start + 1 < len(self.toks) else None
        return words[0] in _POINTING and nxt is not None and nxt.has("one")

    def _acted_on(self, out: Clause, thing: NP) -> bool:
        """A person as the head and a thing a verb acts on ("the kids can't reach the
        cereal", "where did the kids put the football"): the thing becomes the target.
        False (nothing changed) otherwise."""
        head = out.head
        if head is None or out.head_negated or head.labels != ["person"]:
            return False
        if thing.kind != OBJECT or not thing.labels or thing.labels == ["person"]:
            return False
        self.notes.append(f"{thing.noun!r} is the target; {head.noun!r} acts on it")
        out.head = thing
        return True

    def _contrast_one(self, out: Clause, np: NP) -> None:
        """ "not the white cabinet, the brown one", "not the toilet in the WC, the other
        toilet", "avoid the blue bin, use the green one": the kind stays and the first
        one's details are negated."""
        old = out.head
        assert old is not None
        details = [c for c in old.constraints if c.kind != "label"]
        pointed = out.head_pointed and not (old.other or np.other)  # "the other one" says it
        if pointed and not details and not out.negated_head_places:
            out.exclude_previous = True  # "not that chair, the one by the window"
            self.notes.append(f"'not that {old.noun}': the one shown before is ruled out")
        old.constraints = _ruled_out(old.constraints) + np.constraints
        old.places += np.places
        old.other = old.other or np.other  # "not that remote, the other one"
        self._negate_head_places(out)
        out.head_negated = False
        self.notes.append(
            f"'not the {old.noun}' then 'one': the kind stays, its details are negated"
        )

    def _negation_open(self) -> bool:
        """Whether a negation or an exception earlier in this clause still holds at the
        current token: no comma, "and", "but" or subordinate clause since it."""
        for j in range(self.i - 1, -1, -1):
            tok = self.toks[j]
            if tok.has("neg"):
                # "can't remember if it is wood or plastic": what is not known, not ruled out
                return not self._mental_at(j + 1)
            if tok.has("except"):
                return True  # "anywhere except the bedroom or the living room"
            if tok.has("comma", "and", "but", "sub"):
                return False
        return False

    def _negated_alternative(self, out: Clause, refine: bool) -> None:
        """The phrase after "or" / "nor" in the scope of a negation is ruled out too: a
        room ("not in the bedroom or the living room"), or a landmark of the same
        relation ("not on the desk or the table"); any other phrase is negated."""
        start = self.i
        np = self.parse_np()
        if np is None:
            if self.i == start:
                self.advance()
            return
        if np.kind in (ROOM, AREA):
            out.places.append(self._place(np, True))
            return
        head = out.head
        last = next(
            (
                c
                for c in reversed(head.constraints if head is not None else [])
                if isinstance(c, RelationConstraint) and c.negated and c.landmark2 is None
            ),
            None,
        )
        if head is not None and last is not None and np.kind == OBJECT and np.labels:
            head.constraints.append(
                replace(last, landmark=np.landmark(), text=f"not {last.predicate} {np.noun}")
            )
            return
        self.i = start
        self.negate()
        self._noun_phrase(out, refine)

    def _next_errand(self, out: Clause, np: NP, neg: bool, j: int) -> bool:
        """ "Go to the sofa and pick up the remote", "… and find the basket": the object
        of a second command (its verb at token ``j``) after "and" is the target, found
        near the first one (in it, when the first one is a room)."""
        head = out.head
        if neg or head is None or head.kind not in (OBJECT, ROOM) or np.kind != OBJECT:
            return False
        if not np.labels:
            return False
        verb = self.toks[j] if j >= 0 else None
        before = self.toks[j - 1] if j >= 1 else None
        if verb is None or before is None or not before.has("and", "comma"):
            return False
        if not (verb.has("seek", "overb", "fverb") or verb.tag == "VB"):
            return False
        if before.has("comma") and verb.tag != "VB":
            return False  # "we're out of toilet paper, check the cabinet …": a command
        if head.kind == OBJECT and self._where_to_look(head, np, verb):
            # "remote again, check the couch", "the remote is not on the couch, try the
            # coffee table": the thing named first, looked for on the furniture named after
            head.constraints.append(
                RelationConstraint(
                    predicate="near", landmark=np.landmark(), weight=self.weight("relation") / 2,
                    text=f"{verb.text} {np.noun}",
                )
            )  # fmt: skip
            self.notes.append(f"'{verb.text} {np.noun}': where to look for {head.noun!r}")
            return True
        if head.kind == OBJECT and self._part_of_head(head, np, j):
            # "go to the high chair … and wipe the tray", "locate the filing cabinet and
            # open its top drawer": what is done to a part of the thing found first
            self.notes.append(f"{np.noun!r} is a part of {head.noun!r}, still the target")
            return True
        if head.kind == ROOM:  # "go to the TV room and turn on the TV": the TV, in that room
            out.places.append(self._place(head, False))
            self.notes.append(f"{np.noun!r} is the target; {head.noun!r} is where")
            out.head = np
            return True
        self._sought_near_head(out, np, "is the target")
        return True

    @staticmethod
    def _where_to_look(head: NP, np: NP, verb: Tok) -> bool:
        """Whether a second command ("check", "try", "look in") names furniture to look
        on or in for the thing named first, which is no furniture itself."""
        return verb.lemma in _LOOKING and _furnishing(np) and not _furnishing(head)

    def _part_of_head(self, head: NP, np: NP, j: int) -> bool:
        """Whether ``np`` (a command's object, its verb at token ``j``) is a part of
        ``head``: "its" before it, or a part word of the head's kind."""
        if any(t.text == "its" for t in self.toks[j + 1 : self.i]):
            return True
        return any(object_vocab.is_part(w, label) for w in np.words[-1:] for label in head.labels)

    def _verb_of_head(self, out: Clause, np: NP, neg: bool, j: int) -> bool:
        """ "The blinds are white and cover the window": in a description (no command
        before), the object of a placing verb (lexicon ``[relations.verbs]``) after "and"
        is a landmark of the target, not a second errand."""
        head = out.head
        verb = self.toks[j] if j >= 1 else None
        if head is None or head.kind != OBJECT or np.kind != OBJECT or not np.labels:
            return False
        if verb is None or verb.pos != "VERB" or not self.toks[j - 1].has("and"):
            return False
        predicate = lexicon().relation_verbs.get(verb.lemma)
        if predicate is None or any(t.has("seek") for t in self.toks[:j]):
            return False
        head.constraints.append(
            RelationConstraint(
                predicate=predicate, landmark=np.landmark(), negated=neg,
                weight=self.weight("relation"), text=f"{verb.text} {np.noun}",
            )
        )  # fmt: skip
        head.constraints += [c for c in np.constraints if isinstance(c, RelationConstraint)]
        return True

    def _sought_near_head(self, out: Clause, np: NP, how: str) -> None:
        """``np`` becomes the target, found near the head named before it."""
        head = out.head
        assert head is not None
        np.constraints.append(
            RelationConstraint(
                predicate="near", landmark=head.landmark(), weight=self.weight("relation"),
                text=f"near {head.noun}",
            )
        )  # fmt: skip
        self.notes.append(f"{np.noun!r} {how}; {head.noun!r} is where to look")
        out.head = np

    def _asked_for(self, out: Clause, np: NP, neg: bool, prev: Tok | None, start: int) -> bool:
        """A named object the request points at after another one was named: "I'm going
        to read on the couch - take me to the lamp there", "… on the way out the front
        door, which mirror should I use?". It is the target; the first one says where."""
        head = out.head
        if neg or head is None or head.kind != OBJECT or not head.labels or prev is None:
            return False
        if np.kind != OBJECT or not np.labels or set(np.labels) == set(head.labels):
            return False
        first = self.toks[start]
        asks = prev.text in _DIRECTIVES or (first.has("wh") and first.text in ("which", "what"))
        if not asks:
            return False
        self._sought_near_head(out, np, "is asked for")
        return True

    def _stray_object(self, out: Clause, np: NP, prev: object, start: int) -> bool:
        """An unknown noun that is the object of an unparsed verb ("after finishing my
        meal") or of a purpose that was not understood is not the request's head."""
        if np.kind != OBJECT or np.known or prev is None:
            return False
        assert isinstance(prev, Tok)
        after_verb = prev.has("overb", "fverb", "have") and not prev.has("be", "det", "seek")
        if after_verb and prev.lemma in _FETCH_VERBS and self._asked_before(start - 1):
            after_verb = False  # "can you get the salt": what is fetched is sought
        if after_verb and prev.tag in ("VBD", "VBN") and prev.lemma in _LEAVING and start >= 2:
            # "check if I left the iron on": the thing someone left or put is sought
            after_verb = self.toks[start - 2].text not in ("i", "we", "you")
        # "i don't know the name, the thing above the tv": the object of a verb of
        # knowing or saying in a filler phrase (not of "where can i find")
        mental = prev.has("filler") and prev.text.split()[-1] in lexicon().mental_verbs
        after_verb = after_verb or mental
        after_purpose = prev.has("for", "while") and bool(out.functions)
        if after_verb or after_purpose:
            self.notes.append(f"{np.noun!r} is the object of {prev.text!r}, not the target")
            return True
        return False

    def _asked_before(self, at: int) -> bool:
        """Whether the verb at token ``at`` opens the request or follows a request to the
        listener ("can you get", "please fetch")."""
        before = self.toks[at - 1] if at > 0 else None
        return before is None or before.has("filler", "comma", "and")

    def as_description(self, np: NP) -> list[Constraint]:
        """What a noun phrase in a description of the target says of it: a material
        noun ("plastic", "stainless steel") is its material; a part ("the lampshade is
        white") is a part of it; attributes of anything else are not the target's."""
        word = np.words[-1] if np.words else ""
        material = lexicon().materials.get(" ".join(np.words)) or lexicon().materials.get(word)
        said = [c for c in np.constraints if isinstance(c, AttributeConstraint)]
        if material is not None:
            self.notes.append(f"{np.noun!r} is the target's material")
            return [
                *said,
                AttributeConstraint(
                    key="material", value=material, weight=self.weight("attribute"),
                    text=np.noun,
                ),
            ]  # fmt: skip
        if said and object_vocab.is_part(word, None):
            self.notes.append(f"{np.noun!r} is a part of the target")
            values = [str(c.value) for c in said]
            return [
                AttributeConstraint(
                    key="part", value=" ".join([*values, word]), weight=self.weight("attribute"),
                    text=f"{' '.join(values)} {word}",
                )
            ]  # fmt: skip
        return []

    @staticmethod
    def _material_of(np: NP) -> bool:
        """Whether ``np`` names only a material and its colour ("brown leather", "black
        metal"), placed nowhere (not "the glass behind you", "my curling iron")."""
        if not np.words or np.words[-1] not in lexicon().materials or np.places:
            return False
        if any(isinstance(c, RelationConstraint) for c in np.constraints):
            return False
        coloured = any(
            isinstance(c, AttributeConstraint) and c.key == "colour" for c in np.constraints
        )
        # (a bare "glass" may be a glass: a colour or a second word says it is a material)
        plain = all(colour_or_material(w) or w in shade_words() for w in np.words)
        return (coloured or len(np.words) > 1) and plain

    def _replaces_head(self, out: Clause, np: NP, neg: bool) -> bool:
        """A named object after a head that names none takes its place: "not the red one.
        go to another lamp", "go to the kitchen and find the mug", "there should be a lamp
        …". The old head's constraints (or its room) then describe the new one."""
        head = out.head
        assert head is not None
        if neg or np.kind != OBJECT or not np.labels:
            return False
        if head.kind == ANAPHOR and (found := turned_round(np)):
            head.constraints += found  # "it is red and has a pillow on it"
            self.notes.append(f"'{np.noun} … it': a relation of the target, turned round")
            return True
        if self.said_of_it and head.kind == ONE and not head.labels:
            # "… It is yellow plastic.", "It is tall and thin, the lampshade is white":
            # the target described, not a new one named
            head.constraints += self.as_description(np)
            return True
        if head.kind == ONE and not head.labels and self._material_of(np):
            # "the one with its back to the windows, brown leather": what it is made of
            head.constraints += self.as_description(np)
            return True
        if head.kind in (ONE, ANAPHOR, VAGUE) and not head.labels:
            np.constraints = head.constraints + np.constraints
            np.other = np.other or head.other
        elif head.kind == ROOM and head.room_type is not None:
            out.places.append(self._place(head, False))
            np.constraints = head.constraints + np.constraints
        else:
            return False
        self.notes.append(f"{np.noun!r} is the target; the earlier phrase describes it")
        out.head = np
        return True

    def _second_phrase(
        self, out: Clause, np: NP, neg: bool, coordinated: bool, *, definite: bool = False
    ) -> None:
        """A noun phrase after the head: its details, a new target or nothing (``definite``:
        it opened with "the" / "that" / "this")."""
        head = out.head
        assert head is not None
        prev_except = self._after_except
        vague = (GENERIC, GENERIC_AREA, VAGUE)
        same_kind = _names_kind_of(np, head)
        if (
            np.kind == ONE
            or (np.kind in (GENERIC, VAGUE) and head.kind in vague)
            or (neg and same_kind and np.constraints)
        ):
            # "… It's not the armchair by the door": the same kind, its modifiers negated
            cons = [replace(c, negated=not c.negated) if neg else c for c in np.constraints]
            head.constraints += _as_placements(head, parts_of_head(head, cons))
        elif neg and np.kind == OBJECT and np.labels and prev_except and not _related(head, np):
            # "a pen from anywhere apart from Jake's desk": a place ruled out
            head.constraints.append(
                RelationConstraint(
                    predicate="near", landmark=np.landmark(), negated=True,
                    weight=self.weight("relation"), text=f"not near {np.noun}",
                )
            )  # fmt: skip
        elif neg and np.kind == OBJECT and np.labels:
            self._exclude(out, np)
        elif np.kind == OBJECT and np.labels and head.kind in (GENERIC, GENERIC_AREA, VAGUE):
            np.constraints = head.constraints + np.constraints
            out.head = np
        elif coordinated and np.kind == OBJECT and head.kind == OBJECT and not _only_a_look(np):
            head.labels += [x for x in np.labels if x not in head.labels]
            head.words += ["or", *np.words]
            head.constraints += np.constraints
            head.plural = True
        elif head.kind == ROOM and np.kind == OBJECT and np.labels and self.toks[0].has("wh"):
            # "which room is the piano in": the room that holds it
            head.constraints.append(
                RelationConstraint(
                    predicate="contains", landmark=np.landmark(), negated=neg,
                    weight=self.weight("relation"), text=f"holds {np.noun}",
                )
            )  # fmt: skip
        elif (
            not neg
            and definite
            and head.kind in (OBJECT, ROOM)
            and not self.framed  # "This is a whiteboard, the wall next to it has no windows"
            and self._placed_by_head(out, np)
        ):
            pass  # "go to the fridge, the cabinet right above it"
        elif head.kind == ANAPHOR:
            head.constraints += np.constraints
        elif np.kind == ANAPHOR and not np.plural and not neg:
            # "the shelf is white, it is mounted on the wall": "it" is the head again
            head.constraints += np.constraints
        else:
            self.notes.append(f"ignored second noun phrase {np.noun or np.kind!r}")

    def _placed_by_head(self, out: Clause, np: NP) -> bool:
        """A named thing placed by "it" after the head ("go to the fridge, the cabinet
        right above it"): it is the target, and "it" is the head named before. Only a
        definite phrase ("the cabinet"): "…, there are shoes under it" is about the head."""
        head = out.head
        assert head is not None
        if np.kind != OBJECT or not np.labels:
            return False
        by_it = [
            c
            for c in np.constraints
            if isinstance(c, RelationConstraint) and c.landmark.target.anaphor
        ]
        if not by_it:
            return False
        np.constraints = [
            replace(c, landmark=head.landmark(), text=c.text.replace("anaphor", head.noun))
            if c in by_it
            else c
            for c in np.constraints
        ]
        if head.kind == ROOM:
            out.places.append(self._place(head, False))
        self.notes.append(f"{np.noun!r} is the target; 'it' is the {head.noun!r}")
        out.head = np
        return True

    @staticmethod
    def _exclude(out: Clause, np: NP) -> None:
        out.excluded_labels.append(
            LabelConstraint(
                labels=tuple(np.labels), noun=np.noun, negated=True, text=f"not {np.noun}"
            )
        )

    def _place(self, np: NP, neg: bool) -> Constraint:
        if np.kind == ROOM:
            # its size, side and neighbour say which room ("the little bathroom")
            room = self._room(np, neg, np.noun, None)
            return replace(room, weight=self.weight("room"))
        return AreaConstraint(label=np.noun, negated=neg, weight=self.weight("area"), text=np.noun)


def _level_of(np: NP, head: NP) -> bool:
    """Whether ``np`` names a part of ``head`` that holds things in turn, or one the
    object vocabulary does not know as a kind: a shelf or a compartment of a cabinet."""
    part = any(object_vocab.is_part(word, label) for word in np.words for label in head.labels)
    return part and (
        not np.known
        or _holder_predicate(np.labels) == "on"
        or any("storage" in object_vocab.is_a(label) for label in np.labels)
    )


# Verbs that leave a thing somewhere: what "I left" or "we put" is the thing sought.
_LEAVING = frozenset({"leave", "put", "place", "set", "drop", "move", "hide", "store", "keep",
                      "lose", "forget", "stash", "stick"})  # fmt: skip


def _holder_predicate(labels: list[str]) -> str | None:
    """How a thing of one of ``labels`` holds another: "on" a shelf or a surface,
    "inside" a cabinet, box or bin; None for a thing that holds nothing."""
    for label in labels:
        kinds = {label, *object_vocab.is_a(label)}
        if kinds & {"shelf", "surface"}:
            return "on"
        if kinds & {"storage", "container", "bin"}:
            return "inside"
    return None


def _only_a_look(np: NP) -> bool:
    """Whether a phrase after "or" is only a material or colour ("wood or plastic",
    "black or dark blue"): a look the speaker is unsure of, not another kind sought."""
    lx = lexicon()
    words = [w for w in np.words if w not in ("a", "an", "the", "dark", "light")]
    return bool(words) and all(w in lx.materials or w in colour_words() for w in words)
