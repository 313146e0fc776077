"""Words for requests: nouns, plurals, articles and the phrases that render an ObjectSpec.

:class:`Phrasing` turns the parts of one :class:`ObjectSpec` into English. Its word
choices (which synonym, which preposition) are picked by a stable hash of a seed and the
part's position, so every variant rendered for one request uses the same words.
"""

from __future__ import annotations

import re
import zlib
from collections.abc import Sequence

from inherit_sg.ingest.synthetic.truth_spec import (
    AreaConstraint,
    AttributeConstraint,
    FloorConstraint,
    ObjectSpec,
    RelationConstraint,
    RoomConstraint,
)
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS, ROOM_SYNONYMS
from inherit_sg.wording import article

NegatablePart = (
    RoomConstraint | AreaConstraint | FloorConstraint | AttributeConstraint | RelationConstraint
)

PREPOSITIONS: dict[str, tuple[str, ...]] = {
    "on": ("on", "on top of", "sitting on"),
    "under": ("under", "underneath", "below"),
    "above": ("above", "over"),
    "next_to": ("next to", "beside", "right next to", "by"),
    "near": ("near", "close to"),
}
# "with a vase on it": the preposition of the inverse predicate ("supports" has no own one).
WITH_PREPOSITIONS: dict[str, tuple[str, ...]] = {
    "supports": ("on",),
    "above": ("under", "underneath"),
    "under": ("above", "over"),
    "next_to": ("next to",),
    "near": ("near",),
}
SUPERLATIVE_WORDS = {
    "largest": ("largest", "biggest"),
    "smallest": ("smallest",),
    "tallest": ("tallest",),
    "shortest": ("shortest",),
}
SIZE_ADJECTIVES = {"small": "small", "medium": "medium-sized", "large": "large"}
MATERIAL_ADJECTIVES = {"wood": "wooden"}
ORDINALS = ("first", "second", "third", "fourth", "fifth")
_IRREGULAR_PLURALS = {
    "shelf": "shelves",
    "bookshelf": "bookshelves",
    "stairs": "stairs",
    "mouse": "mice",
    "shelves": "shelves",
    "shoes": "shoes",
    "tissues": "tissues",
}
# Nouns counted in pieces rather than as items: no plural, "some" rather than "a".
UNCOUNTABLE = frozenset(
    {"clothes", "clothing", "blinds", "cosmetics", "makeup", "toilet paper", "luggage", "shelving"}
)
_ABBREVIATIONS = re.compile(r"\btv(s?)\b")


def noun_words(label: str) -> tuple[str, ...]:
    """Words people use for objects of ``label`` (its own name when the kind is unknown)."""
    kind = OBJECT_KINDS.get(label)
    if kind is None or not kind.synonyms:
        return (label,)
    return kind.synonyms


def labels_for_noun(noun: str, labels: Sequence[str]) -> list[str]:
    """The labels among ``labels`` that ``noun`` can name ("lamp": lamp and table lamp)."""
    return sorted({lb for lb in labels if noun == lb or noun in noun_words(lb)})


def room_words(room_type: str) -> tuple[str, ...]:
    """Words for a room type."""
    return ROOM_SYNONYMS.get(room_type, (room_type,))


def plural(noun: str) -> str:
    """English plural of a (possibly multi-word) noun."""
    if noun.startswith("chest of "):
        return "chests" + noun[len("chest") :]
    if noun in UNCOUNTABLE:
        return noun
    if noun.startswith(("pair of ", "box of ", "bowl of ", "bar of ", "can of ")):
        first, _, rest = noun.partition(" of ")
        return f"{plural(first)} of {rest}"
    head, _, last = noun.rpartition(" ")
    if last in _IRREGULAR_PLURALS:
        word = _IRREGULAR_PLURALS[last]
    elif last.endswith(("s", "sh", "ch", "x", "z")):
        word = last + "es"
    elif last.endswith("y") and last[-2:-1] not in "aeiou":
        word = last[:-1] + "ies"
    else:
        word = last + "s"
    return f"{head} {word}" if head else word


def display(text: str) -> str:
    """Final touches: abbreviations in capitals, single spaces, first letter upper-case."""
    out = " ".join(text.split()).replace(" ,", ",").replace(" .", ".").replace(" ?", "?")
    out = _ABBREVIATIONS.sub(lambda m: "TV" + m.group(1), out)
    return out[:1].upper() + out[1:]


