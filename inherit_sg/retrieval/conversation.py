"""Conversation history: resolve follow-up requests against earlier turns.

A :class:`Conversation` keeps a stack of turns (the resolved request, the answer node id
and the candidate ids). :meth:`Conversation.resolve` rewrites a follow-up:

- ``previous`` ("take me to it", "that one"): the previous target, pinned to the
  previous answer's node id;
- ``other`` ("the other one", "another chair"): the previous request again, excluding
  every answer given so far for it;
- ``exclude_previous`` ("not that one, the one in the bedroom"): the previous request
  with the new constraints merged in, excluding the previous answer;
- ``refine`` ("the red one", "what about upstairs?"): the previous request with the new
  constraints merged in.

Merging replaces a previous constraint of the same slot (the label, a function, an
attribute key, the room/area, the floor, the superlative) and appends relations.
Landmarks that are anaphors ("what is next to it?") are pinned to the previous answer.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    Constraint,
    LabelConstraint,
    Landmark,
    RelationConstraint,
    Superlative,
    Target,
)
from inherit_sg.retrieval.query import ParsedQuery, map_constraints, number_constraints


@dataclass(frozen=True)
class Turn:
    """One answered request."""

    query: ParsedQuery
    answer_id: str | None = None
    candidate_ids: tuple[str, ...] = ()


def _slot(con: Constraint) -> str | None:
    """Constraints sharing a slot replace one another; None: always appended."""
    if isinstance(con, AttributeConstraint):
        return f"attribute:{con.key}"
    if con.kind in ("room", "area"):
        return "place"
    if con.kind == "relation":
        return None
    return con.kind


def merge_constraints(
    old: tuple[Constraint, ...], new: tuple[Constraint, ...]
) -> tuple[Constraint, ...]:
    """``old`` with ``new`` merged in (same slot replaces; relations are appended)."""
    replaced = {s for s in (_slot(c) for c in new) if s is not None}
    kept = [c for c in old if _slot(c) not in replaced]
    order = {"label": 0, "function": 1, "attribute": 2, "room": 4, "area": 4, "floor": 5}
    merged = sorted([*kept, *new], key=lambda c: order.get(c.kind, 3))
    return number_constraints(tuple(merged))


class Conversation:
    """History stack of turns, newest last."""

    def __init__(self, max_turns: int = 50) -> None:
        self.max_turns = max_turns
        self.turns: list[Turn] = []

    @property
    def last(self) -> Turn | None:
        """The most recent turn, if any."""
        return self.turns[-1] if self.turns else None

    def add_turn(
        self, query: ParsedQuery, answer_id: str | None, candidate_ids: tuple[str, ...] = ()
    ) -> None:
        """Push an answered (resolved) request onto the history."""
        self.turns.append(Turn(query, answer_id, tuple(candidate_ids)))
        del self.turns[: -self.max_turns]

    def clear(self) -> None:
        """Forget the history."""
        self.turns.clear()

    def resolve(self, parsed: ParsedQuery) -> ParsedQuery:
        """Rewrite ``parsed`` using the history (unchanged when it needs none)."""
        last = self.last
        if last is None:
            if parsed.reference == "none":
                return parsed
            return replace(parsed, notes=(*parsed.notes, "no earlier turn to refer to"))
        constraints = self._pin_landmarks(parsed.constraints, last)
        parsed = replace(parsed, constraints=constraints)
        if parsed.reference == "none":
            return parsed
        prev = last.query
        note = f"resolved '{parsed.reference}' against: {prev.text!r}"
        answer = (last.answer_id,) if last.answer_id else ()
        if parsed.reference == "previous":
            target = replace(prev.target, anaphor=False, node_ids=answer)
            merged = merge_constraints(prev.constraints, parsed.constraints)
            return self._build(parsed, target, merged, prev.exclude_ids, note)
        merged = merge_constraints(prev.constraints, parsed.constraints)
        target = self._target(prev.target, parsed.target, merged)
        excluded = prev.exclude_ids
        if parsed.reference in ("other", "exclude_previous"):
            excluded = tuple(dict.fromkeys((*prev.exclude_ids, *answer)))
        return self._build(parsed, target, merged, excluded, note)

    @staticmethod
    def _build(
        parsed: ParsedQuery,
        target: Target,
        constraints: tuple[Constraint, ...],
        excluded: tuple[str, ...],
        note: str,
    ) -> ParsedQuery:
        return replace(
            parsed,
            target=target,
            constraints=constraints,
            exclude_ids=tuple(dict.fromkeys((*excluded, *parsed.exclude_ids))),
            no_target_reason=None,
            notes=(*parsed.notes, note),
        )

    @staticmethod
    def _target(prev: Target, new: Target, merged: tuple[Constraint, ...]) -> Target:
        labels = next((c.labels for c in merged if isinstance(c, LabelConstraint)), prev.labels)
        attributes = tuple(
            c.value for c in merged if isinstance(c, AttributeConstraint) and not c.negated
        )
        return replace(
            new if new.labels else prev,
            labels=labels,
            function=new.function or prev.function,
            attributes=attributes,
            anaphor=False,
            node_ids=(),
        )

    @staticmethod
    def _pin_landmarks(constraints: tuple[Constraint, ...], last: Turn) -> tuple[Constraint, ...]:
        """Point anaphor landmarks ("next to it") at the previous answer."""
        pinned = replace(
            last.query.target,
            anaphor=False,
            node_ids=(last.answer_id,) if last.answer_id else (),
        )

        def _pin(lm: Landmark | None) -> Landmark | None:
            if lm is None or not lm.target.anaphor:
                return lm
            return replace(lm, target=pinned)

        def _fix(con: Constraint) -> Constraint:
            if isinstance(con, RelationConstraint):
                landmark = _pin(con.landmark)
                assert landmark is not None
                return replace(con, landmark=landmark, landmark2=_pin(con.landmark2))
            if isinstance(con, Superlative):
                return replace(con, landmark=_pin(con.landmark))
            return con

        return map_constraints(constraints, _fix)
