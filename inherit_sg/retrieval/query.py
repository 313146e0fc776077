"""A parsed request (:class:`ParsedQuery`) and helpers over its constraint tree:
numbering, walking, mapping and one-line descriptions."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace
from typing import Any

from inherit_sg.retrieval.constraints import (
    PARSERS,
    REFERENCES,
    AreaConstraint,
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    FunctionConstraint,
    LabelConstraint,
    Landmark,
    PlacementConstraint,
    RelationConstraint,
    RoomConstraint,
    Target,
    Viewpoint,
    check,
    constraint_from_dict,
    str_tuple,
)


def number_constraints(
    constraints: tuple[Constraint, ...], prefix: str = "c", start: int = 1
) -> tuple[Constraint, ...]:
    """Give constraints ids ``c1``, ``c2``, …; a relation's landmark constraints are
    numbered below it (``c2.1``, ``c2.2``, continuing through ``landmark2``)."""
    out: list[Constraint] = []
    for i, con in enumerate(constraints, start=start):
        cid = f"{prefix}{i}"
        changes: dict[str, Any] = {"id": cid}
        nxt = 1
        for name in ("landmark", "landmark2"):
            lm = getattr(con, name, None)
            if lm is not None:
                nested = number_constraints(lm.constraints, f"{cid}.", nxt)
                nxt += len(nested)
                changes[name] = replace(lm, constraints=nested)
        out.append(replace(con, **changes))
    return tuple(out)


def map_constraints(
    constraints: tuple[Constraint, ...], fn: Callable[[Constraint], Constraint]
) -> tuple[Constraint, ...]:
    """Apply ``fn`` to every constraint, landmarks' nested ones included (bottom-up)."""
    out: list[Constraint] = []
    for con in constraints:
        changes: dict[str, Any] = {}
        for name in ("landmark", "landmark2"):
            lm = getattr(con, name, None)
            if lm is not None:
                changes[name] = replace(lm, constraints=map_constraints(lm.constraints, fn))
        out.append(fn(replace(con, **changes) if changes else con))
    return tuple(out)


def _walk(constraints: tuple[Constraint, ...], depth: int) -> Iterator[tuple[Constraint, int]]:
    for con in constraints:
        yield con, depth
        for name in ("landmark", "landmark2"):
            lm = getattr(con, name, None)
            if lm is not None:
                yield from _walk(lm.constraints, depth + 1)


def _landmark_text(lm: Landmark | None) -> str:
    return lm.target.describe() if lm is not None else "you"


def _body(con: Constraint) -> str:
    if isinstance(con, LabelConstraint):
        return " / ".join(con.labels)
    if isinstance(con, FunctionConstraint):
        return f"{con.function} (e.g. {', '.join(con.labels) or '?'})"
    if isinstance(con, AttributeConstraint):
        return f"{con.key} = {con.value}"
    if isinstance(con, RelationConstraint):
        second = f" and {_landmark_text(con.landmark2)}" if con.landmark2 is not None else ""
        return f"{con.predicate} → {_landmark_text(con.landmark)}{second}"
    if isinstance(con, RoomConstraint):
        return f"{con.type or '?'} ({con.name})"
    if isinstance(con, AreaConstraint):
        return con.label
    if isinstance(con, FloorConstraint):
        return str(con.level) if con.level is not None else str(con.relative)
    if isinstance(con, PlacementConstraint):
        return {"wall": "against a wall", "corner": "in a corner"}.get(con.where, "in the centre")
    if con.measure == "middle":
        return "the middle one" + (f" from the {con.direction}" if con.direction else "")
    if con.ordinal is not None:
        side = f" from the {con.direction}" if con.direction else ""
        return f"#{con.ordinal}{side}"
    if con.measure in ("closest", "farthest"):
        return f"{con.measure} to {_landmark_text(con.landmark)}"
    if con.measure in ("most", "fewest") and con.landmark is not None:
        return f"{con.measure} {_landmark_text(con.landmark)}"
    return con.measure


