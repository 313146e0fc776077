"""Structured constraints a natural-language request is parsed into.

A parsed request (:class:`inherit_sg.retrieval.query.ParsedQuery`) names what is sought
(a :class:`Target`) and an ordered list of constraints, each with an id (``c1``, ``c2``, …; a landmark's own constraints are
numbered below their relation: ``c3.1``), a polarity (+1, or -1 when negated) and an
importance weight. The retrieval score is ``S(n) = H_floor · Σ p_i · w_i · Sim(n, c_i)``:
floor constraints are the hard filter ``H_floor``, every other constraint one term.

Canonical relation predicates (``PREDICATES``), read as ``predicate(target, landmark)``:

- ``on`` (on, on top of, upon) · ``supports`` (the landmark is on the target: "the table
  with a vase on it") · ``above`` (above, over) · ``under`` (under, below, beneath)
- ``next_to`` (next to, beside, by, alongside) · ``near`` (near, close to, around; "far
  from" / "away from" are ``near`` negated) · ``between`` (needs ``landmark2``)
- ``inside`` (in / inside / within an object: "the book in the cabinet") · ``contains``
  ("the room with a bed", "the box with a cable in it")
- ``with`` (bare "with": the landmark is on, in or next to the target)
- ``facing`` (facing, opposite, across from) · ``in_front_of`` · ``behind`` ·
  ``left_of`` · ``right_of`` (as the viewer sees them: see :class:`Viewpoint`)

"in the kitchen" is a :class:`RoomConstraint`, "in the reading corner" an
:class:`AreaConstraint`, "on the second floor" a :class:`FloorConstraint`; "closest to the
door", "the largest", "the third from the left" and "the middle one" are a
:class:`Superlative`; "against the wall", "in the corner" and "in the centre of the room"
a :class:`PlacementConstraint`. A part ("the bin with the yellow lid", "the chair with
wheels") is an :class:`AttributeConstraint` with key ``part``.

Floors use the US convention shared with the synthetic ground truth: "ground floor" =
"first floor" = level 0 (the lowest), "second floor" = 1, "floor 2" = 1; relative words
are ``upstairs`` (every floor above the lowest), ``downstairs`` (the lowest), ``top``
(the highest) and ``bottom`` (basement / lowest floor).

Intent weighting (``DEFAULT_WEIGHTS``): target label 1.0, function 0.9, relation 0.8,
superlative 0.8, room 0.7, area 0.6, attribute 0.6, placement 0.6; the floor is the separate hard filter
(weight 1.0, not summed). Negated constraints keep their weight and get polarity -1.
Emphasis words ("must", "definitely", "only") raise the next constraint's weight by
``EMPHASIS_BOOST`` (capped at 1.0); hedges ("maybe", "preferably") halve it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any, ClassVar, Union

from inherit_sg.errors import InputError

LAYERS = ("object", "area", "room", "floor")
PREDICATES = (
    "on",
    "supports",
    "above",
    "under",
    "next_to",
    "near",
    "between",
    "inside",
    "contains",
    "with",
    "facing",
    "in_front_of",
    "behind",
    "left_of",
    "right_of",
)
MEASURES = (
    "largest",
    "smallest",
    "tallest",
    "shortest",
    "highest",
    "lowest",
    "widest",
    "narrowest",
    "closest",
    "farthest",
    "ordinal",
    "middle",
    "most",
    "fewest",
)
# Directions an ordinal counts from, as the viewer sees them ("the second from the left";
# "front" = nearest the viewer first, "back" = farthest first).
DIRECTIONS = ("left", "right", "front", "back")
# Where in its room an object stands ("against the wall", "in the corner", "in the middle
# of the room").
PLACEMENTS = ("wall", "corner", "centre")
# How a request sets the viewer: "facing the windows", "from the door" / "as you enter
# through the door", "with your back to the TV".
VIEWPOINT_KINDS = ("facing", "from", "back_to", "seated")
RELATIVE_FLOORS = ("upstairs", "downstairs", "top", "bottom")
ATTRIBUTE_KEYS = ("colour", "material", "size", "height", "shape", "state", "part", "other")
REFERENCES = ("none", "previous", "other", "exclude_previous", "refine")
PARSERS = ("rules", "llm")

DEFAULT_WEIGHTS: dict[str, float] = {
    "label": 1.0,
    "function": 0.9,
    "relation": 0.8,
    "superlative": 0.8,
    "room": 0.7,
    "area": 0.6,
    "attribute": 0.6,
    "placement": 0.6,
    "floor": 1.0,
}
EMPHASIS_BOOST = 0.3
HEDGE_FACTOR = 0.5


def check(ok: bool, message: str) -> None:
    """Raise :class:`InputError` with ``message`` unless ``ok``."""
    if not ok:
        raise InputError(message)


def str_tuple(value: Any, name: str) -> tuple[str, ...]:
    """``value`` (a list) as a tuple of strings; :class:`InputError` naming ``name`` else."""
    check(isinstance(value, list | tuple), f"constraint field {name!r} must be a list")
    return tuple(str(v) for v in value)


@dataclass(frozen=True, kw_only=True)
class Target:
    """What is sought: a layer, canonical labels (any of), an optional function.

    ``noun`` is the phrase as written ("recliner sofa"); ``attributes`` the positive
    attribute values ("red", "wood"), repeated from the attribute constraints for display
    and text matching. ``any`` marks "something" / "a place"; ``anaphor`` marks "it" /
    "that one" (resolved by the conversation into ``node_ids``).
    """

    layer: str = "object"
    labels: tuple[str, ...] = ()
    noun: str = ""
    function: str | None = None
    attributes: tuple[str, ...] = ()
    plural: bool = False
    quantity: int | None = None
    any: bool = False
    anaphor: bool = False
    node_ids: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        check(self.layer in LAYERS, f"target layer {self.layer!r} is not one of {LAYERS}")

    @property
    def is_empty(self) -> bool:
        """True when nothing is named: no label, function, node id, 'any' or anaphor."""
        return not (self.labels or self.function or self.node_ids or self.any or self.anaphor)

    def describe(self) -> str:
        """Short human-readable phrase, e.g. ``red chair (sit)``."""
        head = self.noun or " / ".join(self.labels) or ("it" if self.anaphor else "")
        words = [a for a in self.attributes if a not in head.split()]
        text = " ".join([*words, head or ("something" if self.any else self.layer)])
        if self.function:
            text += f" (to {self.function})"
        if self.node_ids:
            text += " = " + ", ".join(self.node_ids)
        return text

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        out = {f.name: getattr(self, f.name) for f in fields(self)}
        for key in ("labels", "attributes", "node_ids"):
            out[key] = list(out[key])
        return out

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Target:
        """Inverse of :meth:`to_dict`; raises :class:`InputError` naming the bad field."""
        check(isinstance(data, dict), "target must be an object")
        kwargs: dict[str, Any] = {}
        for f in fields(cls):
            if f.name in data:
                value = data[f.name]
                if f.name in ("labels", "attributes", "node_ids"):
                    value = str_tuple(value, f"target.{f.name}")
                kwargs[f.name] = value
        return cls(**kwargs)


@dataclass(frozen=True, kw_only=True)
class _Constraint:
    id: str = ""
    negated: bool = False
    weight: float = 1.0
    text: str = ""
    kind: ClassVar[str] = ""

    def __post_init__(self) -> None:
        check(
            isinstance(self.weight, int | float) and 0.0 <= self.weight <= 1.0,
            f"constraint {self.id or self.kind!r}: weight {self.weight!r} is not in [0, 1]",
        )

    @property
    def polarity(self) -> int:
        """+1 for a constraint that must hold, -1 for a negated (penalising) one."""
        return -1 if self.negated else 1

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form with ``kind`` and ``polarity``."""
        out: dict[str, Any] = {"id": self.id, "kind": self.kind, "polarity": self.polarity}
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, Landmark):
                value = value.to_dict()
            elif isinstance(value, tuple):
                value = list(value)
            out[f.name] = value
        return out


