"""The noun phrase the grammar builds, and its conversion to targets and landmarks."""

from __future__ import annotations

from dataclasses import dataclass, field

from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    Constraint,
    FunctionConstraint,
    Landmark,
    Target,
)

# Phrase kinds: what the head word names.
OBJECT, ROOM, AREA, FLOOR = "object", "room", "area", "floor"
GENERIC, GENERIC_AREA, VAGUE = "generic", "generic_area", "vague"
ANAPHOR, ONE, PERSON = "anaphor", "one", "person"
PLACE_KINDS = (ROOM, AREA, FLOOR)


@dataclass
class NP:
    """A parsed noun phrase: head, its own constraints, and place constraints that
    attach to the request's head (``places``)."""

    kind: str = OBJECT
    labels: list[str] = field(default_factory=list)
    words: list[str] = field(default_factory=list)
    constraints: list[Constraint] = field(default_factory=list)
    places: list[Constraint] = field(default_factory=list)
    plural: bool = False
    quantity: int | None = None
    other: bool = False
    room_type: str | None = None
    beside: str = ""  # a room's neighbour: "the bathroom off the hall" (room phrases only)
    room_side: str = ""  # "the front bathroom", "the back bedroom" (room phrases only)
    floor: int | str | None = None
    superlative: str | None = None
    ordinal: int | None = None
    counted_from: Landmark | None = None  # "the second chair from the window"
    direction: str | None = None
    known: bool = False  # the head noun is in the lexicon
    excluded: bool = False  # the object of "I don't want …": a kind ruled out
    grouped: bool = False  # "the row of lockers": a group a "one" picks from

    @property
    def noun(self) -> str:
        """The head phrase as written ("recliner sofa")."""
        return " ".join(self.words)

    @property
    def layer(self) -> str:
        """Scene-graph layer the phrase names."""
        if self.kind in (ROOM, AREA, FLOOR):
            return self.kind
        return "area" if self.kind == GENERIC_AREA else "object"

    def functions(self) -> list[FunctionConstraint]:
        """Function constraints attached to the phrase, in order."""
        return [c for c in self.constraints if isinstance(c, FunctionConstraint)]

    def target(self) -> Target:
        """The :class:`Target` this phrase names."""
        functions = self.functions()
        labels = list(self.labels)
        if not labels and self.kind in (GENERIC, VAGUE):
            for fn in functions:
                labels += [x for x in fn.labels if x not in labels]
        attributes = tuple(
            dict.fromkeys(
                c.value
                for c in self.constraints
                if isinstance(c, AttributeConstraint) and not c.negated and c.key != "part"
            )
        )
        return Target(
            layer=self.layer,
            labels=tuple(labels),
            noun=self.noun if self.kind not in (GENERIC, GENERIC_AREA, VAGUE, ONE) else "",
            function=functions[0].function if functions else None,
            attributes=attributes,
            plural=self.plural,
            quantity=self.quantity,
            # "the one on the left" alone: any object (a follow-up takes the previous kind);
            # a bare "the other one" stays empty until a conversation resolves it
            any=self.kind in (GENERIC, GENERIC_AREA, VAGUE)
            or (self.kind == ONE and bool(self.constraints))
            or (self.kind == ROOM and not labels),
            anaphor=self.kind == ANAPHOR,
        )

    def landmark(self) -> Landmark:
        """This phrase as the landmark of a relation."""
        return Landmark(target=self.target(), constraints=tuple(self.constraints))
