"""Noun-phrase grammar of the rule parser.

    NP  := DET? PRE* NOUN+ POST*          PRE  := colour | material | adjective | number
                                                  | ordinal | superlative | other | floor
    POST := PP | REL | "with" NP | "without" NP | "to" VP | "for" purpose | "of" NP
    PP  := PREP NP | "between" NP "and" NP
    REL := ("that" | "which") ("is" | "is not") (PP | ADJ) | "that has" NP

Post-modifiers attach to the innermost phrase they follow ("the mug on the table next
to the window": the table is next to the window). Room, area and floor phrases never
attach to a landmark: they are handed back to the request's head. A pending negation is
taken by the first constraint built after it, so it scopes exactly that constraint.
"""

from __future__ import annotations

from inherit_sg.retrieval import lexicon as lx
from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    RelationConstraint,
    RoomConstraint,
    Superlative,
)
from inherit_sg.retrieval.rules import verbs
from inherit_sg.retrieval.rules.cursor import Cursor, weighted
from inherit_sg.retrieval.rules.phrase import (
    ANAPHOR,
    AREA,
    FLOOR,
    GENERIC,
    GENERIC_AREA,
    NP,
    OBJECT,
    ONE,
    PERSON,
    ROOM,
    VAGUE,
)
from inherit_sg.retrieval.rules.tagger import Tok

# Prepositions that put the target in a room or area ("in", "inside", "within", "at");
# "on" only in "on this side" (vague places) and for floors.
_PLACE_PREDICATES = ("inside", "near", "on")
# What may follow a relative pronoun: "that is", "which isn't", "that must be red".
_CLAUSE_STARTS = ("be", "neg", "modal", "have", "emph", "hedge", "adv", "prep", "away",
                  "colour", "adj", "material", "super", "with", "without")  # fmt: skip


