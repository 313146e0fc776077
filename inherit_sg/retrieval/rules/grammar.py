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

import itertools
from dataclasses import replace

from inherit_sg.nlp import lemma_phrase
from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    Landmark,
    PlacementConstraint,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
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
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab import rooms as room_vocab
from inherit_sg.vocab.lexicon import lexicon

# Prepositions that put the target in a room or area ("in", "inside", "within", "at");
# "on" only in "on this side" (vague places) and for floors.
_PLACE_PREDICATES = ("inside", "near", "on")
# Prepositions whose object, when it names a room type, is that room ("in the WC").
_PLACE_WORDS = frozenset({"in", "inside", "within", "from"})
# Words a viewpoint clause may open with before its cue: "if you are facing …".
VIEW_OPENERS = frozenset({"if", "when", "as", "while", "once", "whilst"})
# Participles whose particle is the state itself: "turned on" = on.
_SWITCHED = frozenset({"turned", "switched", "powered", "left", "plugged"})
# Prepositions that, with "wall" or "corner", say where in its room the target stands.
_PLACEMENT_PREDICATES = ("on", "next_to", "near", "inside", "with", "above", "in_front_of")
# What may follow a relative pronoun: "that is", "which isn't", "that must be red".
_CLAUSE_STARTS = ("be", "neg", "modal", "have", "emph", "hedge", "adv", "prep", "away",
                  "colour", "adj", "material", "super", "with", "without")  # fmt: skip


# Prepositions that place a room next to another room or a thing ("the bathroom off the
# entry hall", "the bedroom next to the kitchen", "the bathroom by the front door").
# Kinds that lead from one place to another ("the door to the toilet").
_PASSAGES = frozenset({"door", "stairs", "arch", "gate", "doorway", "hallway"})
# Words that only stress how near a room lies ("just off the hall", "right by the door").
_JUST = frozenset({"just", "right", "directly", "immediately"})
_BESIDE_ROOM = frozenset({
    "off", "off of", "next to", "by", "near", "beside", "close to", "adjacent to",
    "across from", "opposite",
})  # fmt: skip


def _leads_somewhere(np: NP) -> bool:
    """Whether ``np`` names a way through (a door, stairs, an arch): "the door to the
    toilet", "the stairs to the basement" say where it leads, not a second thing."""
    return np.kind == OBJECT and any(
        label in _PASSAGES or any(k in _PASSAGES for k in object_vocab.is_a(label))
        for label in np.labels
    )


# Tags of the words that say a state ("still switched on", "dripping", "full").
_STATE_TAGS = frozenset({"JJ", "VBN", "VBG", "RB", "RP"})
# Verbs that open a state to check ("check the tap isn't dripping").
_CHECKING = frozenset({"check", "ensure", "verify", "confirm", "double-check"})
# Adverbs that put a thing right by a room it is "outside" of ("just outside the kitchen").
_RIGHT_BY = frozenset({"just", "right", "directly", "immediately", "straight"})
# Words that end a posture a thing can be in ("standing up", "lying down").
_POSTURE_ENDS = frozenset({"up", "down", "upright"})


def _opening(np: NP) -> bool:
    """Whether a phrase names a door, window or the like (``openings`` in the lexicon),
    which a thing is "outside" of by standing beside it."""
    openings = lexicon().openings
    return np.kind == OBJECT and any(
        label in openings or any(object_vocab.is_kind_of(label, o) for o in openings)
        for label in np.labels
    )


def _room_in_compound(head: Tok) -> tuple[str, str] | None:
    """The room a compound the vocabulary knows names before its kind ("kitchen sink" is a
    sink, "bathroom scale" a scale): (room type, room word). None when the kind keeps the
    room word ("kitchen cabinet": a kind of its own) or the word is not a room's name."""
    labels = head.tags.get("noun")
    words = head.text.split()
    if not labels or len(words) < 2:
        return None
    for n in range(len(words) - 1, 0, -1):
        word = " ".join(words[:n])
        # the prefix is a room type's own name, and no kind of thing: "kitchen sink",
        # "garage door"; not "laundry basket" (an alias), "bar stool" (a bar is a thing)
        if room_vocab.room_words().get(word) != word or object_vocab.canonical_label(word):
            continue
        rtype = word
        if any(word in str(label) for label in labels):
            return None
        return rtype, word
    return None


