"""Turn a parsed :class:`Clause` into a :class:`ParsedQuery`: the target, the ordered and
numbered constraints, and the conversation reference."""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.retrieval.constraints import (
    Constraint,
    FunctionConstraint,
    LabelConstraint,
    RelationConstraint,
    Superlative,
    Target,
)
from inherit_sg.retrieval.query import ParsedQuery, number_constraints
from inherit_sg.retrieval.rules.clause import Clause
from inherit_sg.retrieval.rules.cursor import weighted
from inherit_sg.retrieval.rules.functions import match_function
from inherit_sg.retrieval.rules.phrase import (
    ANAPHOR,
    GENERIC,
    GENERIC_AREA,
    NP,
    OBJECT,
    ONE,
    VAGUE,
)

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
    places = sorted(clause.places + head.places, key=lambda c: _PLACE_ORDER[c.kind])
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
