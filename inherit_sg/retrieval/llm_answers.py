"""The answers the three LLM roles of the request parser must give, as pydantic models.

The models validate an answer (naming the field that is off) and give the JSON schema sent
with each request (:func:`strict_schema`: OpenAI's strict structured outputs want every
property listed as required, nullable where it may be empty, and no other properties).
:mod:`.llm_roles` turns a validated answer into the constraint model.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from inherit_sg.errors import InputError
from inherit_sg.retrieval.constraints import (
    ATTRIBUTE_KEYS,
    LAYERS,
    MEASURES,
    PREDICATES,
    REFERENCES,
    RELATIVE_FLOORS,
)

ConstraintKind = Literal[
    "attribute", "relation", "room", "area", "floor", "superlative", "function", "label"
]


def _one_of(values: tuple[str, ...]) -> Any:
    """A Literal type over ``values`` (the constraint model's own tuples)."""
    return Literal[values]


AttributeKey = _one_of(ATTRIBUTE_KEYS)
Predicate = _one_of(PREDICATES)
RelativeFloor = _one_of(RELATIVE_FLOORS)
Measure = _one_of(MEASURES)
Layer = _one_of(LAYERS)
Reference = _one_of(REFERENCES)


class _Answer(BaseModel):
    model_config = ConfigDict(extra="forbid")


class LandmarkAnswer(_Answer):
    """A reference object: its kinds and its own constraints (chains nest)."""

    labels: list[str] = Field(default_factory=list)
    constraints: list[ConstraintAnswer] = Field(default_factory=list)


class ConstraintAnswer(_Answer):
    """One requirement of the request; the fields its kind does not use are null."""

    kind: ConstraintKind
    text: str | None = None
    key: AttributeKey | None = None  # type: ignore[valid-type]
    value: str | None = None
    predicate: Predicate | None = None  # type: ignore[valid-type]
    landmark: LandmarkAnswer | None = None
    landmark2: LandmarkAnswer | None = None
    level: int | None = None
    relative: RelativeFloor | None = None  # type: ignore[valid-type]
    measure: Measure | None = None  # type: ignore[valid-type]
    ordinal: int | None = None
    direction: Literal["left", "right"] | None = None

    @field_validator("predicate", mode="before")
    @classmethod
    def _underscored(cls, value: Any) -> Any:
        """ "next to" is read as ``next_to``."""
        return value.replace(" ", "_") if isinstance(value, str) else value

    @field_validator("key", mode="before")
    @classmethod
    def _known_key(cls, value: Any) -> Any:
        """An attribute key the model does not know is read as ``other``."""
        return value if value is None or value in ATTRIBUTE_KEYS else "other"


class TargetAnswer(_Answer):
    """What is sought."""

    layer: Layer = "object"  # type: ignore[valid-type]
    labels: list[str] = Field(default_factory=list)
    function: str | None = None
    plural: bool = False


class Decomposition(_Answer):
    """Role 1: target, constraints, conversation reference, or why there is no target."""

    target: TargetAnswer
    constraints: list[ConstraintAnswer] = Field(default_factory=list)
    reference: Reference = "none"  # type: ignore[valid-type]
    no_target_reason: str | None = None


class Negations(_Answer):
    """Role 2: the ids of the constraints the request negates."""

    negated: list[str]


class Weight(_Answer):
    """One constraint's importance."""

    id: str
    weight: float = Field(ge=0.0, le=1.0)


class Weights(_Answer):
    """Role 3: an importance weight in [0, 1] per constraint id."""

    weights: list[Weight]


# Keywords strict structured outputs refuse; the models still enforce them on the answer.
_NOT_IN_STRICT = ("default", "minimum", "maximum")


def _strict(node: Any) -> None:
    """Every object of a JSON schema with all its properties required, in place."""
    if isinstance(node, dict):
        props = node.get("properties")
        if isinstance(props, dict):
            node["required"] = list(props)
            node["additionalProperties"] = False
            for prop in props.values():
                if isinstance(prop, dict):
                    for word in _NOT_IN_STRICT:
                        prop.pop(word, None)
        for value in node.values():
            _strict(value)
    elif isinstance(node, list):
        for value in node:
            _strict(value)


def strict_schema(model: type[BaseModel]) -> dict[str, Any]:
    """The JSON schema of ``model`` in the strict form structured outputs want."""
    schema = model.model_json_schema()
    _strict(schema)
    return schema


def validated(model: type[_Answer], data: Any, role: str) -> Any:
    """``data`` validated as ``model``; InputError naming the role, the field and what is
    wrong (the parser then falls back to the rule grammar)."""
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        first = exc.errors()[0]
        where = "".join(
            f"[{p}]" if isinstance(p, int) else (f".{p}" if i else str(p))
            for i, p in enumerate(first["loc"])
        )
        got = first.get("input")
        shown = f" (got {got!r})" if isinstance(got, str | int | float | bool) else ""
        raise InputError(f"llm {role}: {where or 'answer'}: {first['msg']}{shown}") from None


LandmarkAnswer.model_rebuild()