class Grammar(Cursor):
    """Recursive-descent parser of noun phrases over tagged tokens."""

    # ----------------------------------------------------------------- noun phrases
    def parse_np(self, landmark: bool = False) -> NP | None:
        """Parse a noun phrase at the cursor; None when no head was found."""
        np = NP()
        mods = self._premodifiers(np)
        if np.kind == FLOOR:
            return np
        run = self._noun_run(np)
        if np.kind == FLOOR:
            return np  # "floor 2"
        if np.kind == PERSON:
            return None  # "a small group", "someone": people are not searched for
        if not run and np.kind not in (ONE, ANAPHOR):
            if not mods:
                return None
            np.kind = ONE  # "the biggest", "the red"
        if run:
            self._head(np, run)
        tok = self.peek()
        if np.kind == ROOM and tok is not None and tok.has("num") and tok.text.isdigit():
            np.words.append(self.advance().text)  # a numbered room: "bedroom 2"
        self._postmodifiers(np, landmark)
        self._finish(np)
        return np

    def _premodifiers(self, np: NP) -> int:
        count = 0
        while (tok := self.peek()) is not None:
            if tok.has("floor") and not self.nounish(1):
                self.advance()
                np.kind, np.floor = FLOOR, tok.tags["floor"]
                return count + 1
            if tok.has("det") and not tok.has("neg"):
                if tok.text in ("this", "that") and not self._modifier_or_noun(1):
                    break  # anaphor "that" / "this"
                if tok.text.startswith("all") or tok.text in ("these", "those"):
                    np.plural = True
            elif tok.has("num") and (not tok.has("one") or self.nounish(1)):
                if self.at("floor_noun", k=1):
                    break
                np.quantity = tok.tags["num"]
                np.plural = np.quantity != 1
            elif tok.has("ord") and not self.at("floor_noun", k=1):
                np.ordinal = tok.tags["ord"]
            elif tok.has("super"):
                np.superlative = tok.tags["super"]
            elif tok.has("shade") and self.at("colour", k=1):
                pass
            elif tok.has("colour", "material", "adj") and self._adjective_here():
                self._attribute(np, tok)
            elif tok.has("other"):
                np.other = True
            elif tok.has("neg") and self.at("colour", "material", "adj", k=1):
                self.negate()
            elif tok.has("emph", "hedge"):
                self.stress("emph" if tok.has("emph") else "hedge")
            elif tok.has("adv") or (tok.has("filler") and not tok.has("noun", "unk")):
                pass
            elif tok.has("and", "or", "comma") and count and self.at("colour", "adj", k=1):
                pass  # "a quiet and private spot"
            else:
                break
            self.advance()
            count += 1
        return count

    def _modifier_or_noun(self, k: int) -> bool:
        return self.nounish(k) or self.at("colour", "material", "adj", "super", "ord", k=k)

    def _adjective_here(self) -> bool:
        """A material word is an adjective only before a noun ("glass door")."""
        tok = self.peek()
        assert tok is not None
        if tok.has("colour", "adj"):
            return not (tok.has("noun") and not self.nounish(1))
        return self.nounish(1) or self.at("colour", "adj", k=1)

    def _attribute(self, np: NP, tok: Tok) -> None:
        neg = self.take_neg()
        if tok.has("colour"):
            key, value = "colour", tok.tags["colour"]
        elif tok.has("material"):
            key, value = "material", tok.tags["material"]
        else:
            key, value = tok.tags["adj"]
        np.constraints.append(
            AttributeConstraint(
                key=key, value=value, negated=neg, weight=self.weight("attribute"), text=tok.text
            )
        )

    def _noun_run(self, np: NP) -> list[Tok]:
        run: list[Tok] = []
        while (tok := self.peek()) is not None:
            if tok.has("one") and not run and not self.nounish(1):
                np.kind = ONE
                np.plural = tok.plural
                self.advance()
                break
            if tok.has("anaphor") and not run and not tok.has("noun", "unk"):
                if tok.has("rel") and self.at(*_CLAUSE_STARTS, k=1):
                    break  # "… that is not in the kitchen": a relative clause
                if tok.text in ("that", "this") and self._modifier_or_noun(1):
                    self.advance()
                    continue
                np.kind = ANAPHOR
                self.advance()
                break
            if tok.has("floor_noun") and self.at("num", k=1):
                self.advance()
                np.kind, np.floor = FLOOR, max(0, self.advance().tags["num"] - 1)
                break
            if tok.has("seeker") and not tok.has("noun"):
                if self.nounish(1) and not self.at("one", k=1):
                    run.append(self.advance())  # "a group discussion"
                    continue
                if not run:
                    np.kind = PERSON
                    self.advance()
                break
            if self.nounish() and not tok.has("one", "be"):
                run.append(self.advance())
                continue
            if tok.has("fverb", "overb") and not tok.has("prep", "det", "modal", "be"):
                # gerund or verb-noun used as a noun: "viewing space", "a snack"
                after_modifier = self.at("det", "adj", "colour", "material", "num", k=-1)
                if self.nounish(1) or after_modifier or (run and not self.np_start(1)):
                    run.append(self.advance())
                    continue
            break
        return run

    def _head(self, np: NP, run: list[Tok]) -> None:
        last = run[-1]
        np.words = [t.text for t in run]
        np.plural = np.plural or last.plural
        if len(run) == 1 and last.has("generic"):
            np.kind = GENERIC
        elif last.has("room_word"):
            np.kind = ROOM
            np.labels = [np.noun] if len(run) > 1 else []
        elif last.has("area_head") and not last.has("noun"):
            deictic = len(run) == 1 and last.text in lx.GENERIC_AREAS
            np.kind = GENERIC_AREA if deictic else AREA
            np.labels = [] if deictic else [np.noun]
        elif last.has("room") and not (last.has("noun") and len(run) == 1):
            np.kind, np.room_type = ROOM, last.tags["room"]
            np.labels = [last.tags["room"]]
        elif last.has("vague"):
            np.kind = VAGUE
        elif last.has("generic"):
            np.kind = GENERIC
            np.labels = [x for t in run[:-1] for x in t.tags.get("noun", ())]
        elif last.has("noun"):
            np.labels = list(last.tags["noun"])
            np.known = True
        elif last.has("floor_noun"):
            np.labels = ["floor"]
        elif last.has("material") and not last.has("unk"):
            np.labels = [last.text]
        else:
            np.labels = [last.tags.get("unk") or lx.singular(last.text)]
        if np.kind == OBJECT and len(run) > 1:
            self.notes.append(f"compound noun {np.noun!r} → label {'/'.join(np.labels)}")

    def _finish(self, np: NP) -> None:
        if np.ordinal is not None:
            side = f" from the {np.direction}" if np.direction else ""
            np.constraints.append(
                Superlative(
                    measure="ordinal",
                    ordinal=np.ordinal,
                    direction=np.direction,
                    weight=self.weight("superlative"),
                    text=f"ordinal {np.ordinal}{side}",
                )
            )
            np.ordinal = None
        if np.superlative is not None:
            np.constraints.append(
                Superlative(
                    measure=np.superlative,
                    weight=self.weight("superlative"),
                    text=np.superlative,
                )
            )
            np.superlative = None

    # -------------------------------------------------------------- post-modifiers
    def _postmodifiers(self, np: NP, landmark: bool) -> None:
        after_be = False
        while (tok := self.peek()) is not None:
            if tok.has("and") and after_be and self.at("colour", "adj", "material", "be", k=1):
                pass  # "a chair that is red and made of wood"
            elif tok.has("comma", "and", "or", "but", "than", "sub"):
                break
            elif tok.has("be") and tok.has("fverb") and self.at("modal", k=-1):
                break  # "somewhere I can put my books away": a verb, not "put" = placed
            elif tok.has("be") or (tok.has("rel") and self.at(*_CLAUSE_STARTS, k=1)):
                after_be = True
            elif tok.has("wh") and tok.text == "where" and self.at("seeker", k=1):
                pass  # "a place where I can sit": the verb phrase follows
            elif tok.has("seeker", "modal") and not self.np_start():
                pass
            elif tok.has("neg"):
                self.negate()
            elif tok.has("emph", "hedge"):
                self.stress("emph" if tok.has("emph") else "hedge")
                after_be = True
            elif tok.has("adv") and not tok.has("prep"):
                pass
            elif tok.has("filler") and not tok.has("wh", "noun", "prep"):
                pass  # "the area would be best for …"
            elif not self._postmodifier(np, tok, landmark, after_be):
                break
            else:
                continue
            self.advance()

    def _postmodifier(self, np: NP, tok: Tok, landmark: bool, after_be: bool) -> bool:
        """Parse one post-modifier starting at ``tok``; False when there is none."""
        if tok.has("prep", "away") and self.with_depth and self.at("anaphor", k=1):
            return False  # "a lamp on it" closes a with-clause
        if tok.has("prep", "away", "from") and self._direction(np):
            return True
        if tok.has("prep", "away"):
            snap = self.state()
            made = self.parse_pp()
            if made is None:
                self.restore(snap)
                return False
            places = [c for c in made if c.kind in ("room", "area", "floor")]
            if places and landmark:
                self.restore(snap)
                return False
            np.places += places
            np.constraints += [c for c in made if c not in places]
            return True
        if tok.has("floor") and not landmark:
            self.advance()
            np.places.append(self._floor(tok.tags["floor"], self.take_neg()))
            return True
        if tok.has("super"):
            self.advance()
            np.constraints.append(self._superlative(tok.tags["super"], tok.text))
            return True
        if np.superlative in ("closest", "farthest") and tok.has("to", "from"):
            self.advance()
            measure, np.superlative = np.superlative, None
            np.constraints.append(self._superlative(measure, measure, landmark_now=True))
            return True
        if tok.has("with", "without") or (tok.has("have") and after_be):
            return self.parse_with(np)
        if after_be and tok.has("colour", "material", "adj"):
            self.advance()
            self._attribute(np, tok)
            return True
        if (tok.has("to") and self.at("fverb", "overb", k=1)) or tok.has("for", "while"):
            self.advance()
            cons, _ = verbs.parse_purpose(self)
            np.constraints += cons
            return True
        if tok.has("like") and self.np_start(1):
            self.advance()
            sub = self.parse_np(landmark=True)
            if sub is not None and sub.labels and np.kind in (GENERIC, VAGUE):
                np.kind, np.labels, np.words = OBJECT, sub.labels, sub.words
                np.known = sub.known
            return True
        if tok.has("of") and self.np_start(1):
            self.advance()
            sub = self.parse_np(landmark=True)
            if sub is not None and sub.kind == ROOM and np.kind in (AREA, GENERIC_AREA):
                np.places.append(self._room(sub, False, "room", None))  # "corner of the kitchen"
            elif sub is not None:
                np.words += ["of", *sub.words]
            return True
        return False

    def _direction(self, np: NP) -> bool:
        """ "from the left" / "on the right" after an ordinal."""
        k = 2 if self.at("det", k=1) else 1
        if not self.at("dir", k=k):
            return False
        np.direction = self.toks[self.i + k].text
        self.i += k + 1
        return True

    # ---------------------------------------------------------- prepositions
    def parse_pp(self) -> list[Constraint] | None:
        """A prepositional phrase → constraints (empty for deictic places); None when
        the preposition has no object."""
        tok = self.advance()
        neg = self.take_neg()
        predicate = tok.tags["prep"] if not tok.has("away") else "near"
        if tok.text in lx.OUTSIDE_PREPOSITIONS:
            predicate = "inside"  # "outside the kitchen": not in it
        if tok.has("away"):
            neg = not neg
        stress = self.take_stress()
        weight = weighted("relation", stress)
        if predicate == "between":
            return self._between(neg, weight, tok.text)
        lm = self.parse_np(landmark=True)
        if lm is None:
            return None
        text = f"{tok.text} {lm.noun or lm.kind}"
        places = lm.places
        if lm.kind == FLOOR and lm.floor is not None:
            return [self._floor(lm.floor, neg)]
        if lm.kind in (ROOM, AREA) and predicate in _PLACE_PREDICATES and tok.text != "on":
            if lm.kind == ROOM:
                place: Constraint = self._room(lm, neg, text, stress)
            else:
                place = AreaConstraint(
                    label=lm.noun, negated=neg, text=text, weight=weighted("area", stress)
                )
            return [place, *lm.constraints, *places]
        if lm.kind in (GENERIC_AREA, VAGUE) and predicate in _PLACE_PREDICATES:
            self.notes.append(f"place {text!r} describes the target, not a named area")
            return [*lm.constraints, *places]
        if lm.kind in (ONE, GENERIC) and not lm.labels:
            self.notes.append(f"{text!r} names no landmark; its modifiers describe the target")
            return [*lm.constraints, *places]
        rel = RelationConstraint(
            predicate=predicate, landmark=lm.landmark(), negated=neg, weight=weight, text=text
        )
        return [rel, *places]

    def _between(self, neg: bool, weight: float, word: str) -> list[Constraint] | None:
        first = self.parse_np(landmark=True)
        if first is None:
            return None
        second = None
        if self.at("and"):
            self.advance()
            second = self.parse_np(landmark=True)
        if second is None:
            self.notes.append("'between' with one landmark read as 'near'")
            return [RelationConstraint(predicate="near", landmark=first.landmark(), negated=neg,
                                       weight=weight, text=f"{word} {first.noun}")]  # fmt: skip
        return [
            RelationConstraint(
                predicate="between",
                landmark=first.landmark(),
                landmark2=second.landmark(),
                negated=neg,
                weight=weight,
                text=f"{word} {first.noun} and {second.noun}",
            ),
            *first.places,
            *second.places,
        ]

    def parse_with(self, np: NP) -> bool:
        """ "with X" / "without X" / "with no X next to it" / "that has X" on ``np``."""
        tok = self.advance()
        neg = self.take_neg() != tok.has("without")
        if self.at("neg"):
            self.advance()
            neg = not neg
        weight = self.weight("relation")
        self.with_depth += 1
        try:
            lm = self.parse_np(landmark=True)
        finally:
            self.with_depth -= 1
        if lm is None:
            return True
        predicate = "contains" if np.kind in (ROOM, AREA, GENERIC_AREA) else "with"
        after = self.peek()
        if after is not None and after.has("prep") and self.at("anaphor", k=1):
            predicate = lx.WITH_INVERSE.get(after.tags["prep"], after.tags["prep"])
            self.i += 2
        np.constraints.append(
            RelationConstraint(
                predicate=predicate,
                landmark=lm.landmark(),
                negated=neg,
                weight=weight,
                text=f"{tok.text} {lm.noun or lm.kind}",
            )
        )
        np.places += lm.places
        return True

    def _superlative(self, measure: str, text: str, landmark_now: bool = False) -> Superlative:
        weight = self.weight("superlative")
        lm = None
        if measure in ("closest", "farthest"):
            if not landmark_now and self.at("to", "from"):
                self.advance()
                landmark_now = True
            if landmark_now or self.at("det"):
                lm = self.parse_np(landmark=True)
        return Superlative(
            measure=measure,
            landmark=lm.landmark() if lm is not None else None,
            weight=weight,
            text=f"{text} {lm.noun}" if lm is not None else text,
        )

    @staticmethod
    def _room(np: NP, neg: bool, text: str, stress: str | None) -> RoomConstraint:
        return RoomConstraint(
            type=np.room_type, name=np.noun, negated=neg, text=text, weight=weighted("room", stress)
        )

    def _floor(self, value: int | str, neg: bool = False) -> FloorConstraint:
        if isinstance(value, int):
            return FloorConstraint(level=value, negated=neg, text=f"floor {value}")
        return FloorConstraint(relative=value, negated=neg, text=value)