class Grammar(Cursor):
    """Recursive-descent parser of noun phrases over tagged tokens."""

    # ----------------------------------------------------------------- noun phrases
    def parse_np(self, landmark: bool = False) -> NP | None:
        """Parse a noun phrase at the cursor; None when no head was found."""
        np = NP()
        opening = self.peek()
        picked_one = opening is not None and opening.text.startswith("one of ")
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
        if picked_one:
            np.plural, np.quantity = False, None  # "one of the two lamps": one lamp
        tok = self.peek()
        if np.kind == ROOM and tok is not None and tok.has("num") and tok.text.isdigit():
            np.words.append(self.advance().text)  # a numbered room: "bedroom 2"
        elif np.kind == ROOM and tok is not None and tok.has("one") and tok.text in ("one", "ones"):
            self.advance()  # "the kitchen one": one of the kind spoken of, in the kitchen
            np.places.append(self._room(np, False, np.noun, None))
            np.kind, np.labels, np.words, np.room_type = ONE, [], [], None
            np.plural = tok.text == "ones"
        elif np.kind == OBJECT and self._modifies_one():
            self._open_words_describe_one(np)  # "not the big heavy-duty one"
        self._postmodifiers(np, landmark)
        self._finish(np)
        return np

    def _modifies_one(self) -> bool:
        """ "one" / "ones" follows, and not as "one of" ("the box one of you left")."""
        tok = self.peek()
        return (
            tok is not None
            and tok.has("one")
            and tok.text in ("one", "ones")
            and self.text_at(1) != "of"
        )

    def _open_words_describe_one(self, np: NP) -> None:
        """Nouns just before "one" ("the canvas one", "the heavy-duty one", written apart
        as "heavy duty") describe the one meant; they name no kind."""
        tok = self.advance()
        for word in np.words:
            np.constraints.append(
                AttributeConstraint(
                    key="other", value=word, negated=False,
                    weight=self.weight("attribute"), text=word,
                )
            )  # fmt: skip
        np.kind, np.labels, np.words = ONE, [], []
        np.plural = tok.text == "ones"

    def _premodifiers(self, np: NP) -> int:
        count = 0
        while (tok := self.peek()) is not None:
            if tok.has("floor") and not self.nounish(1):
                self.advance()
                np.kind, np.floor = FLOOR, tok.tags["floor"]
                return count + 1
            if tok.has("other"):
                np.other = True  # "another chair", "the other one"
            elif tok.has("det") and not tok.has("neg"):
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
            elif tok.has("side") and (not self.at("of", k=1) or self._group_follows(1)):
                np.direction = tok.tags["side"]  # "the leftmost chair", "… of the chairs"
            elif (
                tok.has("dir")
                and tok.tags["dir"] in ("left", "right")
                and (self._head_follows(1) or (count and self._phrase_ends(1)))
            ) or (tok.has("dir") and tok.tags["dir"] in ("front", "back") and self.at("one", k=1)):
                # "the left chair", "the right one"; "…, not the right" (the one on it);
                # "the far one", "the near one" (a "far chair" may be a kind's name)
                np.direction = tok.tags["dir"]
            elif (
                tok.has("dir")
                and tok.tags["dir"] in ("front", "back")
                and self.at("room", k=1)
                and not self.at("noun", k=1)  # "the back stairs": a thing too
            ):
                np.room_side = str(tok.tags["dir"])  # "the front bathroom": which room
            elif tok.has("middle") and self._head_follows(1) and not self.at("floor_noun", k=1):
                np.superlative = "middle"  # "the middle chair", "the centre one"
            elif tok.has("shade") and self.at("colour", k=1):
                pass
            elif tok.has("colour", "material", "adj") and self._adjective_here():
                self._attribute(np, tok)
            elif self._open_adjective():
                self._open_attribute(np, tok)  # "the dried out ones"
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

    def _phrase_ends(self, k: int) -> bool:
        """Nothing, or a clause break, follows ``k`` tokens ahead."""
        return self.peek(k) is None or self.at("comma", "and", "but", "or", k=k)

    def _head_follows(self, k: int) -> bool:
        """A noun, "one" (also "one of the") or an adjective then a noun follows ``k``
        tokens ahead."""
        if self.nounish(k) or self.at("one", k=k):
            return True
        tok = self.peek(k)
        if tok is not None and tok.has("det") and tok.text.startswith("one of"):
            return True  # "the middle one of the three chairs"
        return self.at("colour", "material", "adj", k=k) and (
            self.nounish(k + 1) or self.at("one", k=k + 1)
        )

    def _modifier_or_noun(self, k: int) -> bool:
        return self.nounish(k) or self.at("colour", "material", "adj", "super", "ord", k=k)

    def _adjective_here(self) -> bool:
        """A material word is an adjective only before a noun ("glass door")."""
        tok = self.peek()
        assert tok is not None
        if tok.has("colour", "adj"):
            return not (tok.has("noun") and not self.nounish(1))
        return self.nounish(1) or self.at("colour", "adj", "one", k=1)  # "the metal one"

    def _open_adjective(self) -> bool:
        """An adjective the vocabulary does not know, just before "one" / "ones" ("the
        dry ones", "the dried out one"; a particle may follow it)."""
        tok = self.peek()
        assert tok is not None
        if tok.tags.keys() - {"unk", "fverb", "overb"} or not (
            tok.pos == "ADJ" or (tok.pos == "VERB" and tok.tag in ("VBN", "VBD"))
        ):
            return False
        k = 2 if self.text_at(1) in ("out", "up", "off") else 1
        return self.at("one", k=k)

    def _open_attribute(self, np: NP, tok: Tok) -> None:
        """An adjective the vocabulary does not know, as a description to look for."""
        words = [tok.text]
        if self.text_at(1) in ("out", "up", "off"):
            self.advance()
            words.append(self.toks[self.i].text)
        np.constraints.append(
            AttributeConstraint(
                key="other", value=" ".join(words), negated=self.take_neg(),
                weight=self.weight("attribute"), text=" ".join(words),
            )
        )  # fmt: skip

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
            if not run and self._owner_before_thing(tok):
                self.advance()  # "the kids lunchboxes", "dads coat": whose, not what
                continue
            if tok.has("seeker", "abstract") and not tok.has("noun"):
                if self.nounish(1) and not self.at("one", k=1) and not tok.has("abstract"):
                    run.append(self.advance())  # "a group discussion"
                    continue
                if not run:
                    np.kind = PERSON  # people and times are never what is sought
                    self.advance()
                break
            if self.nounish() and not tok.has("one", "be"):
                run.append(self.advance())
                continue
            if tok.tag in ("VBN", "VBD") and run and not tok.has("noun", "unk"):
                break  # a participle after the noun describes it: "a board covered with"
            if tok.has("participle") and run:
                break  # "on the couch watching telly": what is done there, not its name
            if (
                tok.has("fverb", "overb")
                and not tok.has("prep", "det", "modal", "be")
                and (tok.tag.startswith("NN") or tok.tag in ("VBG", ""))
            ):
                # gerund or verb-noun used as a noun: "viewing space", "a snack"
                after_modifier = self.at("det", "adj", "colour", "material", "num", k=-1)
                trailing = run and not self.np_start(1) and tok.tag != "VBG"  # not "… running"
                if self.nounish(1) or after_modifier or trailing:
                    run.append(self.advance())
                    continue
            break
        return run

    def _owner_before_thing(self, tok: Tok) -> bool:
        """A person word written as an owner without its apostrophe ("the kids
        lunchboxes", "dads coat") before a thing that is not a room."""
        return (
            tok.has("seeker")
            and tok.text.endswith("s")
            and not tok.text.endswith("ss")
            and self.nounish(1)
            and not self.at("room", "room_word", "one", k=1)
        )

    def _head(self, np: NP, run: list[Tok]) -> None:
        if len(run) > 1 and run[-1].has("generic") and run[-1].pos == "ADV":
            run = run[:-1]  # "my hearing aid case somewhere": the thing, said to be somewhere
        last = run[-1]
        np.words = [t.text for t in run]
        np.plural = np.plural or last.plural
        if len(run) == 1 and last.has("generic"):
            np.kind = GENERIC
        elif len(run) > 1 and _room_mark(last) and run[-2].has("room"):
            # "conference room B", "bedroom 2": a room with its letter or number
            np.kind, np.room_type = ROOM, run[-2].tags["room"]
            np.labels = [run[-2].tags["room"]]
        elif last.has("room_word"):
            np.kind = ROOM
            np.labels = [np.noun] if len(run) > 1 else []
        elif last.has("area_head") and not last.has("noun"):
            self._name_area(np)
            deictic = len(np.words) == 1 and last.text in lexicon().generic_areas
            np.kind = GENERIC_AREA if deictic else AREA
            np.labels = [] if deictic else [np.noun]
        elif last.has("room") and (self.place_object or not (last.has("noun") and len(run) == 1)):
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
            np.labels = [_open_label(run)]
        if np.kind == OBJECT and len(run) > 1:
            self._part_of_owner(np, run)
            self.notes.append(f"compound noun {np.noun!r} → label {'/'.join(np.labels)}")
        if np.kind == OBJECT:
            self._room_modifier(np, run)
            self._place_modifier(np, run)

    @staticmethod
    def _part_of_owner(np: NP, run: list[Tok]) -> None:
        """ "the oven door", "the fridge door", "the cabinet door under the sink": a part
        named with the thing it belongs to may be mapped only as that thing, so the
        thing's kind is a name of the target too (a map that holds cabinet doors of their
        own still finds the door)."""
        owner, part = run[-2], run[-1]
        if not owner.has("noun") or owner.has("room"):
            return
        word = part.lemma or part.text
        if word not in _BUILT_IN_PARTS:
            return  # "the telly remote", "the dog leash": things of their own
        owners = [label for label in owner.tags["noun"] if object_vocab.is_part(word, label)]
        np.labels += [label for label in owners if label not in np.labels]

    def _room_modifier(self, np: NP, run: list[Tok]) -> None:
        """A room word before the head noun says where the thing is: "the bedroom TV",
        "the living room lamp" (a room constraint on the phrase; compounds the object
        vocabulary knows, such as "office chair", are one token and keep their kind)."""
        rooms = [t for t in run[:-1] if t.has("room") and not t.has("noun")]
        if rooms:
            word = rooms[-1]
            rtype, name = str(word.tags["room"]), word.text
        elif (found := _room_in_compound(run[-1])) is not None:
            rtype, name = found  # "the kitchen sink": a sink, in the kitchen
        else:
            return
        np.constraints.append(
            RoomConstraint(
                type=rtype, name=name, weight=self.weight("room"),
                text=f"{name} {run[-1].text}" if rooms else run[-1].text,
            )
        )  # fmt: skip

    def _place_modifier(self, np: NP, run: list[Tok]) -> None:
        """A modifier that says where the thing is ("the bedside lamp", "the couch
        cushions", lexicon ``place_modifiers``) adds a hedged relation to that place,
        also inside a compound the object vocabulary knows as one label."""
        words = [w for tok in run for w in tok.text.split()]
        places = lexicon().place_modifiers
        said = next((w for w in words[:-1] if w in places), None)
        if said is None:
            return
        if any(said in label.split() for label in np.labels):
            return  # part of the kind's own name: "the sofa bed", "the tv stand"
        predicate, place = places[said]
        labels = object_vocab.labels_for(place)
        if not labels or set(labels) & set(np.labels):
            return
        if predicate == "on" and any("furniture" in object_vocab.is_a(k) for k in np.labels):
            return  # "the sofa chair" is an armchair, not a chair on a sofa
        np.constraints.append(
            RelationConstraint(
                predicate=predicate,
                landmark=Landmark(target=Target(layer="object", labels=labels, noun=place)),
                weight=weighted("relation", "hedge"),
                text=f"{said} {words[-1]}",
            )
        )
        self.notes.append(f"'{said}' places the {words[-1]} {predicate.replace('_', ' ')} {place}")

    @staticmethod
    def _name_area(np: NP) -> None:
        """Open adjectives belong to an area's name: "the casual viewing space", "the
        social area" (known attributes such as "quiet" still describe it)."""
        words: list[str] = []
        kept: list[Constraint] = []
        for con in np.constraints:
            if (
                isinstance(con, AttributeConstraint)
                and con.key == "other"
                and not con.negated
                and con.value not in lexicon().adjectives
            ):
                words.append(con.text or con.value)
                continue
            kept.append(con)
        if words:
            np.constraints = kept
            np.words = [*words, *np.words]

    def _finish(self, np: NP) -> None:
        if np.superlative == "middle":
            np.constraints.append(
                Superlative(
                    measure="middle",
                    direction=np.direction,
                    weight=self.weight("superlative"),
                    text="the middle one",
                )
            )
            np.superlative, np.direction = None, None
        if np.direction is not None and np.ordinal is None and np.superlative is None:
            np.ordinal = 1  # "the one on the left": the first from the left
        if np.ordinal is not None and np.counted_from is None and np.direction is None:
            np.counted_from, self.count_origin = self.count_origin, None
        if np.ordinal is not None:
            side = f" from the {np.direction}" if np.direction else ""
            mark = np.counted_from
            if mark is not None:
                side = f" from the {mark.target.noun}"
            np.constraints.append(
                Superlative(
                    measure="ordinal",
                    ordinal=np.ordinal,
                    direction=np.direction,
                    landmark=mark if np.direction is None else None,
                    weight=self.weight("superlative"),
                    text=f"ordinal {np.ordinal}{side}",
                )
            )
            np.ordinal, np.counted_from = None, None
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
            at = self.i
            if tok.text.split()[0] in VIEW_OPENERS and (tok.has("view") or self.at("seeker", k=1)):
                break  # "the left one if you're facing the headboard": a viewpoint
            bare = np.kind == ONE and not np.labels  # "it is long and made of wood"
            if (
                tok.has("and")
                and (after_be or bare)
                and self.at("colour", "adj", "material", "be", k=1)
            ):
                after_be = True  # "a chair that is red and made of wood", "yellow and plastic"
            elif tok.has("comma") and (after_be or bare) and self.text_at(1).startswith("made "):
                after_be = True  # "it is long and L shaped, made of black granite"
            elif tok.has("and") and after_be and self.at("have", k=1) and self.np_start(2):
                pass  # "the chair is grey and has four legs": its parts, not a new errand
            elif tok.has("and", "rel") and (after_be or tok.has("rel")) and self._relation_verb(1):
                after_be = True  # "the blinds are white and cover the window"
            elif tok.has("comma", "and", "or", "but", "than", "sub"):
                break
            elif tok.has("be") and tok.has("fverb") and self.at("modal", k=-1):
                break  # "somewhere I can put my books away": a verb, not "put" = placed
            elif tok.has("rel") and landmark and self._plural_clause(np):
                break  # "the pillows on the couch that aren't white": about the pillows
            elif tok.has("be") and tok.lemma != "be" and self._doing_word(np, tok):
                continue  # "the suitcase that isn't standing up": a posture it is not in
            elif tok.has("be") and tok.lemma == "be" and landmark and not after_be:
                break  # "the fridge under the desk is black": the subject is black
            elif tok.has("be") or (tok.has("rel") and self.at(*_CLAUSE_STARTS, k=1)):
                after_be = True
            elif tok.has("wh") and tok.text == "where" and self.at("seeker", k=1):
                pass  # "a place where I can sit": the verb phrase follows
            elif (
                tok.tag in ("VBN", "VBG")
                and not tok.has("prep", "noun", "unk", "fverb")
                and self.at("prep", "with", "without", "away", "placement", k=1)
                and (self.np_start(2) or self.at("placement", k=1))
            ):
                after_be = True  # "the boxes stacked by the door", "a lamp standing by"
            elif np.kind == ONE and not after_be and tok.has("adj") and tok.tag in ("VBN", "JJ"):
                after_be = True  # "not the ones broken", "except the ones marked": its state
                continue
            elif np.kind == ONE and self._state_of_one(np, tok):
                after_be = True  # "except the one plugged in by my bed": how it stands
                continue
            elif tok.has("seeker", "modal") and not self.np_start():
                pass
            elif tok.has("neg") and self.state_to_check():
                # "check the bathroom tap isn't dripping", "make sure the kettle isn't
                # still switched on": the state to check, not a thing ruled out
                self.notes.append(f"'{tok.text}' in a state to check: nothing ruled out")
                while (word := self.peek(1)) is not None and word.tag in _STATE_TAGS:
                    self.advance()  # the state itself says nothing of which thing it is
                after_be = True
            elif tok.has("neg"):
                self.negate()
                after_be = True  # "the chair not pushed in" = "… that is not pushed in"
            elif tok.has("emph", "hedge"):
                self.stress("emph" if tok.has("emph") else "hedge")
                after_be = True
            elif tok.has("adv") and not tok.has("prep"):
                pass
            elif tok.has("filler") and not tok.has("wh", "noun", "prep"):
                pass  # "the area would be best for …"
            elif not self._postmodifier(np, tok, landmark, after_be):
                break
            elif self.i == at:
                break  # a reading that consumed nothing: stop rather than loop
            else:
                continue
            self.advance()

    def _state_of_one(self, np: NP, tok: Tok) -> bool:
        """A participle after "one" and before a place ("the one plugged in by my bed",
        "the one running to the freezer") says how that one stands, not what it is for:
        its particle is passed over with it."""
        phrasal = tok.tag == "RP" and " " in tok.text  # "plugged in", one token
        if not (tok.tag in ("VBN", "VBG") or phrasal) or tok.has("prep", "noun", "unk"):
            return False
        k = 2 if self.text_at(1) in ("in", "up", "out", "off") and self.at("prep", k=2) else 1
        if not (self.at("prep", "to", k=k) and self.np_start(k + 1)):
            return False
        for _ in range(k):
            self.advance()
        if self.at("to") and not self.at("prep"):
            self.advance()  # "the one running to the freezer": near where it leads
            lm = self.parse_np(landmark=True)
            if lm is not None and lm.kind == OBJECT and lm.labels:
                np.constraints.append(
                    RelationConstraint(
                        predicate="near", landmark=lm.landmark(), negated=self.take_neg(),
                        weight=self.weight("relation"), text=f"{tok.text} to {lm.noun}",
                    )
                )  # fmt: skip
        return True

    def _material_phrase(self, np: NP) -> bool:
        """ "covered in grey fabric", "a sofa in black leather", "upholstered with velvet":
        after "in" / "with", colour and material words that end on a material and head
        no noun describe the thing itself, not a landmark."""
        k = 2 if self.at("det", k=1) and not self.at("noun", "unk", k=1) else 1
        words: list[Tok] = []
        while (t := self.peek(k + len(words))) is not None and t.has("colour", "material", "adj"):
            if t.has("noun", "unk") and not t.has("material"):
                return False
            words.append(t)
        if not words or not words[-1].has("material"):
            return False
        after = self.peek(k + len(words))
        if after is not None and (after.has("noun", "unk") or after.pos in ("NOUN", "PROPN")):
            return False  # "in the wooden box": a landmark made of wood
        if words[-1].has("noun") and after is not None and not after.has("comma", "and", "or"):
            return False  # "with a glass of water on it": the glass is a thing
        for _ in range(k):
            self.advance()
        for t in words:
            self.advance()
            self._attribute(np, t)
        return True

    def _relation_verb(self, k: int) -> bool:
        """Whether token ``k`` ahead is a verb whose object places the thing that does
        it ("covers the window", "holding the books"; lexicon ``[relations.verbs]``)."""
        tok = self.peek(k)
        if tok is None or tok.pos != "VERB" or tok.lemma not in lexicon().relation_verbs:
            return False
        finite = tok.tag in ("VBZ", "VBP", "VBG") or (tok.tag == "VB" and k > 0)
        return finite and not tok.has("prep", "be") and self.np_start(k + 1)

    @staticmethod
    def _beside(np: NP, made: list[Constraint]) -> bool:
        """A room phrase's neighbour: the room or thing of a "next to" phrase after it."""
        if len(made) != 1 or made[0].negated:
            return False
        con = made[0]
        if isinstance(con, RoomConstraint):
            np.beside = con.type or con.name
        elif isinstance(con, RelationConstraint) and con.landmark.target.labels:
            np.beside = con.landmark.target.noun or con.landmark.target.labels[0]
        else:
            return False
        return True

    def _postmodifier(self, np: NP, tok: Tok, landmark: bool, after_be: bool) -> bool:
        """Parse one post-modifier starting at ``tok``; False when there is none."""
        if tok.has("prep", "away") and self.with_depth and self.at("anaphor", k=1):
            return False  # "a lamp on it" closes a with-clause
        if after_be and tok.text in ("on", "off") and self._state_word(np, tok):
            return True  # "the lamp that's not on"
        if after_be and self._doing_word(np, tok):
            return True  # "the door that doesn't squeak", "the laptop that isn't charging"
        if tok.has("prep", "away", "from") and self._direction(np):
            return True
        if tok.text == "from" and self._counted_from(np):
            return True
        if tok.has("placement"):
            self.advance()
            self._placement(np, tok.tags["placement"], tok.text)
            return True
        if tok.has("side") and (not self.at("of", k=1) or self._group_follows(1)):
            self.advance()
            np.direction = tok.tags["side"]  # "the one farthest left"
            return True
        if tok.has("prep") and tok.text == "in" and self._middle_here(np):
            return True
        if self._middle_of_group(np, tok):
            return True
        if tok.text in ("in", "with") and self._material_phrase(np):
            return True
        if (
            landmark
            and np.kind == ROOM
            and tok.text in _JUST
            and (nxt := self.peek(1)) is not None
            and nxt.text in _BESIDE_ROOM
        ):
            self.advance()  # "the bathroom just off the front hall"
            tok = nxt
        if tok.text == "into" and _leads_somewhere(np) and self._leads_to(np):
            return True  # "the doorway into the dining room": where it leads
        if tok.has("prep", "away"):
            snap = self.state()
            made = self.parse_pp()
            if made is None:
                self.restore(snap)
                return False
            places = [c for c in made if c.kind in ("room", "area", "floor")]
            if landmark and np.kind == ROOM and tok.text in _BESIDE_ROOM and self._beside(np, made):
                return True  # "the bathroom off the entry hall", "… by the front door"
            if places and landmark:
                self.restore(snap)
                return False
            np.places += places
            np.constraints += [c for c in made if c not in places]
            self.adopt_group(np)
            return True
        if tok.has("floor") and not landmark:
            self.advance()
            np.places.append(self._floor(tok.tags["floor"], self.take_neg()))
            return True
        if self._relation_verb(0):
            snap = self.state()
            made = self.parse_pp(predicate=lexicon().relation_verbs[tok.lemma])
            if made is None:
                self.restore(snap)
                return False
            places = [c for c in made if c.kind in ("room", "area", "floor")]
            np.places += places
            np.constraints += [c for c in made if c not in places]
            return True
        if tok.has("super"):
            self.advance()
            self._superlative(np, tok.tags["super"], tok.text)
            return True
        if (
            np.superlative in ("closest", "farthest")
            and tok.has("to", "from")
            and not self.at("fverb", "overb", k=1)  # "the closest place to sit to …"
        ):
            side = self._towards_side()
            if side is not None:  # "the farthest chair to the right"
                np.superlative, np.direction = None, side
                return True
            self.advance()
            measure, np.superlative = np.superlative, None
            self._superlative(np, measure, measure, landmark_now=True)
            return True
        before = self.peek(-1)
        seen_from = before is not None and before.pos == "VERB"  # "the lamp seen from …"
        if tok.has("from") and not tok.has("prep") and not landmark and np.kind in (OBJECT, ONE):
            if seen_from:
                return False
            # "a pillow from the bed", "a towel from the bathroom": where it is taken from
            snap = self.state()
            made = self.parse_pp("on") if self.np_start(1) else None
            if not made:
                self.restore(snap)
                return False
            np.places += [c for c in made if c.kind in ("room", "area", "floor")]
            np.constraints += [c for c in made if c.kind not in ("room", "area", "floor")]
            return True
        if tok.has("with", "without") or (
            tok.has("have") and (after_be or self.at("modal", "neg", k=-1))
        ):
            return self.parse_with(np, landmark=landmark)
        if after_be and tok.has("colour", "material", "adj"):
            self.advance()
            self._attribute(np, tok)
            return True
        if after_be and self._state_word(np, tok):
            return True
        if (tok.has("to") and self.at("fverb", "overb", k=1)) or tok.has("for", "while"):
            self.advance()
            cons, cand = verbs.parse_purpose(self)
            np.places += [c for c in cons if c.kind in ("room", "area", "floor")]
            np.constraints += [c for c in cons if c.kind not in ("room", "area", "floor")]
            if cand is not None and cand.kind in (GENERIC, VAGUE, ONE):
                np.constraints += cand.constraints  # "a place to find something to read"
                np.places += cand.places
            elif (
                cand is not None
                and cand.kind == OBJECT
                and cand.labels
                and np.kind
                in (
                    GENERIC,
                    VAGUE,
                )
            ):
                # "a spot to make a phone call", "somewhere to find the remote": the thing
                # the light verb takes is what serves
                np.kind, np.labels, np.words = OBJECT, cand.labels, cand.words
                np.known = cand.known
                np.constraints += cand.constraints
                np.places += cand.places
            return True
        if tok.has("to", "prep") and tok.text in ("to", "into") and _leads_somewhere(np):
            return self._leads_to(np)
        if tok.has("like") and self.np_start(1):
            self.advance()
            sub = self.parse_np(landmark=True)
            if sub is not None and sub.labels and np.kind in (GENERIC, VAGUE):
                np.kind, np.labels, np.words = OBJECT, sub.labels, sub.words
                np.known = sub.known
            return True
        if tok.has("of") and self.np_start(1):
            before = self.peek(-1)
            self.advance()
            sub = self.parse_np(landmark=True)
            if (
                sub is not None
                and sub.kind == OBJECT
                and before is not None
                and before.text == "full"
            ):
                np.constraints.append(  # "a bookshelf full of books": what it holds
                    RelationConstraint(
                        predicate="with", landmark=sub.landmark(), weight=self.weight("relation"),
                        text=f"full of {sub.noun}",
                    )
                )  # fmt: skip
                return True
            position = lexicon().position_nouns.get(" ".join(np.words[-2:])) or (
                lexicon().position_nouns.get(np.words[-1]) if np.words else None
            )
            if sub is not None and position is not None and sub.kind in (OBJECT, ROOM, ANAPHOR):
                self._position(np, sub, position)  # "the top of the stairs"
            elif sub is not None and sub.kind == ROOM:
                # "the corner of the kitchen", "the floor of the closet"
                np.places.append(self._room(sub, False, f"of {sub.noun}", None))
            elif sub is not None and sub.kind == OBJECT and self._picks_from(np):
                self._partitive(np, sub)  # "the larger of the two toolboxes"
            elif sub is not None and sub.kind == ONE and sub.quantity and not sub.labels:
                # "the smaller bin of the two by the desk": the group is the named kind,
                # and what is said of the group holds for the target
                np.constraints += sub.constraints
                np.places += sub.places
            elif sub is not None and sub.words:
                np.words += ["of", *sub.words]  # "a cup of tea", "the bag of chips"
                # where the contents are is where the container is ("the bottle of water
                # on the desk"); what they look like stays with them ("of red wine")
                np.constraints += [
                    c for c in sub.constraints if not isinstance(c, AttributeConstraint)
                ]
                np.places += sub.places
            return True  # "the middle monitor of the three": the group, counted
        return False

    def _leads_to(self, np: NP) -> bool:
        """ "the door to the toilet": the door is one of the room's (a room constraint on
        the door itself, never on what the request seeks); "the door to the garden": the
        words stay with the door."""
        if self.at("anaphor", "side", k=1) or self.at("side", k=2):
            return False  # "the door to its right", "the door to the left"
        snap = self.state()
        self.advance()
        start = self.i
        sub = self.parse_np(landmark=True) if self.np_start() else None
        if sub is None or sub.kind not in (OBJECT, ROOM, FLOOR):
            self.restore(snap)
            return False
        rtype = sub.room_type if sub.kind == ROOM else room_vocab.room_type(sub.noun)
        if rtype is not None:  # "toilet" names a room here, though it is also a thing
            np.constraints.append(
                RoomConstraint(
                    type=rtype,
                    name=sub.noun,
                    text=f"to {sub.noun}",
                    weight=self.weight("room"),
                    opening=True,
                )
            )
        else:
            said = [t.text for t in self.toks[start : self.i] if not t.has("det")]
            np.words += ["to", *said]
        return True

    def _plural_clause(self, np: NP) -> bool:
        """A relative clause whose verb is plural ("that are", "which aren't", "that
        have") cannot describe a singular noun."""
        verb = self.peek(1)
        return (
            not np.plural
            and verb is not None
            and verb.text in ("are", "were", "have", "do", "don't")
        )

    def _state_word(self, np: NP, tok: Tok) -> bool:
        """After "is": a participle or "on" / "off" that states the node's state ("that
        isn't made", "not turned on", "that are not pushed in", "the lamp that's on")."""
        nxt = self.peek(1)
        if tok.text in ("on", "off") and (nxt is None or not self.np_start(1)):
            value = tok.text
            self.advance()
        elif tok.tag in ("VBN", "VBD") and not tok.has("prep", "noun", "unk", "be"):
            self.advance()
            value = tok.text
            particle = self.peek()
            if (
                particle is not None
                and particle.text in ("in", "on", "off", "up", "out", "down")
                and not self.np_start(1)
            ):
                self.advance()  # "pushed in", "dried out"; "turned on" is "on"
                value = particle.text if tok.text in _SWITCHED else f"{tok.text} {particle.text}"
        else:
            return False
        np.constraints.append(
            AttributeConstraint(
                key="state", value=value, negated=self.take_neg(), weight=self.weight("attribute"),
                text=value,
            )
        )  # fmt: skip
        return True

    def _doing_word(self, np: NP, tok: Tok) -> bool:
        """After "that (doesn't)" / "that is (not)": a verb with no object says what the
        thing does or is doing ("that doesn't wobble", "isn't charging"), a state."""
        phrasal = self._neg and tok.has("fverb") and " " in tok.text  # "isn't plugged in"
        posture = (
            (self._neg or np.kind == ONE)
            and tok.has("be")
            and tok.tag == "VBG"
            and self.text_at(1) in _POSTURE_ENDS
        )  # "that isn't standing up", "not the ones standing up"
        if not phrasal and (tok.pos != "VERB" or tok.tag not in ("VB", "VBG", "VBZ", "VBP", "VBN")):
            return False
        if not posture and tok.has("prep", "noun", "be", "have", "placement", "view"):
            return False
        if tok.has("fverb") and not self._neg:
            return False  # "the desk that serves for work": a function
        before = self.peek(-1)
        if before is not None and before.has("modal") and before.text.split()[0] not in _DO:
            return False  # "something that could help": what it can do, no state
        # "that isn't plugged in", "not hanging up": the verb's particle belongs to it
        particle = self.peek(1)
        k = 2 if particle is not None and (posture or (self._neg and particle.tag == "RP")) else 1
        if tok.tag == "VBN" and k == 1 and not phrasal and (not self._neg or tok.has("adj")):
            return False  # a participle alone is an adjective's business ("cracked")
        after = self.peek(k)
        ends: tuple[str, ...] = ("comma", "and", "but", "or", "sub", "rel")
        if phrasal:
            ends = (*ends, "prep", "placement")  # "that isn't plugged in by the bed"
        if after is not None and not after.has(*ends):
            return False  # "that holds the TV", "that sits by …": more than a state
        relative = any(t.has("rel") for t in self.toks[max(0, self.i - 3) : self.i])
        words = [self.advance().text for _ in range(k)]
        verb = tok.text if tok.tag in ("VBG", "VBN") or phrasal else (tok.lemma or tok.text)
        if k == 2 and words[1] in ("on", "off"):
            value = text = words[1]  # "not turned on": the state "on"
        else:
            value, text = " ".join([verb, *words[1:]]), " ".join(words)
        neg = self.take_neg()
        if neg and not relative and tok.tag != "VBN" and self._reports_fault(tok, words):
            value, neg, text = "broken", False, f"not {text}"  # "it won't charge": broken
        np.constraints.append(
            AttributeConstraint(
                key="state", value=value, negated=neg, weight=self.weight("attribute"), text=text
            )
        )
        return True

    @staticmethod
    def _reports_fault(tok: Tok, words: list[str]) -> bool:
        """Whether a negated verb said of the thing itself (not in a relative clause)
        reports a fault ("the scanner won't charge", "the camera isn't connecting"); "the
        tablet that's not charging" and "not turned on" tell one thing from another."""
        return " ".join([tok.lemma or tok.text, *words[1:]]) in lexicon().fault_verbs

    def _position(self, np: NP, sub: NP, predicate: str) -> None:
        """ "the top of the stairs", "the far end of the hallway": a position, not a
        thing; what stands there is sought (in a room: the room; else near the object)."""
        where = " ".join(np.words)
        np.kind, np.labels, np.known = VAGUE, [], False
        np.words = [*np.words, "of", *sub.words]
        if sub.kind == ROOM:
            np.places.append(self._room(sub, False, f"{where} of {sub.noun}", None))
        else:
            np.constraints.append(
                RelationConstraint(
                    predicate=predicate, landmark=sub.landmark(), weight=self.weight("relation"),
                    text=f"{where} of {sub.noun or sub.kind}",
                )
            )  # fmt: skip
            np.places += sub.places
        self.notes.append(f"'{where} of {sub.noun or 'it'}' is a position, not the target")

    def adopt_group(self, np: NP) -> None:
        """A pending group ("in the row of lockers") names what a bare "the last one"
        picks from."""
        group = self.group
        if group is None or np.kind not in (ONE, ANAPHOR) or np.labels:
            return
        np.kind, np.labels, np.words, np.known = OBJECT, group.labels, group.words, group.known
        np.constraints += group.constraints
        np.places += group.places
        self.group = None
        self.notes.append(f"the one is picked from the group of {group.noun!r}")

    @staticmethod
    def _picks_from(np: NP) -> bool:
        """Whether ``np`` picks one of what "of …" names: "the larger of", "the second
        of", "one of", "the leftmost of", "the stack of" (not "full of", "made of")."""
        if np.kind == OBJECT and np.words:
            last, quantities = np.words[-1], lexicon().quantity_nouns
            if last in quantities or (last.endswith("s") and last[:-1] in quantities):
                return True  # "the pair of shoes", "pairs of shoes"
        if np.kind not in (ONE, GENERIC) or np.labels:
            return False
        ranked = any(isinstance(c, Superlative) for c in np.constraints)
        # "the darker of the two rugs", "the newer of the laptops": a comparison
        compared = any(
            isinstance(c, AttributeConstraint) and c.text.endswith("er") for c in np.constraints
        )
        return (
            ranked
            or compared
            or np.kind == GENERIC
            or bool(np.superlative or np.ordinal or np.direction or np.quantity)
        )

    def _partitive(self, np: NP, sub: NP) -> None:
        """ "the larger of the two toolboxes", "the second of the chairs": the phrase
        after "of" names what the head picks from."""
        np.grouped = np.kind == OBJECT  # "the row of lockers": a group to pick from
        np.kind, np.labels, np.words, np.known = OBJECT, sub.labels, sub.words, sub.known
        np.plural = False
        np.constraints += sub.constraints
        np.places += sub.places
        self.notes.append(f"'of {sub.noun}' names what the request picks from")

    def _counted_from(self, np: NP) -> bool:
        """ "the second chair from the window", "the third one from the door": an ordinal
        counted by distance from a landmark."""
        if np.ordinal is None or np.direction is not None or not self.np_start(1):
            return False
        snap = self.state()
        self.advance()
        mark = self.parse_np(landmark=True)
        if mark is None or mark.kind != OBJECT or not mark.labels:
            self.restore(snap)
            return False
        np.counted_from = mark.landmark()
        return True

    def _direction(self, np: NP) -> bool:
        """ "from the left", "on your right", "to the right side", "in front", "at the
        back" (no "of" after: "to the left of the sofa" is a relation)."""
        tok = self.peek()
        assert tok is not None
        if (
            tok.has("prep")
            and tok.tags["prep"] in ("in_front_of", "behind")
            and (self.peek(1) is None or self.at("comma", "and", "but", "be", "rel", k=1))
        ):
            self.advance()  # "the one in front", "the chair behind"
            np.direction = "front" if tok.tags["prep"] == "in_front_of" else "back"
            return True
        k = 1
        while self.at("det", "seeker", k=k) and k < 3:
            k += 1  # "the", "your", "my"
        counted = np.ordinal is not None and not np.labels
        if counted and self._side_of_group(np, k):
            return True
        if not self.at("dir", k=k):
            return False
        end = k + 1
        if self.text_at(end) == "side":
            end += 1
        if (self.at("of", k=end) and not (counted and self._group_follows(end))) or (
            self.at("det", k=end) and self.np_start(end)
        ):
            return False  # "to the left of the sofa", "in near the doorway"
        if self.at("noun", "unk", "room", k=end):
            return False  # "beneath the left window": the side is the landmark's; "in the
            # front bathroom": which bathroom
        np.direction = self.toks[self.i + k].tags["dir"]
        self.i += end
        return True

    def _middle_here(self, np: NP) -> bool:
        """ "in the middle" / "in the centre" of a row (not "of the room")."""
        k = 2 if self.at("det", k=1) else 1
        if not self.at("middle", k=k):
            return False
        if self.at("of", k=k + 1) and (np.labels or not self._group_follows(k + 1)):
            return False  # "in the middle of the room" (but "of the three sinks" is a row)
        self.i += k + 1
        if np.superlative is None:
            np.superlative = "middle"
        return True

    def _group_follows(self, k: int) -> bool:
        """ "of the three chairs" ``k`` tokens ahead: things of one kind that a side or a
        count picks from ("the leftmost of the chairs", "the second from the right of
        the four chairs"), not a place ("the far left of the room", "left of the sofa")."""
        return self.at("of", k=k) and self._group_at(k + 1) is not None

    def _group_at(self, k: int) -> NP | None:
        """The plural object phrase that starts ``k`` tokens ahead, read without moving."""
        snap = self.state()
        sub = self._take_group(k)
        self.restore(snap)
        return sub

    def _take_group(self, k: int) -> NP | None:
        """Read the plural object phrase that starts ``k`` tokens ahead and move past it;
        None (and no move) when none starts there."""
        if not self.np_start(k):
            return None
        snap = self.state()
        self.i += k
        sub = self.parse_np(landmark=True)
        if sub is None or sub.kind != OBJECT or not sub.plural:
            self.restore(snap)
            return None
        return sub

    def _middle_of_group(self, np: NP, tok: Tok) -> bool:
        """ "the one in the middle of the three sinks": the middle one of a group (a
        named thing "in the middle of" others stands between them)."""
        if tok.tags.get("prep") != "between" or tok.text == "between":
            return False
        if np.kind == OBJECT and np.labels and (end := self._count_only(1)):
            self.i += end  # "the monitor in the middle of the three": of the monitors
            np.superlative = "middle"
            return True
        if np.kind != ONE or np.labels or (sub := self._take_group(1)) is None:
            return False
        np.superlative = "middle"
        self._partitive(np, sub)
        return True

    def _count_only(self, k: int) -> int:
        """Tokens of a bare count starting ``k`` ahead ("the three", "the 4"), with no
        noun after it; 0 when there is none."""
        j = k + 1 if self.at("det", k=k) else k
        tok = self.peek(j)
        if tok is None or not tok.has("num") or tok.has("one") or self.nounish(j + 1):
            return 0
        return j + 1

    def _side_of_group(self, np: NP, k: int) -> bool:
        """ "the second from the right of the four chairs": the side is counted from, and
        the group after it (one "right of" token) is what the count picks from."""
        side = self.peek(k)
        if side is None or side.tags.get("prep") not in ("left_of", "right_of"):
            return False
        if (sub := self._take_group(k + 1)) is None:
            return False
        np.direction = str(side.tags["prep"]).removesuffix("_of")
        self._partitive(np, sub)
        return True

    def _placement(self, np: NP, where: str, text: str) -> None:
        """A placement constraint ("against the wall", "in the corner"), with the room
        that may follow ("in the corner of the kitchen")."""
        np.constraints.append(
            PlacementConstraint(
                where=where, negated=self.take_neg(), weight=self.weight("placement"), text=text
            )
        )
        if self.at("of") and self.np_start(1):
            snap = self.state()
            self.advance()
            room = self.parse_np(landmark=True)
            if room is None or room.kind != ROOM:
                self.restore(snap)
                return
            if room.room_type or room.labels:
                np.places.append(self._room(room, False, f"of {room.noun}", None))
            elif room.beside:
                # "of the room" says nothing more, and what follows it ("in the corner of
                # the room next to the sofa") places the target, not the room: read up to
                # the room word and leave the rest
                self.restore(snap)
                self.advance()
                while (tok := self.peek()) is not None and tok.text != room.noun:
                    self.advance()
                if tok is not None:
                    self.advance()

    # ---------------------------------------------------------- prepositions
    def _side_of(self, lm: NP) -> NP:
        """ "on the back of the chair", "on the side of the fridge", "at the far end of
        it": a side of a thing names no landmark of its own; the thing after "of" is the
        landmark."""
        k = 1 if self.at("dir", "side") else 0  # "the back" leaves "back" unread
        if lm.kind != ONE or lm.labels or not self.at("of", k=k) or not self.np_start(k + 1):
            return lm
        snap = self.state()
        self.i += k + 1
        thing = self.parse_np(landmark=True)
        named = thing is not None and thing.kind == OBJECT and bool(thing.labels)
        if thing is None or not (named or thing.kind == ANAPHOR):
            self.restore(snap)
            return lm
        return thing  # "at the far end of it": the thing said before

    def state_to_check(self) -> bool:
        """Whether the negation at the cursor says a state to check: right after "is" in
        a clause that a verb of checking opens ("check (that) the tap isn't dripping",
        "make sure the oven is not on"), not in a relative clause ("the drawer that
        isn't locked")."""
        if self.i < 2 or not self.toks[self.i - 1].has("be"):
            return False
        if self.toks[self.i - 2].has("rel") or self.toks[self.i - 2].text in ("that", "which"):
            return False
        texts = [t.text for t in self.toks[: self.i - 1]]
        if "which" in texts or "what" in texts:
            return False  # "check which window isn't closed": the one that is not
        lemmas = {t.lemma for t in self.toks[: self.i - 1]}
        sure = any(
            a in ("make", "making", "makes") and b == "sure" for a, b in itertools.pairwise(texts)
        )
        return sure or bool(lemmas & _CHECKING)

    def _just_outside(self, at: int, lm: NP) -> bool:
        """Whether "outside" (token ``at``) places a thing beside a room rather than out
        of it: "just / right outside", after the room the thing is in ("in the hallway
        outside the lab"), or outside a numbered room ("outside room 12")."""
        before = self.toks[max(0, at - 4) : at]
        if before and before[-1].text in _RIGHT_BY:
            return True
        if any(t.has("room") for t in before):
            return True
        return any(w.isdigit() for w in lm.words)

    def parse_pp(self, predicate: str | None = None) -> list[Constraint] | None:
        """A prepositional phrase → constraints (empty for deictic places); None when
        the preposition has no object. ``predicate`` overrides the preposition's own."""
        at = self.i
        tok = self.advance()
        neg = self.take_neg()
        if predicate is None:
            predicate = tok.tags["prep"] if not tok.has("away") else "near"
        if tok.text in lexicon().outside_prepositions:
            predicate = "inside"  # "outside the kitchen": not in it
        if tok.has("away"):
            neg = not neg
        stress = self.take_stress()
        weight = weighted("relation", stress)
        if predicate == "between":
            return self._between(neg, weight, tok.text)
        self.place_object = predicate in ("inside", "on") and tok.text in _PLACE_WORDS
        try:
            lm = self.parse_np(landmark=True)
        finally:
            self.place_object = False
        if lm is None:
            return None
        lm = self._side_of(lm)
        if predicate == "inside" and tok.text in lexicon().outside_prepositions:
            just_outside = self._just_outside(at, lm)
            if lm.kind == ROOM and just_outside:
                # "just outside the kitchen", "in the hallway outside the lab", "outside
                # room 12": beside the room, in another one; neither in it nor ruled out
                self.notes.append(f"'{tok.text} {lm.noun}': beside that room, not out of it")
                return []
            if _opening(lm) or just_outside:
                # "the patio chair outside the sliding door", "… outside the lab"
                predicate, neg = "near", not neg
        text = f"{tok.text} {lm.noun or lm.kind}"
        places = lm.places
        if lm.kind == FLOOR and lm.floor is not None:
            return [self._floor(lm.floor, neg)]
        if lm.grouped and not neg and predicate in ("inside", "on", "near", "next_to"):
            self.group = lm  # "in the row of lockers": what "the last one" picks from
            return [*lm.constraints, *places]
        # a room word before the noun names the room ("on the living room wall")
        rooms = [c for c in lm.constraints if isinstance(c, RoomConstraint)]
        bare = len(lm.words) == 1 or (
            len(lm.words) == 2 and bool(rooms) and rooms == lm.constraints
        )
        where = lexicon().placement_nouns.get(lm.words[-1]) if bare else None
        if where is not None and predicate in _PLACEMENT_PREDICATES:
            # "on the far wall", "in the back corner": where in the room, not an object
            placement = PlacementConstraint(
                where=where, negated=neg, weight=weighted("placement", stress), text=text
            )
            # what places the wall places the target ("leaning against the wall next to
            # the bed"); the wall's own looks stay with it
            beside = [c for c in lm.constraints if isinstance(c, RelationConstraint)]
            return [placement, *[replace(c, negated=neg) for c in rooms], *beside, *places]
        on_room = lm.kind == ROOM and bool(lm.words) and lm.words[-1] in lexicon().on_rooms
        if (
            lm.kind in (ROOM, AREA)
            and predicate in _PLACE_PREDICATES
            and (
                tok.text != "on" or on_room  # "on the landing", "on the deck": in that room
            )
        ):
            if lm.kind == ROOM:
                place: Constraint = self._room(lm, neg, text, stress)
            else:
                place = AreaConstraint(
                    label=lm.noun, negated=neg, text=text, weight=weighted("area", stress)
                )
            # the room's size words and ordinals pick the room ("in the little WC", "in
            # the second bathroom"), they do not describe the target; a superlative
            # measured to a thing does ("the stool in the kitchen closest to the hall")
            kept = [
                c
                for c in lm.constraints
                if not (isinstance(c, AttributeConstraint) and c.key == "size")
                and not (
                    isinstance(c, Superlative)
                    and (c.landmark is None or c.measure not in ("closest", "farthest"))
                )
            ]
            return [place, *kept, *places]
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
        if second is None and (first.plural or (first.quantity or 0) >= 2):
            second = first  # "between the two beds": two of one kind
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

    def parse_with(self, np: NP, *, landmark: bool = False) -> bool:
        """ "with X" / "without X" / "with no X next to it" / "that has X" on ``np``; on
        a room that places something else (``landmark``), "with X" says which room.
        False (nothing consumed) when X is a part a room cannot have: "the chair in the
        room without arms" is about the chair."""
        snap = self.state()
        tok = self.advance()
        if self._empty_of_things():
            return True
        neg = self.take_neg() != tok.has("without")
        if self.at("neg"):
            self.advance()
            neg = not neg
        lm = self._with_object()
        if lm is None:
            if neg:
                self.negate()  # "that hasn't been watered": for what follows
            return True
        if np.kind in (ROOM, AREA, GENERIC_AREA) and self._is_part(np, lm):
            self.restore(snap)
            return False
        if landmark and np.kind == ROOM and not neg and not np.beside and (lm.noun or lm.labels):
            np.beside = lm.noun or lm.labels[0]  # "the bathroom with the shower": which one
            np.places += lm.places
            return True
        held = [lm]
        if np.kind == OBJECT or np.kind == ONE:
            held += self._more_with_objects()  # "with two pillows and a blanket (on it)"
        predicate = "contains" if np.kind in (ROOM, AREA, GENERIC_AREA) else "with"
        after = self.peek()
        on_it = after is not None and after.has("prep") and self.at("anaphor", k=1)
        if on_it:
            assert after is not None
            self.i += 2
        for thing in held:
            np.constraints.append(
                self._with_constraint(np, thing, neg, tok.text, predicate, after if on_it else None)
            )
            np.places += thing.places
        if on_it and np.kind in (OBJECT, ONE):
            self._more_placed_with(np, neg, tok.text)
        return True

    def _more_placed_with(self, np: NP, neg: bool, word: str) -> None:
        """Further things a "with" phrase places by the target after the first one's place
        ("the sink with the mirror over it and the two baskets underneath", "… and a
        lamp beside it"): each a relation of the target, not a second target."""
        while self.at("and") and self.np_start(1) and not self.at("anaphor", k=1):
            snap = self.state()
            self.advance()
            thing = self._with_object()
            where = self.peek()
            if thing is None or thing.kind != OBJECT or not thing.labels or where is None:
                self.restore(snap)
                return
            if where.has("prep") and self.at("anaphor", k=1):
                self.i += 2
                prep = str(where.tags["prep"])
            elif where.has("prep") and where.tags["prep"] == "under" and not self.np_start(1):
                self.i += 1  # "… and two baskets underneath"
                prep = "under"
            else:
                self.restore(snap)
                return
            predicate = lexicon().with_inverse.get(prep, prep)
            np.constraints.append(
                RelationConstraint(
                    predicate=predicate, landmark=thing.landmark(), negated=neg,
                    weight=self.weight("relation"), text=f"{word} {thing.noun}",
                )
            )  # fmt: skip
            np.places += thing.places

    def _empty_of_things(self) -> bool:
        """ "with nothing (else) on it": read and set aside with a note. Whether it rules
        anything out is a judgement people make both ways (most of the request sets
        written here say it does not); "without anything on it" is the negated form."""
        k = 2 if self.text_at(1) == "else" else 1
        if self.text_at() != "nothing" or not (
            self.at("prep", k=k) and self.at("anaphor", k=k + 1)
        ):
            return False
        said = " ".join(t.text for t in self.toks[self.i : self.i + k + 2])
        self.i += k + 2
        self.notes.append(f"'with {said}': an empty surface is not checked")
        return True

    def _with_object(self) -> NP | None:
        """The thing a "with" / "has" phrase names ("with a lid", "has two monitors")."""
        self.with_depth += 1
        try:
            return self.parse_np(landmark=True)
        finally:
            self.with_depth -= 1

    def _more_with_objects(self) -> list[NP]:
        """Further things after "and" in a "with" / "has" phrase: "the sofa with two
        pillows and a blanket", "the desk has a lamp and a computer on it"."""
        more: list[NP] = []
        while self.at("and") and self.np_start(1) and not self.at("anaphor", k=1):
            snap = self.state()
            self.advance()
            thing = self._with_object()
            if thing is None or thing.kind != OBJECT or not thing.labels:
                self.restore(snap)
                break
            more.append(thing)
        return more

    def _with_constraint(
        self, np: NP, lm: NP, neg: bool, word: str, predicate: str, on_it: Tok | None
    ) -> Constraint:
        """One thing ``np`` has: a part ("with a yellow lid") or a thing with it ("with a
        lamp on it": the lamp is on the target)."""
        if predicate == "with" and self._is_part(np, lm) and not (on_it and lm.known):
            return self._part(np, lm, neg, word)  # "a cup with no lid on it": the cup's lid
        if on_it is not None:
            predicate = lexicon().with_inverse.get(on_it.tags["prep"], on_it.tags["prep"])
            if predicate == "between":
                predicate = "contains"  # "a shelf with books in the middle of it"
        return RelationConstraint(
            predicate=predicate,
            landmark=lm.landmark(),
            negated=neg,
            weight=self.weight("relation"),
            text=f"{word} {lm.noun or lm.kind}",
        )

    @staticmethod
    def _is_part(np: NP, lm: NP) -> bool:
        """Whether ``lm`` ("a yellow lid", "wheels") names a part of what ``np`` names: a
        part of that kind, or a part of some kind that is no object kind itself ("wheels",
        "armrests"; a "blanket" on a bed is an object of its own)."""
        if lm.kind != OBJECT or not lm.words:
            return False
        word = lm.words[-1]
        if any(object_vocab.is_part(word, label) for label in np.labels):
            return True
        return not lm.known and object_vocab.is_part(word, None)

    def _part(self, np: NP, lm: NP, neg: bool, word: str) -> AttributeConstraint:
        """ "with a yellow lid" → part = "yellow lid" (its colour or material first)."""
        values = [
            c.value for c in lm.constraints if isinstance(c, AttributeConstraint) and not c.negated
        ]
        # what the phrase went on to say ("with a blue mattress next to a brown
        # nightstand") describes the whole object, not its part
        np.constraints += [c for c in lm.constraints if not isinstance(c, AttributeConstraint)]
        np.places += lm.places
        # a part keeps its own word ("a white frame", not the painting "frame" may name)
        word_here = lemma_phrase(lm.words[-1]) if lm.words else ""
        own = word_here and any(object_vocab.is_part(word_here, t) for t in (*np.labels, None))
        label = word_here if own else (lm.labels[0] if lm.labels else lm.words[-1])
        value = " ".join([*values, label])
        self.notes.append(f"'{word} {lm.noun}' is a part of the target, not an object")
        return AttributeConstraint(
            key="part", value=value, negated=neg, weight=weighted("attribute", None),
            text=f"{word} {' '.join([*values, lm.noun])}",
        )  # fmt: skip

    def _superlative(self, np: NP, measure: str, text: str, landmark_now: bool = False) -> None:
        """A superlative ("the tallest", "closest to the door") → a constraint on ``np``;
        "closest to the centre of the room" says where in the room: a placement."""
        weight = self.weight("superlative")
        neg = self.take_neg()  # "the monitor which is not closest to the window"
        lm = None
        if measure in ("closest", "farthest") and not landmark_now:
            side = self._towards_side()
            if side is not None:  # "the one farthest to the right"
                np.constraints.append(
                    Superlative(
                        measure="ordinal", ordinal=1, direction=side, weight=weight,
                        text=f"{text} to the {side}", negated=neg,
                    )
                )  # fmt: skip
                return
        if measure in ("closest", "farthest"):
            if not landmark_now and self.text_at() in ("away from", "far from"):
                self.advance()  # "the cabinet farthest away from the sink"
                landmark_now = True
            elif not landmark_now and self.at("to", "from"):
                self.advance()
                landmark_now = True
            if self._centre_of(np, measure, text):
                return
            if landmark_now or self.at("det"):
                lm = self.parse_np(landmark=True)
        np.constraints.append(
            Superlative(
                measure=measure,
                landmark=lm.landmark() if lm is not None else None,
                weight=weight,
                text=f"{text} {lm.noun}" if lm is not None else text,
                negated=neg,
            )
        )

    def _centre_of(self, np: NP, measure: str, text: str) -> bool:
        """ "closest to the centre of the room": where in the room, a placement (with the
        room, when it is named; "farthest from …" rules the centre out); "closest to the
        middle of the table": the table is the landmark."""
        k = 1 if self.at("det") else 0
        centre = self.peek(k)
        if centre is None or centre.text not in _CENTRE_WORDS or not self.at("of", k=k + 1):
            return False
        snap = self.state()
        self.i += k + 2
        sub = self.parse_np(landmark=True) if self.np_start() else None
        if sub is not None and sub.kind == OBJECT and sub.labels:
            np.constraints.append(
                Superlative(
                    measure=measure, landmark=sub.landmark(), weight=self.weight("superlative"),
                    text=f"{text} {centre.text} of {sub.noun}",
                )
            )  # fmt: skip
            return True
        if sub is None or sub.kind != ROOM:
            self.restore(snap)
            return False
        np.constraints.append(
            PlacementConstraint(
                where="centre", negated=measure == "farthest", weight=self.weight("placement"),
                text=f"{text} {'from' if measure == 'farthest' else 'to'} the {centre.text} "
                f"of the {sub.noun}",
            )
        )  # fmt: skip
        if sub.room_type or sub.labels:
            np.places.append(self._room(sub, False, f"of {sub.noun}", None))
        return True

    def _towards_side(self) -> str | None:
        """ "to the right", "to your left", "left" after "farthest": the side, consumed."""
        k = 0
        if self.at("to", "prep", k=0) and self.peek() is not None:
            k = 1
        while self.at("det", "seeker", k=k) and k < 3:
            k += 1
        if not self.at("dir", k=k) or self.at("of", "room", k=k + 1):
            return None  # "in the front bathroom": which bathroom, not a side
        side = str(self.toks[self.i + k].tags["dir"])
        if k == 0 or self.at("to", k=0) or self.text_at() in ("on", "at"):
            self.i += k + 1
            return side
        return None

    @classmethod
    def room_place(cls, np: NP) -> RoomConstraint:
        """The room a room phrase names, as a constraint on the target ("go to the
        lounge. Find the table …": the table is in the lounge)."""
        return cls._room(np, False, np.noun, None)

    @staticmethod
    def _room(np: NP, neg: bool, text: str, stress: str | None) -> RoomConstraint:
        # "the small bathroom", "the big bedroom": the size says which room of the type
        size = next(
            (
                c.value
                for c in np.constraints
                if isinstance(c, AttributeConstraint) and c.key == "size" and not c.negated
            ),
            None,
        ) or next(
            (
                _ROOM_SIZE_OF[c.measure]  # "in the biggest bedroom"
                for c in np.constraints
                if isinstance(c, Superlative) and c.landmark is None and c.measure in _ROOM_SIZE_OF
            ),
            None,
        )
        name = f"{size} {np.noun}" if size in ("small", "large") and np.noun else np.noun
        later = any(
            isinstance(c, Superlative) and c.landmark is None and (c.ordinal or 0) >= 2
            for c in np.constraints
        )
        if (np.other or later) and name and size is None:
            name = f"other {name}"  # "the second bathroom", "the other bedroom": not the main one
        if np.room_side and name:
            name = f"{np.room_side} {name}"  # "the front bathroom": the one by the entrance
        return RoomConstraint(
            type=np.room_type, name=name, negated=neg, text=text,
            weight=weighted("room", stress), beside=np.beside,
        )  # fmt: skip

    def _floor(self, value: int | str, neg: bool = False) -> FloorConstraint:
        if isinstance(value, int):
            return FloorConstraint(level=value, negated=neg, text=f"floor {value}")
        return FloorConstraint(relative=value, negated=neg, text=value)


