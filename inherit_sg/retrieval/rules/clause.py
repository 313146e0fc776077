"""Top level of a request: find the head noun phrase and attach everything else to it.

Phrases may come in any order ("in the kitchen, the red mug"): place phrases and
relations met before the head wait for it. Verb phrases give functions; a second noun
phrase after the head is a coordination ("a chair or a stool"), an apposition ("the red
one"), or, negated, an excluded label ("a seat but not a stool").
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    Constraint,
    LabelConstraint,
    RoomConstraint,
)
from inherit_sg.retrieval.rules import verbs
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

_SKIP = (
    "filler", "wh", "modal", "seeker", "comma", "and", "or", "but", "adv", "than", "overb",
    "be", "rel", "of", "to", "from", "dir", "for", "while", "have", "fverb", "shade", "sub",
    "like",
)  # fmt: skip


@dataclass
class Clause:
    """What the top level found."""

    head: NP | None = None
    pending: list[Constraint] = field(default_factory=list)
    places: list[Constraint] = field(default_factory=list)
    functions: list[Constraint] = field(default_factory=list)
    excluded_labels: list[Constraint] = field(default_factory=list)
    exclude_previous: bool = False
    floor_np: NP | None = None


class ClauseParser(Grammar):
    """Parses a whole request (after frame detection) into a :class:`Clause`."""

    def parse(self, refine: bool = False) -> Clause:
        """Walk the tokens once, building the clause."""
        out = Clause()
        while (tok := self.peek()) is not None:
            if verbs.is_verb_here(self):
                made, candidate = verbs.parse_vp(self)
                out.functions += [c for c in made if c.kind == "function"]
                self._route(out, [c for c in made if c.kind != "function"])
                if candidate is not None and out.head is None:
                    out.head = candidate
                    out.places += candidate.places
            elif tok.has("seeker") and self.at("modal", "wh", k=-1):
                self.advance()  # "where would one go"
            elif tok.has("for", "while"):
                self._purpose(out)
            elif tok.has("neg", "except"):
                self.advance()
                self.negate()
            elif tok.has("emph", "hedge"):
                self.advance()
                self.stress("emph" if tok.has("emph") else "hedge")
            elif tok.has("prep", "away"):
                phrase = self.parse_pp()
                if phrase is not None:
                    self._route(out, phrase)
            elif tok.has("super") and out.head is not None:
                self._attach_postmodifiers(out.head)
            elif out.head is not None and tok.has("with", "without", "have"):
                self.parse_with(out.head)
            elif self.np_start():
                self._noun_phrase(out, refine)
            else:
                if not tok.has(*_SKIP):
                    self.notes.append(f"skipped {tok.text!r}")
                self.advance()
        return out

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
        out.places += [replace(c, negated=not c.negated) if flip else c for c in np.places]
        np.places = []
        if np.kind == FLOOR:
            if np.floor is not None:
                out.places.append(replace(self._floor(np.floor), negated=neg))
                out.floor_np = out.floor_np or np
            return
        if np.kind in (ROOM, AREA) and (refine or neg or out.head is not None):
            out.places.append(self._place(np, neg))
            return
        if np.kind == ANAPHOR and neg and out.head is None:
            out.exclude_previous = True
            return
        if out.head is None:
            if self._stray_object(out, np, prev):
                return
            if flip:  # "not the red one. …": the one excluded, described by negation
                np.constraints = [replace(c, negated=not c.negated) for c in np.constraints]
            out.head = np
            return
        if self._replaces_head(out, np, neg):
            return
        self._second_phrase(out, np, neg, prev is not None and prev.has("and", "or"))

    def _stray_object(self, out: Clause, np: NP, prev: object) -> bool:
        """An unknown noun that is the object of an unparsed verb ("after finishing my
        meal") or of a purpose that was not understood is not the request's head."""
        if np.kind != OBJECT or np.known or prev is None:
            return False
        assert isinstance(prev, Tok)
        after_verb = prev.has("overb", "fverb", "have") and not prev.has("be", "det")
        after_purpose = prev.has("for", "while") and bool(out.functions)
        if after_verb or after_purpose:
            self.notes.append(f"{np.noun!r} is the object of {prev.text!r}, not the target")
            return True
        return False

    def _replaces_head(self, out: Clause, np: NP, neg: bool) -> bool:
        """A named object after a head that names none takes its place: "not the red one.
        go to another lamp", "go to the kitchen and find the mug", "there should be a lamp
        …". The old head's constraints (or its room) then describe the new one."""
        head = out.head
        assert head is not None
        if neg or np.kind != OBJECT or not np.labels:
            return False
        if head.kind == ONE and not head.labels:
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

    def _second_phrase(self, out: Clause, np: NP, neg: bool, coordinated: bool) -> None:
        head = out.head
        assert head is not None
        vague = (GENERIC, GENERIC_AREA, VAGUE)
        if np.kind == ONE or (np.kind in (GENERIC, VAGUE) and head.kind in vague):
            cons = [replace(c, negated=not c.negated) if neg else c for c in np.constraints]
            head.constraints += cons
        elif neg and np.kind == OBJECT and np.labels:
            out.excluded_labels.append(
                LabelConstraint(
                    labels=tuple(np.labels), noun=np.noun, negated=True, text=f"not {np.noun}"
                )
            )
        elif np.kind == OBJECT and np.known and head.kind in (GENERIC, GENERIC_AREA, VAGUE):
            np.constraints = head.constraints + np.constraints
            out.head = np
        elif coordinated and np.kind == OBJECT and head.kind == OBJECT:
            head.labels += [x for x in np.labels if x not in head.labels]
            head.words += ["or", *np.words]
            head.constraints += np.constraints
            head.plural = True
        elif head.kind == ANAPHOR:
            head.constraints += np.constraints
        else:
            self.notes.append(f"ignored second noun phrase {np.noun or np.kind!r}")

    def _place(self, np: NP, neg: bool) -> Constraint:
        if np.kind == ROOM:
            return RoomConstraint(
                type=np.room_type, name=np.noun, negated=neg, weight=self.weight("room"),
                text=np.noun,
            )  # fmt: skip
        return AreaConstraint(label=np.noun, negated=neg, weight=self.weight("area"), text=np.noun)