@dataclass(frozen=True, kw_only=True)
class LabelConstraint(_Constraint):
    """The node's label is one of ``labels`` (negated: "a seat, but not a stool")."""

    kind: ClassVar[str] = "label"
    labels: tuple[str, ...] = ()
    noun: str = ""


@dataclass(frozen=True, kw_only=True)
class FunctionConstraint(_Constraint):
    """The node serves ``function`` ("sit", "wash hands"); ``labels`` are likely kinds."""

    kind: ClassVar[str] = "function"
    function: str = ""
    labels: tuple[str, ...] = ()


@dataclass(frozen=True, kw_only=True)
class AttributeConstraint(_Constraint):
    """A colour, material, size, height, shape, state or other adjective (``key``)."""

    kind: ClassVar[str] = "attribute"
    key: str = "other"
    value: str = ""

    def __post_init__(self) -> None:
        super().__post_init__()
        check(self.key in ATTRIBUTE_KEYS, f"attribute key {self.key!r} not in {ATTRIBUTE_KEYS}")


@dataclass(frozen=True, kw_only=True)
class RoomConstraint(_Constraint):
    """In a room of canonical ``type`` ("kitchen"; None when the word is unknown).

    ``name`` holds the words used ("cafe lounge"), for text matching against room and
    area labels. ``beside`` names what the room lies next to, a room type or a thing
    ("the bathroom off the entry hall": "entryway"; "… by the front door": "front door").
    ``opening``: what is sought leads into the room ("the door to the toilet"), so the
    rooms that open onto a room of the type match as well as the room itself.
    """

    kind: ClassVar[str] = "room"
    type: str | None = None
    name: str = ""
    beside: str = ""
    opening: bool = False


