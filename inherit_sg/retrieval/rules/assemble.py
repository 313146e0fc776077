"""Turn a parsed :class:`Clause` into a :class:`ParsedQuery`: the target, the ordered and
numbered constraints, and the conversation reference."""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.retrieval.constraints import (
    Constraint,
    FunctionConstraint,
    LabelConstraint,
    Landmark,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
    Viewpoint,
)
from inherit_sg.retrieval.query import ParsedQuery, number_constraints
from inherit_sg.retrieval.rules.clause import Clause
from inherit_sg.retrieval.rules.cursor import weighted
from inherit_sg.retrieval.rules.functions import match_function
from inherit_sg.retrieval.rules.grammar import Grammar
from inherit_sg.retrieval.rules.phrase import (
    ANAPHOR,
    GENERIC,
    GENERIC_AREA,
    NP,
    OBJECT,
    ONE,
    ROOM,
    VAGUE,
)
from inherit_sg.vocab.lexicon import lexicon

NO_TARGET = "no object, place or function found in the request"
_NO_LABEL_KINDS = (GENERIC, GENERIC_AREA, VAGUE, ONE, ANAPHOR)
_PLACE_ORDER = {"room": 0, "area": 1, "floor": 2}


def _reference(clause: Clause, head: NP | None, refine: bool) -> str:
    if clause.exclude_previous:
        return "exclude_previous"
    if head is not None:
        if head.kind == ANAPHOR:
            return "previous"
        if head.other:
            return "other"
        if head.kind == ONE:
            return "refine"
    return "refine" if refine else "none"


def _head(clause: Clause, reference: str) -> NP | None:
    if clause.head is not None:
        return clause.head
    if clause.functions or clause.pending or clause.implied:
        return NP(kind=GENERIC)  # "where can I sit?", "what is on the table?"
    if clause.floor_np is not None and reference == "none" and not clause.places[1:]:
        return NP(kind="floor", labels=["floor"], words=clause.floor_np.words)
    if reference != "none" and clause.places:
        return NP(kind=ONE)  # "what about upstairs?"
    return None


def _dedupe(constraints: list[Constraint]) -> list[Constraint]:
    seen: set[str] = set()
    out = []
    for con in constraints:
        key = repr({k: v for k, v in con.to_dict().items() if k not in ("id", "weight", "text")})
        if key not in seen:
            seen.add(key)
            out.append(con)
    return out


# Landmarks that are surfaces of the building: what follows them places the target.
_SURFACES = frozenset({"floor", "wall", "ceiling", "ground"})


def _lift_surface_relations(constraints: list[Constraint]) -> list[Constraint]:
    """ "on the floor next to the bed", "on the wall above the desk": the second phrase
    places the target, not the floor or the wall it stands on or hangs from."""
    out: list[Constraint] = []
    for con in constraints:
        out.append(con)
        if not isinstance(con, RelationConstraint) or con.negated:
            continue
        labels = set(con.landmark.target.labels) or {con.landmark.target.noun}
        if not labels <= _SURFACES:
            continue
        lifted = [c for c in con.landmark.constraints if isinstance(c, RelationConstraint)]
        if lifted:
            rest = tuple(c for c in con.landmark.constraints if c not in lifted)
            out[-1] = replace(con, landmark=replace(con.landmark, constraints=rest))
            out += lifted
    return out


def _lift_proximity_superlatives(constraints: list[Constraint]) -> list[Constraint]:
    """ "the pillow on the couch closest to the tv": "closest to the tv" picks the pillow
    (people name the target's place, then single it out); with one couch the landmark
    reading would lose it, and with several the closest pillow sits on the closest couch
    anyway. Only when the target has no superlative of its own."""
    if any(isinstance(c, Superlative) for c in constraints):
        return constraints
    out: list[Constraint] = []
    lifted: list[Constraint] = []
    for con in constraints:
        if isinstance(con, RelationConstraint) and not con.negated and not lifted:
            picks = [
                c
                for c in con.landmark.constraints
                if isinstance(c, Superlative)
                and c.measure in ("closest", "farthest")
                and c.landmark is not None
                and not c.negated
            ]
            if picks:
                rest = tuple(c for c in con.landmark.constraints if c not in picks)
                con = replace(con, landmark=replace(con.landmark, constraints=rest))
                lifted.append(picks[0])
        out.append(con)
    return out + lifted


def _guess_function(words: list[str], notes: list[str]) -> list[FunctionConstraint]:
    """Purpose words anywhere in the request when the grammar found neither label nor
    function ("a workspace with noise reduction" → work); weighted as a hedge."""
    sense = match_function(None, words)
    if sense is None:
        return []
    notes.append(f"function {sense[0]!r} guessed from purpose words")
    return [
        FunctionConstraint(
            function=sense[0], labels=sense[1], weight=weighted("function", "hedge"), text=text
        )
        for text in [" ".join(words)]
    ]


