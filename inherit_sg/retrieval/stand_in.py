"""Where a thing is said to be, when the map has no such thing.

"Could you leave my glasses on one of the nightstands?", "the remote's on the telly
cabinet, grab it", "my scarf's on the bedpost": the thing named is carried, small or
simply not mapped, and the place the request puts it on, in or by is where the robot
goes. When the map holds nothing of the target's kind (its label term stays below
:data:`ABSENT_LABEL` for every candidate) and the map has the place (its best
candidate's label term reaches :data:`PLACE_LABEL`), the answer is that place, and the
trace says so. Only support and containment place a thing so ("on", "in"): "the post
next to the bed" describes a thing by what stands near it, which may be mapped under
another name.
"""

from __future__ import annotations

from collections.abc import Sequence

from inherit_sg.retrieval.constraints import LabelConstraint, RelationConstraint
from inherit_sg.retrieval.plan import NodeSpec
from inherit_sg.retrieval.scoring import STRONG_MATCH, Scored

# The best candidate's label term below this: nothing in the map is of the kind asked for
# (the place must then be mapped well, which keeps "the plant on the dining table" on a
# plant pot when the map has no dining table).
ABSENT_LABEL = STRONG_MATCH
# The place's best candidate must match its words at least this well.
PLACE_LABEL = STRONG_MATCH
# Relations that put a thing somewhere, most telling first.
PLACING = ("on", "inside")
# Nearness places a thing only when nothing in the map resembles it at all (its best
# label term below NOTHING_LIKE): "find my phone down the side of the sofa".
NEARNESS = ("next_to", "near")
NOTHING_LIKE = 0.2
# Parts of the building are no place to go to for a thing ("it sits on the floor").
_STRUCTURE = frozenset({"floor", "wall", "ceiling", "ground", "carpet"})


def _placing(spec: NodeSpec, kinds: tuple[str, ...]) -> list[RelationConstraint]:
    """The wanted relations of ``spec`` whose predicate is one of ``kinds``."""
    return [
        c
        for c in spec.scored()
        if isinstance(c, RelationConstraint) and not c.negated and c.predicate in kinds
    ]


def _best_label(spec: NodeSpec, ranked: Sequence[Scored]) -> float | None:
    """The best label term among ``ranked`` (None when ``spec`` names no kind)."""
    label = next(
        (c for c in spec.scored() if isinstance(c, LabelConstraint) and not c.negated), None
    )
    if label is None or spec.target.function:
        return None
    return max((c.terms[label.id].sim for c in ranked if label.id in c.terms), default=0.0)


def absent(spec: NodeSpec, ranked: Sequence[Scored]) -> float | None:
    """How well the best candidate matches the kind ``spec`` names, when the map holds
    nothing of it (below :data:`ABSENT_LABEL`); None when it does or names no kind. A
    request for whatever is in or on a thing ("what's in that box under the mirror?")
    counts as absent when no candidate is really in or on it (the contents are not
    mapped; the box is where to go)."""
    if not spec.target.labels and not spec.target.function:
        placed = [c.id for c in _placing(spec, PLACING)]
        held = max((c.terms[i].sim for c in ranked for i in placed if i in c.terms), default=0.0)
        return 1.0 if placed and held < ABSENT_LABEL else None
    best = _best_label(spec, ranked)
    return best if best is not None and best < ABSENT_LABEL else None


def place_found(place: NodeSpec, ranked: Sequence[Scored]) -> bool:
    """Whether the map has the place a request puts its thing on or in: its best
    candidate matches the place's words well."""
    best = _best_label(place, ranked)
    return best is not None and best >= PLACE_LABEL


def said_place(spec: NodeSpec, likeness: float) -> NodeSpec | None:
    """The landmark spec of the relation that says where the target is ("on one of the
    nightstands"), or None when the request places it nowhere; ``likeness`` is how well
    the map's best candidate matches the target's kind (see :data:`NEARNESS`)."""
    kinds = PLACING + (NEARNESS if likeness < NOTHING_LIKE else ())
    placed = [
        c
        for c in _placing(spec, kinds)
        if c.id in spec.landmarks
        and c.landmark.target.noun not in _STRUCTURE
        and not set(c.landmark.target.labels) & _STRUCTURE
    ]
    if not placed:
        return None
    best = min(placed, key=lambda c: kinds.index(c.predicate))
    return spec.landmarks[best.id]