@dataclass(frozen=True, kw_only=True)
class AreaConstraint(_Constraint):
    """In a functional area whose label resembles ``label`` ("reading corner")."""

    kind: ClassVar[str] = "area"
    label: str = ""


@dataclass(frozen=True, kw_only=True)
class FloorConstraint(_Constraint):
    """On floor ``level`` (0 = lowest) or on the floors a ``relative`` word names."""

    kind: ClassVar[str] = "floor"
    hard: ClassVar[bool] = True
    level: int | None = None
    relative: str | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        check(
            (self.level is None) != (self.relative is None),
            "floor constraint needs exactly one of 'level' and 'relative'",
        )
        check(
            self.relative is None or self.relative in RELATIVE_FLOORS,
            f"floor relative {self.relative!r} is not one of {RELATIVE_FLOORS}",
        )


@dataclass(frozen=True, kw_only=True)
class Superlative(_Constraint):
    """Rank the candidates: by size/height, by distance to ``landmark`` (to the viewer
    when None), by ``ordinal`` position (2 = second; -1 = last) or the ``middle`` one,
    counted from ``direction`` (``DIRECTIONS``, as the viewer sees them) when given;
    without a direction an ordinal counts from the viewer outwards ("the second door");
    ``most`` / ``fewest``: by how many of the ``landmark`` things each holds or has on or
    beside it ("the shelf with the most books", "the floor with the most bedrooms")."""

    kind: ClassVar[str] = "superlative"
    measure: str = "largest"
    landmark: Landmark | None = None
    ordinal: int | None = None
    direction: str | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        check(self.measure in MEASURES, f"superlative {self.measure!r} not in {MEASURES}")
        check(
            (self.measure == "ordinal") == (self.ordinal is not None),
            "an ordinal superlative needs 'ordinal' (and only it)",
        )
        check(
            self.direction is None or self.direction in DIRECTIONS,
            f"superlative direction {self.direction!r} is not one of {DIRECTIONS}",
        )


@dataclass(frozen=True, kw_only=True)
class PlacementConstraint(_Constraint):
    """Where in its room the node stands: against a ``wall``, in a ``corner`` or in the
    ``centre`` (``PLACEMENTS``); measured on the room's floor mask."""

    kind: ClassVar[str] = "placement"
    where: str = "wall"

    def __post_init__(self) -> None:
        super().__post_init__()
        check(self.where in PLACEMENTS, f"placement {self.where!r} is not one of {PLACEMENTS}")


@dataclass(frozen=True, kw_only=True)
class RelationConstraint(_Constraint):
    """``predicate(target, landmark)`` holds (see ``PREDICATES``); ``between`` needs
    ``landmark2``."""

    kind: ClassVar[str] = "relation"
    predicate: str = "near"
    landmark: Landmark = field(default_factory=lambda: Landmark())
    landmark2: Landmark | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        check(self.predicate in PREDICATES, f"predicate {self.predicate!r} not in {PREDICATES}")
        check(
            (self.predicate == "between") == (self.landmark2 is not None),
            "relation 'between' needs 'landmark2' (and only it)",
        )