# Weight of "near the thing the speaker stands at or sits on", given to the target
# ("sitting on the family room sofa, the cushion on the left"): a hint, weaker than a
# relation said of the target.
STANDPOINT_NEAR_WEIGHT = 0.4
# Words of a standpoint that leaves its place.
_LEAVING = frozenset({"out", "leave", "leaving", "exit", "exiting", "outside"})


def _owns_bare_positions(head: NP, standpoint: Landmark, notes: list[str]) -> bool:
    """Give a position said with no owner ("the cushion at the far left end", "the one
    on the side") the standpoint's thing as its owner ("when you sit on the sofa, …":
    the end of the sofa), in place; whether any was given one."""
    positions = lexicon().position_nouns
    given = False
    for k, con in enumerate(list(head.constraints)):
        if not isinstance(con, RelationConstraint) or con.negated:
            continue
        sides = [c for c in con.landmark.constraints if isinstance(c, Superlative)]
        if con.landmark.target.noun not in positions or len(sides) != len(con.landmark.constraints):
            continue
        head.constraints[k] = replace(
            con, predicate=positions[con.landmark.target.noun], landmark=standpoint,
            text=f"{con.text} of {standpoint.target.noun}",
        )  # fmt: skip
        head.constraints += sides  # "at the far left end": the leftmost one
        notes.append(f"'{con.text}' is of the standpoint ({standpoint.target.noun})")
        given = True
    return given


def _instrument(
    head: NP, own: list[Constraint], functions: list[FunctionConstraint], notes: list[str]
) -> list[Constraint]:
    """``own`` without the relation that names the thing a need is met with ("wash my
    hands in the sink", "check my outfit in the mirror": the sink, the mirror), which
    then names the target; unchanged when the target is named or no such relation is."""
    if head.kind not in (GENERIC, VAGUE) or head.labels or not functions:
        return own
    kinds = {label for f in functions for label in f.labels}
    for con in own:
        if not isinstance(con, RelationConstraint) or con.negated:
            continue
        named = [label for label in con.landmark.target.labels if label in kinds]
        if named and con.predicate in _INSTRUMENT_PREDICATES:
            head.kind, head.labels = OBJECT, named
            head.words = con.landmark.target.noun.split() or head.words
            notes.append(f"'{con.text}' names what the need is met with: the target")
            own = [c for c in own if c is not con] + list(con.landmark.constraints)
            return own
    return own


# Relations whose landmark may be what a need is met with ("in the sink", "on the towel");
# not "with" ("a place to read with some light": the light helps) nor "near" ("relax
# close to the armchair": somewhere by it).
_INSTRUMENT_PREDICATES = frozenset({"inside", "on"})


def _standpoint(clause: Clause) -> Viewpoint | None:
    """The request's viewpoint when it is a thing the speaker stands at or sits on; None
    for a room, or a place one leaves ("as you come out of the kitchen, …")."""
    view = clause.viewpoint
    if view is None or view.landmark.target.layer != "object" or not view.landmark.target.labels:
        return None
    return None if _LEAVING & set(view.text.split()) else view


def _near_standpoint(
    view: Viewpoint, clause: Clause, head: NP, notes: list[str]
) -> list[Constraint]:
    """ "near" the thing the speaker stands at or sits on (``view``: "from the family
    room sofa, the picture to your right", "standing at the sink, the towel on your
    left"), as a hint for a target the request places by nothing of its own: people point
    out what is around them. From a door, the room entered instead ("as you walk into
    the bathroom, …")."""
    if any(isinstance(c, RelationConstraint) and not c.negated for c in head.constraints):
        return []
    if any(c.kind == "room" for c in clause.places + head.places):
        return []
    if set(view.landmark.target.labels) & set(head.labels) or head.kind == ONE:
        return []  # "facing the desks, the third from the left": picked from them
    if any("door" in label for label in view.landmark.target.labels):
        # "as you walk into the guest bathroom, the towel on your left": seen from the
        # way in, not near it, but in the room entered
        rooms = [c for c in view.landmark.constraints if isinstance(c, RoomConstraint)]
        if rooms and not rooms[0].negated:
            notes.append(f"the room entered ({rooms[0].name}) is where to look")
            return [replace(rooms[0], weight=STANDPOINT_NEAR_WEIGHT)]
        return []
    noun = view.landmark.target.noun
    notes.append(f"the standpoint ({noun}) is near the target")
    return [
        RelationConstraint(
            predicate="near", landmark=view.landmark, weight=STANDPOINT_NEAR_WEIGHT,
            text=f"near {noun} (where the speaker is)",
        )
    ]  # fmt: skip


