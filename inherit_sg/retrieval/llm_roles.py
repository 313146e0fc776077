"""The three LLM roles of the request parser: prompts, JSON schemas, and validation of
their answers into the constraint model.

1. *decomposer*: target, landmarks and spatial requirements as constraints;
2. *negation extractor*: which constraint ids the request negates;
3. *weight assigner*: an importance weight in [0, 1] per constraint id.

Answers are validated by the pydantic models of :mod:`.llm_answers` (which also give the
JSON schemas sent); anything off raises :class:`InputError` naming the role and the field,
which makes the parser fall back to the rule grammar.
"""

from __future__ import annotations

import json
from dataclasses import replace
from typing import Any

from inherit_sg.errors import InputError
from inherit_sg.retrieval.constraints import (
    ATTRIBUTE_KEYS,
    LAYERS,
    MEASURES,
    PREDICATES,
    RELATIVE_FLOORS,
    AreaConstraint,
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    FunctionConstraint,
    LabelConstraint,
    Landmark,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
)
from inherit_sg.retrieval.labels import request_labels
from inherit_sg.retrieval.llm_answers import (
    ConstraintAnswer,
    Decomposition,
    LandmarkAnswer,
    Negations,
    Weights,
    strict_schema,
    validated,
)
from inherit_sg.retrieval.query import ParsedQuery, describe, map_constraints, number_constraints
from inherit_sg.vocab.functions import kinds_serving
from inherit_sg.vocab.rooms import room_type

DECOMPOSE_SCHEMA = strict_schema(Decomposition)
NEGATION_SCHEMA = strict_schema(Negations)
WEIGHT_SCHEMA = strict_schema(Weights)

DECOMPOSER_PROMPT = f"""You are the decomposer of a robot's request parser (role 1 of 3).
Turn an indoor navigation request into JSON matching the schema. Do not judge negation or
importance; other roles do that.
- target: what is sought. layer is one of {list(LAYERS)}; labels are singular English
  nouns for the kind of thing ("sofa" for "couches"); function is what the user wants to do
  when no object is named ("sit", "wash hands"); leave labels empty if unknown.
- constraints: one per requirement, with "text" quoting the request's words:
  attribute (key in {list(ATTRIBUTE_KEYS)}, value e.g. "red"); relation (predicate in
  {list(PREDICATES)}, read predicate(target, landmark); "between" also needs landmark2;
  a landmark has its own labels and constraints, so chains nest); room (value: room words);
  area (value: functional area name); floor (level: ground/first floor = 0, second = 1, or
  relative in {list(RELATIVE_FLOORS)}); superlative (measure in {list(MEASURES)}, landmark
  for closest/farthest, ordinal for "the second one"); function (value); label (value: a
  kind the user excludes or adds).
- Keep negated requirements as ordinary constraints ("not in the kitchen" -> room kitchen).
- reference: "previous" for "it"/"that one", "other" for "the other one",
  "exclude_previous" for "not that one, ...", "refine" for "the red one"/"what about ...".
- no_target_reason: a short reason when the request asks about the space as a whole and
  names nothing to find; otherwise null. Unused fields are null."""

NEGATION_PROMPT = """You are the negation extractor of a robot's request parser (role 2
of 3). You get a request and its numbered constraints. Return the ids of the constraints
the request negates or excludes ("not", "no", "n't", "without", "except", "other than",
"away from", "no X next to it"). Return an empty list when nothing is negated."""

WEIGHT_PROMPT = """You are the weight assigner of a robot's request parser (role 3 of 3).
You get a request and its numbered constraints. Give every constraint an importance weight
between 0 and 1: about 1.0 for what the user insists on or names as the thing sought,
about 0.8 for spatial relations, 0.6 for descriptive details, lower for hedged wishes
("maybe", "preferably")."""


def messages(system: str, payload: Any) -> list[dict[str, str]]:
    """A system + user message pair; the user message is ``payload`` as JSON text."""
    text = payload if isinstance(payload, str) else json.dumps(payload, ensure_ascii=False)
    return [{"role": "system", "content": system}, {"role": "user", "content": text}]


def listing(query: ParsedQuery) -> dict[str, Any]:
    """The request and its numbered constraints, as roles 2 and 3 see them."""
    return {
        "request": query.text,
        "constraints": [
            {"id": c.id, "kind": c.kind, "meaning": describe(c), "text": c.text}
            for c, _ in query.walk()
        ],
    }


def _labels(raw: list[str]) -> tuple[str, ...]:
    out: list[str] = []
    for label in raw:
        for canon in request_labels(label):
            if canon not in out:
                out.append(canon)
    return tuple(out)


def _landmark(raw: LandmarkAnswer) -> Landmark:
    labels = _labels(raw.labels)
    return Landmark(
        target=Target(labels=labels, noun=" / ".join(labels), any=not labels),
        constraints=tuple(_constraint(c) for c in raw.constraints),
    )


