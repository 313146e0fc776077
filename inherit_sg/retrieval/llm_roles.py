"""The three LLM roles of the request parser: prompts, JSON schemas, and validation of
their answers into the constraint model.

1. *decomposer*: target, landmarks and spatial requirements as constraints;
2. *negation extractor*: which constraint ids the request negates;
3. *weight assigner*: an importance weight in [0, 1] per constraint id.

Answers are checked field by field; anything off raises :class:`InputError` naming the
role and the field, which makes the parser fall back to the rule grammar.
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
    REFERENCES,
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
from inherit_sg.retrieval.query import ParsedQuery, describe, map_constraints, number_constraints
from inherit_sg.vocab.functions import kinds_serving
from inherit_sg.vocab.rooms import room_type

_STRS = {"type": "array", "items": {"type": "string"}}
_NSTR = {"type": ["string", "null"]}
_KINDS = ["attribute", "relation", "room", "area", "floor", "superlative", "function", "label"]


def _enum(values: tuple[str, ...] | list[str], nullable: bool = False) -> dict[str, Any]:
    if nullable:
        return {"type": ["string", "null"], "enum": [*values, None]}
    return {"type": "string", "enum": list(values)}


def _strict(props: dict[str, Any]) -> dict[str, Any]:
    return {"type": "object", "additionalProperties": False, "required": list(props),
            "properties": props}  # fmt: skip


_LANDMARK_REF = {"anyOf": [{"$ref": "#/$defs/landmark"}, {"type": "null"}]}
CONSTRAINT_SCHEMA = _strict({
    "kind": _enum(_KINDS), "text": {"type": "string"}, "key": _enum(ATTRIBUTE_KEYS, True),
    "value": _NSTR, "predicate": _enum(PREDICATES, True), "landmark": _LANDMARK_REF,
    "landmark2": _LANDMARK_REF, "level": {"type": ["integer", "null"]},
    "relative": _enum(RELATIVE_FLOORS, True), "measure": _enum(MEASURES, True),
    "ordinal": {"type": ["integer", "null"]}, "direction": _enum(("left", "right"), True),
})  # fmt: skip
LANDMARK_SCHEMA = _strict(
    {"labels": _STRS, "constraints": {"type": "array", "items": {"$ref": "#/$defs/constraint"}}}
)
DECOMPOSE_SCHEMA: dict[str, Any] = {
    **_strict({
        "target": _strict({"layer": _enum(LAYERS), "labels": _STRS, "function": _NSTR,
                           "plural": {"type": "boolean"}}),
        "constraints": {"type": "array", "items": {"$ref": "#/$defs/constraint"}},
        "reference": _enum(REFERENCES), "no_target_reason": _NSTR,
    }),
    "$defs": {"constraint": CONSTRAINT_SCHEMA, "landmark": LANDMARK_SCHEMA},
}  # fmt: skip
NEGATION_SCHEMA = _strict({"negated": _STRS})
WEIGHT_SCHEMA = _strict(
    {"weights": {"type": "array", "items": _strict({"id": {"type": "string"},
                                                   "weight": {"type": "number"}})}}
)  # fmt: skip

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


def _need(ok: bool, where: str, message: str) -> None:
    if not ok:
        raise InputError(f"llm decomposer: {where}: {message}")


def _function_labels(function: str) -> tuple[str, ...]:
    return kinds_serving(function)


def _labels(raw: Any, where: str) -> tuple[str, ...]:
    _need(isinstance(raw, list) and all(isinstance(x, str) for x in raw), where,
          "labels must be a list of strings")  # fmt: skip
    out: list[str] = []
    for label in raw:
        for canon in request_labels(label):
            if canon not in out:
                out.append(canon)
    return tuple(out)


def _landmark(raw: Any, where: str) -> Landmark:
    _need(isinstance(raw, dict), where, "landmark must be an object")
    labels = _labels(raw.get("labels", []), f"{where}.labels")
    nested = raw.get("constraints", [])
    _need(isinstance(nested, list), where, "landmark constraints must be a list")
    return Landmark(
        target=Target(labels=labels, noun=" / ".join(labels), any=not labels),
        constraints=tuple(
            _constraint(c, f"{where}.constraints[{i}]") for i, c in enumerate(nested)
        ),
    )


def _constraint(raw: Any, where: str) -> Constraint:
    _need(isinstance(raw, dict), where, "constraint must be an object")
    kind, text, value = raw.get("kind"), str(raw.get("text") or ""), raw.get("value")
    try:
        if kind == "attribute":
            _need(isinstance(value, str) and bool(value), where, "attribute needs a value")
            key = raw.get("key") if raw.get("key") in ATTRIBUTE_KEYS else "other"
            return AttributeConstraint(key=key, value=value.lower(), text=text, weight=0.6)
        if kind == "relation":
            predicate = str(raw.get("predicate") or "").replace(" ", "_")
            second = raw.get("landmark2")
            return RelationConstraint(
                predicate=predicate, landmark=_landmark(raw.get("landmark"), f"{where}.landmark"),
                landmark2=_landmark(second, f"{where}.landmark2") if second else None,
                text=text, weight=0.8,
            )  # fmt: skip
        if kind == "room":
            _need(isinstance(value, str) and bool(value), where, "room needs a value")
            return RoomConstraint(type=room_type(value), name=value.lower(), text=text, weight=0.7)
        if kind == "area":
            _need(isinstance(value, str) and bool(value), where, "area needs a value")
            return AreaConstraint(label=value.lower(), text=text, weight=0.6)
        if kind == "floor":
            return FloorConstraint(level=raw.get("level"), relative=raw.get("relative"), text=text)
        if kind == "superlative":
            lm = raw.get("landmark")
            return Superlative(
                measure=str(raw.get("measure")), ordinal=raw.get("ordinal"),
                direction=raw.get("direction"), text=text, weight=0.8,
                landmark=_landmark(lm, f"{where}.landmark") if lm else None,
            )  # fmt: skip
        if kind == "function":
            _need(isinstance(value, str) and bool(value), where, "function needs a value")
            return FunctionConstraint(function=value, labels=_function_labels(value), text=text,
                                      weight=0.9)  # fmt: skip
        if kind == "label":
            labels = _labels([value] if isinstance(value, str) else [], where)
            _need(bool(labels), where, "label needs a value")
            return LabelConstraint(labels=labels, noun=str(value), text=text)
    except InputError as exc:
        if exc.message.startswith("llm decomposer"):
            raise
        raise InputError(f"llm decomposer: {where}: {exc.message}") from None
    raise InputError(f"llm decomposer: {where}: unknown constraint kind {kind!r}")


def decomposition_to_query(text: str, data: dict[str, Any]) -> ParsedQuery:
    """Validate the decomposer's answer into a numbered :class:`ParsedQuery`."""
    raw_target = data.get("target")
    _need(isinstance(raw_target, dict), "target", "missing or not an object")
    assert isinstance(raw_target, dict)
    layer = raw_target.get("layer", "object")
    _need(layer in LAYERS, "target.layer", f"{layer!r} is not one of {LAYERS}")
    labels = _labels(raw_target.get("labels", []), "target.labels")
    function = raw_target.get("function")
    _need(function is None or isinstance(function, str), "target.function", "must be a string")
    raw = data.get("constraints", [])
    _need(isinstance(raw, list), "constraints", "must be a list")
    found = [_constraint(c, f"constraints[{i}]") for i, c in enumerate(raw)]
    head: list[Constraint] = []
    if labels and not any(c.kind == "label" and not c.negated for c in found):
        head.append(LabelConstraint(labels=labels, noun=" / ".join(labels), text="target"))
    if function and not any(c.kind == "function" for c in found):
        head.append(FunctionConstraint(function=function, labels=_function_labels(function),
                                       weight=0.9, text="target"))  # fmt: skip
    reference = data.get("reference", "none")
    _need(reference in REFERENCES, "reference", f"{reference!r} is not one of {REFERENCES}")
    reason = data.get("no_target_reason")
    attributes = tuple(c.value for c in found if isinstance(c, AttributeConstraint))
    target = Target(
        layer=layer, labels=labels, noun=" / ".join(labels), function=function,
        attributes=attributes, plural=bool(raw_target.get("plural", False)),
        any=not labels and bool(function),
    )  # fmt: skip
    return ParsedQuery(
        text=text,
        target=target,
        constraints=number_constraints((*head, *found)),
        reference=reference,
        no_target_reason=str(reason) if reason and not labels and not function else None,
        parser="llm",
    )


def apply_negations(query: ParsedQuery, data: dict[str, Any]) -> ParsedQuery:
    """Flag the constraint ids the negation extractor returned."""
    ids = data.get("negated")
    if not isinstance(ids, list) or not all(isinstance(x, str) for x in ids):
        raise InputError("llm negation extractor: 'negated' must be a list of ids")
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
    items = data.get("weights")
    if not isinstance(items, list):
        raise InputError("llm weight assigner: 'weights' must be a list")
    known = {c.id for c, _ in query.walk()}
    weights: dict[str, float] = {}
    for item in items:
        cid = item.get("id") if isinstance(item, dict) else None
        weight = item.get("weight") if isinstance(item, dict) else None
        if cid not in known:
            raise InputError(f"llm weight assigner: unknown constraint id {cid!r}")
        if not isinstance(weight, int | float) or not 0.0 <= weight <= 1.0:
            raise InputError(f"llm weight assigner: weight of {cid} must be in [0, 1]")
        weights[str(cid)] = float(weight)
    constraints = map_constraints(
        query.constraints, lambda c: replace(c, weight=weights.get(c.id, c.weight))
    )
    return replace(query, constraints=constraints)