Constraint = Union[  # noqa: UP007 - a runtime alias used by isinstance checks
    LabelConstraint,
    FunctionConstraint,
    AttributeConstraint,
    RoomConstraint,
    AreaConstraint,
    FloorConstraint,
    Superlative,
    RelationConstraint,
    PlacementConstraint,
]
KINDS: dict[str, type[_Constraint]] = {
    c.kind: c
    for c in (
        LabelConstraint,
        FunctionConstraint,
        AttributeConstraint,
        RoomConstraint,
        AreaConstraint,
        FloorConstraint,
        Superlative,
        RelationConstraint,
        PlacementConstraint,
    )
}


@dataclass(frozen=True, kw_only=True)
class Landmark:
    """A reference object of a relation: its own target and nested constraints
    (chains: "the mug on the table next to the window")."""

    target: Target = field(default_factory=Target)
    constraints: tuple[Constraint, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return {
            "target": self.target.to_dict(),
            "constraints": [c.to_dict() for c in self.constraints],
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Landmark:
        """Inverse of :meth:`to_dict`."""
        check(isinstance(data, dict), "landmark must be an object")
        return cls(
            target=Target.from_dict(data.get("target", {})),
            constraints=tuple(constraint_from_dict(c) for c in data.get("constraints", [])),
        )


@dataclass(frozen=True, kw_only=True)
class Viewpoint:
    """Where the speaker stands and looks, for "left", "right", "front" and ordinals.

    ``kind`` (``VIEWPOINT_KINDS``): ``facing`` — looking towards the landmark ("if you
    face the windows"); ``from`` — standing at the landmark and looking into the room
    ("from the door", "as you come through the door"); ``back_to`` — looking away from
    the landmark ("with your back to the TV"); ``seated`` — sitting or lying on the
    landmark and looking the way it faces ("sitting on the sofa", "lying in bed"). The
    robot's own pose, when a request carries it, is given to the engine separately
    (:class:`ViewerPose`). ``toward``: what the speaker looks at from there, when the
    request says so ("standing at the sink looking at the bar", "sitting on the couch
    facing the TV").
    """

    kind: str = "facing"
    landmark: Landmark = field(default_factory=Landmark)
    text: str = ""
    toward: Landmark | None = None

    def __post_init__(self) -> None:
        check(
            self.kind in VIEWPOINT_KINDS,
            f"viewpoint kind {self.kind!r} is not one of {VIEWPOINT_KINDS}",
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        out = {"kind": self.kind, "landmark": self.landmark.to_dict(), "text": self.text}
        if self.toward is not None:
            out["toward"] = self.toward.to_dict()
        return out

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Viewpoint:
        """Inverse of :meth:`to_dict`."""
        check(isinstance(data, dict), "viewpoint must be an object")
        toward = data.get("toward")
        return cls(
            kind=str(data.get("kind", "facing")),
            landmark=Landmark.from_dict(data.get("landmark", {})),
            text=str(data.get("text", "")),
            toward=Landmark.from_dict(toward) if toward is not None else None,
        )


def constraint_from_dict(data: dict[str, Any]) -> Constraint:
    """Build one constraint from its :meth:`to_dict` form (dispatch on ``kind``)."""
    check(isinstance(data, dict), "constraint must be an object")
    cls = KINDS.get(str(data.get("kind")))
    check(cls is not None, f"constraint kind {data.get('kind')!r} is not one of {list(KINDS)}")
    assert cls is not None
    kwargs: dict[str, Any] = {}
    for f in fields(cls):
        if f.name not in data:
            continue
        value = data[f.name]
        if f.name in ("landmark", "landmark2") and value is not None:
            value = Landmark.from_dict(value)
        elif f.name == "labels":
            value = str_tuple(value, f.name)
        kwargs[f.name] = value
    try:
        made = cls(**kwargs)
    except TypeError as exc:
        raise InputError(f"constraint {data.get('id', '?')}: {exc}") from None
    return made  # type: ignore[return-value]