def floor_words(floor: FloorConstraint) -> tuple[str, ...]:
    """Phrases naming a floor: "upstairs", "on the second floor", …"""
    if floor.relative == "upstairs":
        return ("upstairs",)
    if floor.relative == "downstairs":
        return ("downstairs",)
    if floor.relative == "top":
        return ("on the top floor",)
    if floor.relative == "ground" or floor.level == 0:
        return ("on the ground floor", "on the ground floor", "on the first floor")
    level = floor.level if floor.level is not None else 0
    ordinal = ORDINALS[level] if level < len(ORDINALS) else f"number {level + 1}"
    return (f"on the {ordinal} floor",)


class Phrasing:
    """Renders the parts of one spec with stable word choices."""

    def __init__(self, spec: ObjectSpec, seed: int) -> None:
        self.spec = spec
        self.seed = seed

    def pick(self, options: Sequence[str], key: str) -> str:
        """A stable choice among ``options`` for the slot ``key``."""
        return options[zlib.crc32(f"{self.seed}:{key}".encode()) % len(options)]

    # -- nouns --------------------------------------------------------------------
    def noun(self, spec: ObjectSpec | None = None, many: bool = False) -> str:
        """The spec's noun, in the plural when ``many``."""
        s = spec or self.spec
        word = s.noun or (s.labels[0] if s.labels else "thing")
        return plural(word) if many else word

    def adjectives(self, spec: ObjectSpec | None = None, key: str = "t") -> str:
        """Superlative, size, colour and material words of the positive attributes."""
        s = spec or self.spec
        out = []
        if s.superlative:
            out.append(self.pick(SUPERLATIVE_WORDS[s.superlative], f"{key}.sup"))
        values = {a.key: a.value for a in s.attributes if not a.negated}
        if "size" in values:
            out.append(SIZE_ADJECTIVES.get(values["size"], values["size"]))
        if "colour" in values:
            out.append(values["colour"])
        if "material" in values:
            out.append(MATERIAL_ADJECTIVES.get(values["material"], values["material"]))
        return " ".join(out)

    def head(self, det: str, spec: ObjectSpec | None = None, key: str = "t") -> str:
        """Determiner + adjectives + noun; ``det`` is "the", "a", "bare" or "plural"."""
        s = spec or self.spec
        body = " ".join(x for x in (self.adjectives(s, key), self.noun(s, det == "plural")) if x)
        if det == "a":
            return f"{'some' if self.noun(s) in UNCOUNTABLE else article(body)} {body}"
        return body if det == "bare" else f"the {body}"

    # -- places -------------------------------------------------------------------
    def room_ref(self, room: RoomConstraint) -> str:
        """ "the kitchen", "the lounge" or "bedroom 2"."""
        if room.name and (room.type is None or room.name.lower() not in room_words(room.type)):
            return room.name
        return "the " + self.pick(room_words(room.type or room.name or "room"), "room")

    def area_ref(self, area: AreaConstraint) -> str:
        """ "the reading corner"."""
        return f"the {area.label}"

    def floor_phrase(self, floor: FloorConstraint) -> str:
        """ "upstairs", "on the second floor"."""
        return self.pick(floor_words(floor), "floor")

    def place(self, spec: ObjectSpec | None = None, room: bool = True, floor: bool = True) -> str:
        """Positive area, room and floor phrases: "in the reading corner of the lounge upstairs"."""
        s = spec or self.spec
        parts = []
        area = s.area if s.area is not None and not s.area.negated else None
        rc = s.room if room and s.room is not None and not s.room.negated else None
        if area is not None and rc is not None:
            parts.append(f"in {self.area_ref(area)} of {self.room_ref(rc)}")
        elif area is not None:
            parts.append(f"in {self.area_ref(area)}")
        elif rc is not None:
            parts.append(f"in {self.room_ref(rc)}")
        if floor and s.floor is not None and not s.floor.negated:
            parts.append(self.floor_phrase(s.floor))
        return " ".join(parts)

    # -- relations ----------------------------------------------------------------
    def landmark(self, spec: ObjectSpec, det: str, key: str) -> str:
        """A landmark's noun phrase with its own relations ("the table next to the window")."""
        tail = self.relations(spec, key)
        place = self.place(spec)
        return " ".join(x for x in (self.head(det, spec, key), tail, place) if x)

    def relation(self, rel: RelationConstraint, key: str, pronoun: str = "it") -> str:
        """A positive relation: "on the table", "between the sofa and the lamp"."""
        if rel.predicate == "between":
            assert rel.landmark2 is not None
            first = self.landmark(rel.landmark, "the", f"{key}.a")
            return f"between {first} and {self.landmark(rel.landmark2, 'the', f'{key}.b')}"
        # A landmark with its own relations, or a function request ("somewhere to sit near
        # the TV"), reads best after a preposition rather than in a "with ... it" clause.
        if rel.predicate in PREPOSITIONS and (
            rel.predicate not in WITH_PREPOSITIONS
            or rel.landmark.relations
            or self.spec.function is not None
            or self.pick("dw", f"{key}.form") == "d"
        ):
            prep = self.pick(PREPOSITIONS[rel.predicate], f"{key}.prep")
            return f"{prep} {self.landmark(rel.landmark, 'the', key)}"
        prep = self.pick(WITH_PREPOSITIONS[rel.predicate], f"{key}.prep")
        return f"with {self.landmark(rel.landmark, 'a', key)} {prep} {pronoun}"

    def relations(self, spec: ObjectSpec | None = None, key: str = "t", pronoun: str = "it") -> str:
        """All positive relations of ``spec``, joined ("them" refers to a plural target)."""
        s = spec or self.spec
        parts = [
            self.relation(r, f"{key}.r{i}", pronoun)
            for i, r in enumerate(s.relations)
            if not r.negated
        ]
        return " ".join(parts)

    def np(self, det: str, room: bool = True, floor: bool = True, relations: bool = True) -> str:
        """The request's full positive noun phrase."""
        rel = self.relations(pronoun="them" if det == "plural" else "it") if relations else ""
        where = self.place(room=room, floor=floor)
        return " ".join(x for x in (self.head(det), rel, where) if x)

    def scope(self, room: bool = True, floor: bool = True) -> str:
        """Positive relations and places, for function requests ("near the TV upstairs")."""
        return " ".join(x for x in (self.relations(), self.place(room=room, floor=floor)) if x)

    # -- negation -----------------------------------------------------------------
    def negated_part(self) -> NegatablePart | None:
        """The spec's first negated constraint at the top level."""
        s = self.spec
        for part in (s.room, s.area, s.floor, *s.attributes, *s.relations):
            if part is not None and part.negated:
                return part
        return None

    def negated_clause(self) -> str:
        """ "that is not in the kitchen", "without a table next to it", "that isn't red"."""
        part = self.negated_part()
        be = self.pick(("that is not", "that isn't"), "neg.be")
        if isinstance(part, RoomConstraint):
            ref = self.room_ref(part)
            return self.pick((f"{be} in {ref}", f"outside {ref}", f"not in {ref}"), "neg.form")
        if isinstance(part, AreaConstraint):
            return f"{be} in {self.area_ref(part)}"
        if isinstance(part, FloorConstraint):
            return f"{be} {self.floor_phrase(part)}"
        if isinstance(part, AttributeConstraint):
            if part.key == "material":
                return f"{be} made of {part.value}"
            return f"{be} {SIZE_ADJECTIVES.get(part.value, part.value)}"
        if isinstance(part, RelationConstraint):
            return self._negated_relation(part, be)
        raise ValueError("the spec has no negated constraint")

    def _negated_relation(self, rel: RelationConstraint, be: str) -> str:
        if rel.predicate == "between":
            return f"{be} {self.relation(rel, 'neg')}"
        use_with = rel.predicate in WITH_PREPOSITIONS and (
            rel.predicate not in PREPOSITIONS or self.pick("dw", "neg.form") == "w"
        )
        if not use_with:
            prep = self.pick(PREPOSITIONS[rel.predicate], "neg.prep")
            return f"{be} {prep} {self.landmark(rel.landmark, 'a', 'neg')}"
        prep = self.pick(WITH_PREPOSITIONS[rel.predicate], "neg.prep")
        if self.pick(("without", "with no"), "neg.no") == "without":
            return f"without {self.landmark(rel.landmark, 'a', 'neg')} {prep} it"
        return f"with no {self.landmark(rel.landmark, 'bare', 'neg')} {prep} it"

    def excluded_one(self, many: bool) -> str:
        """The excluded objects as "the one(s) in the kitchen" / "the red one"."""
        part = self.negated_part()
        one = "ones" if many else "one"
        if isinstance(part, AttributeConstraint):
            if part.key == "material":
                return f"the {one} made of {part.value}"
            return f"the {SIZE_ADJECTIVES.get(part.value, part.value)} {one}"
        if isinstance(part, RoomConstraint):
            return f"the {one} in {self.room_ref(part)}"
        if isinstance(part, AreaConstraint):
            return f"the {one} in {self.area_ref(part)}"
        if isinstance(part, FloorConstraint):
            return f"the {one} {self.floor_phrase(part)}"
        if isinstance(part, RelationConstraint):
            positive = RelationConstraint(part.predicate, part.landmark, part.landmark2)
            return f"the {one} {self.relation(positive, 'neg', 'them' if many else 'it')}"
        raise ValueError("the spec has no negated constraint")
