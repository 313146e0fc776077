"""The structured, JSON-serialisable form of a ground-truth request.

An :class:`ObjectSpec` describes the objects a request asks for: a label set (any of),
an optional function, attribute constraints, a room, an area, a floor (each possibly
negated), relations to landmarks (each landmark is itself an :class:`ObjectSpec`, so
constraints chain) and an optional superlative applied last, among the objects that pass
everything else. ``truth.evaluate`` turns a spec into the ids of every matching object.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field, replace
from typing import Any

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.synthetic.truth_predicates import (
    BINARY_PREDICATES,
    RELATIVE_FLOORS,
    SUPERLATIVES,
)

RELATIONS = (*BINARY_PREDICATES, "between")


@dataclass
class AttributeConstraint:
    """``attributes[key] == value`` (or ``!=`` when negated), e.g. colour red."""

    key: str
    value: str
    negated: bool = False


@dataclass
class RoomConstraint:
    """In a room of ``type`` and/or with ``name`` (or not, when negated)."""

    type: str | None = None
    name: str | None = None
    negated: bool = False


@dataclass
class AreaConstraint:
    """In a functional area with ``label`` ("reading corner"), or not when negated."""

    label: str
    negated: bool = False


@dataclass
class FloorConstraint:
    """On floor ``level`` or on the floors a relative word names ("upstairs")."""

    level: int | None = None
    relative: str | None = None
    negated: bool = False


@dataclass
class RelationConstraint:
    """``predicate(target, landmark)`` holds for some landmark (none, when negated).

    ``between`` needs ``landmark2``: the target lies between one object of each spec.
    """

    predicate: str
    landmark: ObjectSpec
    landmark2: ObjectSpec | None = None
    negated: bool = False


@dataclass
class ObjectSpec:
    """What a request asks for; ``noun`` is the word the request used (not evaluated)."""

    labels: list[str] = field(default_factory=list)
    noun: str = ""
    function: str | None = None
    attributes: list[AttributeConstraint] = field(default_factory=list)
    room: RoomConstraint | None = None
    area: AreaConstraint | None = None
    floor: FloorConstraint | None = None
    relations: list[RelationConstraint] = field(default_factory=list)
    superlative: str | None = None
    exclude_ids: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """Compact JSON-able form (empty parts left out)."""
        out: dict[str, Any] = {"labels": sorted(self.labels)}
        if self.noun:
            out["noun"] = self.noun
        if self.function:
            out["function"] = self.function
        if self.attributes:
            out["attributes"] = [_plain(vars(a)) for a in self.attributes]
        for name in ("room", "area", "floor"):
            part = getattr(self, name)
            if part is not None:
                out[name] = _plain(vars(part))
        if self.relations:
            out["relations"] = [_relation_dict(r) for r in self.relations]
        if self.superlative:
            out["superlative"] = self.superlative
        if self.exclude_ids:
            out["exclude_ids"] = sorted(self.exclude_ids)
        return out

    def key(self) -> str:
        """Canonical text of what the spec means (``noun`` left out), for deduplication."""
        data = self.to_dict()
        _drop_nouns(data)
        return json.dumps(data, sort_keys=True)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ObjectSpec:
        """Inverse of :meth:`to_dict`; raises :class:`DatasetError` naming the bad field."""
        try:
            return _spec_from_dict(data)
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise DatasetError(f"malformed gt_constraints: {exc}") from None

    def positive(self) -> ObjectSpec:
        """A copy without this level's negated constraints (landmarks are kept as they are)."""
        return replace(
            self,
            attributes=[a for a in self.attributes if not a.negated],
            room=None if self.room is not None and self.room.negated else self.room,
            area=None if self.area is not None and self.area.negated else self.area,
            floor=None if self.floor is not None and self.floor.negated else self.floor,
            relations=[r for r in self.relations if not r.negated],
        )

    def negation_count(self) -> int:
        """How many constraints at this level are negated."""
        parts = [self.room, self.area, self.floor, *self.attributes, *self.relations]
        return sum(1 for p in parts if p is not None and p.negated)


def _plain(values: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in values.items() if v is not None and v is not False}


def _relation_dict(rel: RelationConstraint) -> dict[str, Any]:
    out: dict[str, Any] = {"predicate": rel.predicate, "landmark": rel.landmark.to_dict()}
    if rel.landmark2 is not None:
        out["landmark2"] = rel.landmark2.to_dict()
    if rel.negated:
        out["negated"] = True
    return out


def _drop_nouns(data: dict[str, Any]) -> None:
    data.pop("noun", None)
    for rel in data.get("relations", []):
        _drop_nouns(rel["landmark"])
        if "landmark2" in rel:
            _drop_nouns(rel["landmark2"])


def _spec_from_dict(data: dict[str, Any]) -> ObjectSpec:
    superlative = data.get("superlative")
    if superlative is not None and superlative not in SUPERLATIVES:
        raise ValueError(f"superlative {superlative!r} is not one of {SUPERLATIVES}")
    room = data.get("room")
    area = data.get("area")
    floor = data.get("floor")
    return ObjectSpec(
        labels=[str(x) for x in data.get("labels", [])],
        noun=str(data.get("noun", "")),
        function=data.get("function"),
        attributes=[AttributeConstraint(**a) for a in data.get("attributes", [])],
        room=RoomConstraint(**room) if room is not None else None,
        area=AreaConstraint(**area) if area is not None else None,
        floor=_floor_from_dict(floor) if floor is not None else None,
        relations=[_relation_from_dict(r) for r in data.get("relations", [])],
        superlative=superlative,
        exclude_ids=[str(x) for x in data.get("exclude_ids", [])],
    )


def _floor_from_dict(data: dict[str, Any]) -> FloorConstraint:
    floor = FloorConstraint(**data)
    if floor.relative is not None and floor.relative not in RELATIVE_FLOORS:
        raise ValueError(f"floor.relative {floor.relative!r} is not one of {RELATIVE_FLOORS}")
    if floor.relative is None and floor.level is None:
        raise ValueError("floor needs 'level' or 'relative'")
    return floor


def _relation_from_dict(data: dict[str, Any]) -> RelationConstraint:
    predicate = data["predicate"]
    if predicate not in RELATIONS:
        raise ValueError(f"relation predicate {predicate!r} is not one of {RELATIONS}")
    second = data.get("landmark2")
    if (predicate == "between") != (second is not None):
        raise ValueError("relation 'between' needs 'landmark2' (and only it)")
    return RelationConstraint(
        predicate=predicate,
        landmark=_spec_from_dict(data["landmark"]),
        landmark2=_spec_from_dict(second) if second is not None else None,
        negated=bool(data.get("negated", False)),
    )