_CENTRE_WORDS = frozenset({"center", "centre", "middle"})
# A room's superlative of size names it as its size word does ("the biggest bedroom").
_ROOM_SIZE_OF = {"largest": "large", "smallest": "small"}
# Parts built into a thing, which a map rarely holds apart from it ("the oven door").
_BUILT_IN_PARTS = frozenset(
    {"door", "lid", "handle", "knob", "leg", "arm", "armrest", "backrest", "seat", "screen",
     "drawer", "panel", "button", "dial", "hinge", "cushion"}
)  # fmt: skip
_DO = frozenset({"do", "does", "did"})


def _open_label(run: list[Tok]) -> str:
    """The label of a noun no vocabulary knows: the compound with its last word's lemma
    ("paper towel dispensers" → "paper towel dispenser"), or the known kind its tail names
    ("metal shelving unit" → the kind of "shelving unit")."""
    while len(run) > 1 and run[0].has("room"):
        run = run[1:]  # "cafeteria roundmetaltable": the room word says where, not what
    last = run[-1]
    head = str(last.tags.get("unk") or last.lemma or last.text)
    phrase = " ".join([*(t.text for t in run[:-1]), head])
    known = object_vocab.labels_for(phrase)
    return known[0] if len(known) == 1 else phrase


def _room_mark(tok: Tok) -> bool:
    """Whether ``tok`` is the letter or number that names one room of a kind ("B" of
    "conference room B", "2" of "bedroom 2")."""
    return (len(tok.text) == 1 and tok.text.isalpha()) or tok.text.isdigit()