def _value(raw: ConstraintAnswer) -> str:
    if not raw.value:
        raise InputError(f"{raw.kind} needs a value")
    return raw.value


def _constraint(raw: ConstraintAnswer) -> Constraint:
    """One validated constraint answer in the constraint model."""
    text = raw.text or ""
    if raw.kind == "attribute":
        return AttributeConstraint(key=raw.key or "other", value=_value(raw).lower(), text=text,
                                   weight=0.6)  # fmt: skip
    if raw.kind == "relation":
        if raw.landmark is None:
            raise InputError("relation needs a landmark")
        return RelationConstraint(
            predicate=str(raw.predicate or ""), landmark=_landmark(raw.landmark),
            landmark2=_landmark(raw.landmark2) if raw.landmark2 else None, text=text, weight=0.8,
        )  # fmt: skip
    if raw.kind == "room":
        value = _value(raw)
        return RoomConstraint(type=room_type(value), name=value.lower(), text=text, weight=0.7)
    if raw.kind == "area":
        return AreaConstraint(label=_value(raw).lower(), text=text, weight=0.6)
    if raw.kind == "floor":
        return FloorConstraint(level=raw.level, relative=raw.relative, text=text)
    if raw.kind == "superlative":
        return Superlative(
            measure=str(raw.measure), ordinal=raw.ordinal, direction=raw.direction, text=text,
            weight=0.8, landmark=_landmark(raw.landmark) if raw.landmark else None,
        )  # fmt: skip
    if raw.kind == "function":
        value = _value(raw)
        return FunctionConstraint(function=value, labels=kinds_serving(value), text=text,
                                  weight=0.9)  # fmt: skip
    labels = _labels([raw.value] if raw.value else [])
    if not labels:
        raise InputError("label needs a value")
    return LabelConstraint(labels=labels, noun=str(raw.value), text=text)


def _constraints(raw: list[ConstraintAnswer]) -> list[Constraint]:
    """The constraints of the decomposition, the failing one named by its index."""
    out = []
    for i, item in enumerate(raw):
        try:
            out.append(_constraint(item))
        except InputError as exc:
            raise InputError(f"llm decomposer: constraints[{i}]: {exc.message}") from None
    return out


def decomposition_to_query(text: str, data: dict[str, Any]) -> ParsedQuery:
    """Validate the decomposer's answer into a numbered :class:`ParsedQuery`."""
    answer: Decomposition = validated(Decomposition, data, "decomposer")
    labels = _labels(answer.target.labels)
    function = answer.target.function
    found = _constraints(answer.constraints)
    head: list[Constraint] = []
    if labels and not any(c.kind == "label" and not c.negated for c in found):
        head.append(LabelConstraint(labels=labels, noun=" / ".join(labels), text="target"))
    if function and not any(c.kind == "function" for c in found):
        head.append(FunctionConstraint(function=function, labels=kinds_serving(function),
                                       weight=0.9, text="target"))  # fmt: skip
    reason = answer.no_target_reason
    attributes = tuple(c.value for c in found if isinstance(c, AttributeConstraint))
    target = Target(
        layer=answer.target.layer, labels=labels, noun=" / ".join(labels), function=function,
        attributes=attributes, plural=answer.target.plural, any=not labels and bool(function),
    )  # fmt: skip
    return ParsedQuery(
        text=text,
        target=target,
        constraints=number_constraints((*head, *found)),
        reference=answer.reference,
        no_target_reason=str(reason) if reason and not labels and not function else None,
        parser="llm",
    )


def apply_negations(query: ParsedQuery, data: dict[str, Any]) -> ParsedQuery:
    """Flag the constraint ids the negation extractor returned."""
    ids = validated(Negations, data, "negation extractor").negated
    known = {c.id for c, _ in query.walk()}
    unknown = sorted(set(ids) - known)
    if unknown:
        raise InputError(f"llm negation extractor: unknown constraint ids {unknown}")
    wanted = set(ids)
    constraints = map_constraints(query.constraints, lambda c: replace(c, negated=c.id in wanted))
    attributes = tuple(
        c.value for c in constraints if isinstance(c, AttributeConstraint) and not c.negated
    )
    return replace(query, constraints=constraints,
                   target=replace(query.target, attributes=attributes))  # fmt: skip


def apply_weights(query: ParsedQuery, data: dict[str, Any]) -> ParsedQuery:
    """Set the weights the weight assigner returned (others keep their defaults)."""
    answer: Weights = validated(Weights, data, "weight assigner")
    known = {c.id for c, _ in query.walk()}
    weights: dict[str, float] = {}
    for item in answer.weights:
        if item.id not in known:
            raise InputError(f"llm weight assigner: unknown constraint id {item.id!r}")
        weights[item.id] = item.weight
    constraints = map_constraints(
        query.constraints, lambda c: replace(c, weight=weights.get(c.id, c.weight))
    )
    return replace(query, constraints=constraints)