def _one_of_viewed(clause: Clause, notes: list[str]) -> None:
    """ "Facing the monitors, the one on the right": a bare "one" picks from the things
    the speaker faces when they are several of a kind; the head becomes that kind."""
    head, view = clause.head, clause.viewpoint
    if head is None or head.kind != ONE or head.labels or head.other or view is None:
        return
    seen = view.landmark.target
    if not (seen.plural and seen.labels and seen.noun):
        return
    head.kind, head.labels, head.words = OBJECT, list(seen.labels), seen.noun.split()
    notes.append(f"'the one' picks from the {seen.noun} of the viewpoint")


def _within(words: list[str], room: NP) -> bool:
    """Whether the request names the room after "in" / "inside" / "within", or says
    what is done "where" in it (where in it, not which room to go to: "where should I
    go in the kitchen", "a bathroom near the front door where I could wash my hands")."""
    first = room.words[0] if room.words else ""
    if room.room_type and first in words and "where" in words[words.index(first) + 1 :]:
        return True
    return any(
        a in ("in", "inside", "within") and (b == first or (b == "the" and c == first))
        for a, b, c in zip(words, words[1:], [*words[2:], ""], strict=False)
    )


def assemble(
    text: str, clause: Clause, refine: bool, notes: list[str], words: list[str]
) -> ParsedQuery:
    """Build the final :class:`ParsedQuery` for ``text`` (``words``: its tokens)."""
    _one_of_viewed(clause, notes)
    reference = _reference(clause, clause.head, refine)
    head = _head(clause, reference)
    if head is None and reference == "none" and not clause.places:
        clause.functions = list(_guess_function(words, notes))
        head = NP(kind=GENERIC) if clause.functions else None
    if head is None:
        return ParsedQuery(
            text=text,
            reference=reference,
            no_target_reason=None if reference != "none" else NO_TARGET,
            notes=tuple(notes),
            viewpoint=clause.viewpoint,
        )
    view = _standpoint(clause)
    standpoint: list[Constraint] = []
    if view is not None and not _owns_bare_positions(head, view.landmark, notes):
        standpoint = _near_standpoint(view, clause, head, notes)
    own = clause.pending + head.constraints
    named = clause.functions + own + clause.implied
    functions = [c for c in named if isinstance(c, FunctionConstraint)]
    functions = list({f.function: f for f in reversed(functions)}.values())[::-1]
    described = any(isinstance(c, RelationConstraint) and not c.negated for c in own)
    if not functions and not head.labels and head.kind in (GENERIC, GENERIC_AREA, VAGUE):
        # "the little yellow thing on the desk" is described, not asked for by purpose
        # the head's own word names no purpose ("the closest thing to the door" is no
        # "thing" to store)
        said = [w for w in words if w not in head.words]
        functions = [] if described else list(_guess_function(said, notes))
    elif not functions and head.kind == OBJECT and not head.known and head.words:
        # an unknown head that is a purpose noun: "I want a long soak" seeks a bathtub
        functions = list(_guess_function(head.words[-1:], notes))
        if functions and clause.fetched:
            notes.append(f"{head.noun!r} is fetched: the thing itself is sought")
        elif functions:
            head.kind, head.labels = GENERIC, []
            own = [c for c in own if c.kind != "attribute"]
    if head.kind == ROOM and functions and _within(words, head):
        # "I'd like to wash my hands — where should I go in the kitchen?": a thing in it
        notes.append(f"{head.noun!r} is where; the need is met by a thing in it")
        clause.places.append(Grammar.room_place(head))
        head = NP(kind=GENERIC)
    own = _instrument(head, own, functions, notes)
    head.constraints = functions + [c for c in own if not isinstance(c, FunctionConstraint)]
    target = head.target()
    if head.kind == ONE and functions:
        target = Target(layer=target.layer, any=True, function=functions[0].function)
    constraints: list[Constraint] = []
    if target.labels and head.kind not in _NO_LABEL_KINDS:
        constraints.append(LabelConstraint(labels=target.labels, noun=head.noun, text=head.noun))
    constraints += functions
    constraints += _dedupe([c for c in own if c.kind == "attribute"])
    constraints += _lift_proximity_superlatives(
        _lift_surface_relations([c for c in own if c.kind not in ("attribute", "function")])
    )
    constraints += clause.excluded_labels
    constraints += [c for c in standpoint if c.kind != "room"]
    places = [*clause.places, *head.places, *(c for c in standpoint if c.kind == "room")]
    places = sorted(places, key=lambda c: _PLACE_ORDER[c.kind])
    constraints += _dedupe(places)
    if target.is_empty and head.kind not in (ONE,) and not constraints:
        return ParsedQuery(text=text, reference=reference, no_target_reason=NO_TARGET,
                           notes=tuple(notes))  # fmt: skip
    return ParsedQuery(
        text=text,
        target=target,
        constraints=number_constraints(tuple(constraints)),
        reference=reference,
        notes=tuple(notes),
        viewpoint=clause.viewpoint,
    )