def describe(con: Constraint) -> str:
    """One line for traces and the CLI, e.g. ``NOT relation next_to → window``."""
    return f"{'NOT ' if con.negated else ''}{con.kind} {_body(con)}"


@dataclass(frozen=True, kw_only=True)
class ParsedQuery:
    """A request parsed into a target and weighted, polarised constraints.

    ``reference`` says how a follow-up relates to the conversation (``REFERENCES``):
    ``previous`` ("it", "that one"), ``other`` ("the other one"), ``exclude_previous``
    ("not that one, …") or ``refine`` ("the red one", "what about upstairs?").
    ``no_target_reason`` is set for requests with nothing to find ("how does this space
    encourage socialising?"). ``exclude_ids`` are node ids ruled out by the conversation.
    ``viewpoint`` is where the speaker stands and looks when the request says so ("facing
    the windows, the one on the left").
    """

    text: str
    target: Target = field(default_factory=Target)
    constraints: tuple[Constraint, ...] = ()
    reference: str = "none"
    exclude_ids: tuple[str, ...] = ()
    no_target_reason: str | None = None
    parser: str = "rules"
    notes: tuple[str, ...] = ()
    viewpoint: Viewpoint | None = None

    def __post_init__(self) -> None:
        check(self.reference in REFERENCES, f"reference {self.reference!r} not in {REFERENCES}")
        check(self.parser in PARSERS, f"parser {self.parser!r} not in {PARSERS}")

    @property
    def has_target(self) -> bool:
        """True when the request seeks a node (False for 'global' requests)."""
        return self.no_target_reason is None and not self.target.is_empty

    def of_kind(self, kind: str) -> list[Constraint]:
        """Top-level constraints of one kind, in order."""
        return [c for c in self.constraints if c.kind == kind]

    @property
    def floor(self) -> Constraint | None:
        """The floor constraint (the hard filter), if any."""
        found = self.of_kind("floor")
        return found[0] if found else None

    def walk(self) -> Iterator[tuple[Constraint, int]]:
        """Every constraint with its nesting depth (landmarks' constraints included)."""
        yield from _walk(self.constraints, 0)

    def find(self, cid: str) -> Constraint | None:
        """The constraint with id ``cid`` at any depth."""
        return next((c for c, _ in self.walk() if c.id == cid), None)

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form (the ``constraints`` part of a query result)."""
        return {
            "text": self.text,
            "target": self.target.to_dict(),
            "constraints": [c.to_dict() for c in self.constraints],
            "reference": self.reference,
            "exclude_ids": list(self.exclude_ids),
            "no_target_reason": self.no_target_reason,
            "parser": self.parser,
            "notes": list(self.notes),
            "viewpoint": self.viewpoint.to_dict() if self.viewpoint is not None else None,
        }

    def to_json(self, indent: int | None = None) -> str:
        """:meth:`to_dict` as a JSON string."""
        return json.dumps(self.to_dict(), indent=indent)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ParsedQuery:
        """Inverse of :meth:`to_dict`; raises :class:`InputError` naming the bad field."""
        check(isinstance(data, dict), "parsed query must be an object")
        check(isinstance(data.get("text"), str), "parsed query needs 'text' (a string)")
        return cls(
            text=data["text"],
            target=Target.from_dict(data.get("target", {})),
            constraints=tuple(constraint_from_dict(c) for c in data.get("constraints", [])),
            reference=str(data.get("reference", "none")),
            exclude_ids=str_tuple(data.get("exclude_ids", []), "exclude_ids"),
            no_target_reason=data.get("no_target_reason"),
            parser=str(data.get("parser", "rules")),
            notes=str_tuple(data.get("notes", []), "notes"),
            viewpoint=(
                Viewpoint.from_dict(data["viewpoint"])
                if data.get("viewpoint") is not None
                else None
            ),
        )
