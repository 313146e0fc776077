"""The constraint data model: validation, polarity, numbering, JSON round trips."""

from __future__ import annotations

import json
from collections.abc import Callable

import pytest

from inherit_sg.errors import InputError
from inherit_sg.retrieval import (
    AttributeConstraint,
    FloorConstraint,
    Landmark,
    ParsedQuery,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
    describe,
    parse_rules,
)
from inherit_sg.retrieval.constraints import DEFAULT_WEIGHTS, constraint_from_dict
from inherit_sg.retrieval.query import map_constraints, number_constraints


def _chain() -> ParsedQuery:
    window = Landmark(target=Target(labels=("window",)))
    table = Landmark(
        target=Target(labels=("table",)),
        constraints=(RelationConstraint(predicate="next_to", landmark=window),),
    )
    constraints = number_constraints(
        (
            AttributeConstraint(key="colour", value="red", negated=True, weight=0.6),
            RelationConstraint(predicate="on", landmark=table, weight=0.8),
            FloorConstraint(relative="upstairs"),
        )
    )
    return ParsedQuery(text="x", target=Target(labels=("mug",)), constraints=constraints)


def test_polarity_follows_negation() -> None:
    assert RoomConstraint(type="kitchen").polarity == 1
    assert RoomConstraint(type="kitchen", negated=True).polarity == -1


@pytest.mark.parametrize(
    ("make", "field"),
    [
        (lambda: RelationConstraint(predicate="beside", landmark=Landmark()), "beside"),
        (lambda: RelationConstraint(predicate="between", landmark=Landmark()), "landmark2"),
        (lambda: FloorConstraint(), "exactly one"),
        (lambda: FloorConstraint(level=1, relative="top"), "exactly one"),
        (lambda: FloorConstraint(relative="attic"), "attic"),
        (lambda: AttributeConstraint(key="flavour", value="x"), "flavour"),
        (lambda: Superlative(measure="ordinal"), "ordinal"),
        (lambda: Superlative(measure="prettiest"), "prettiest"),
        (lambda: RoomConstraint(weight=1.5), "weight"),
        (lambda: Target(layer="building"), "building"),
        (lambda: ParsedQuery(text="x", reference="that"), "reference"),
    ],
)
def test_invalid_constraints_raise_input_error_naming_the_field(
    make: Callable[[], object], field: str
) -> None:
    with pytest.raises(InputError, match=field):
        make()


def test_numbering_reaches_into_landmarks() -> None:
    parsed = _chain()
    assert [c.id for c, _ in parsed.walk()] == ["c1", "c2", "c2.1", "c3"]
    assert [depth for _, depth in parsed.walk()] == [0, 0, 1, 0]
    found = parsed.find("c2.1")
    assert isinstance(found, RelationConstraint) and found.predicate == "next_to"
    assert parsed.floor is not None and parsed.floor.relative == "upstairs"  # type: ignore[union-attr]


def test_between_landmarks_are_numbered_in_sequence() -> None:
    red = (AttributeConstraint(key="colour", value="red"),)
    rel = RelationConstraint(
        predicate="between",
        landmark=Landmark(target=Target(labels=("sofa",)), constraints=red),
        landmark2=Landmark(target=Target(labels=("tv",)), constraints=red),
    )
    (numbered,) = number_constraints((rel,))
    assert numbered.landmark.constraints[0].id == "c1.1"  # type: ignore[union-attr]
    assert numbered.landmark2.constraints[0].id == "c1.2"  # type: ignore[union-attr]


def test_json_round_trip_is_lossless() -> None:
    for parsed in (_chain(), parse_rules("the second chair from the left, not in the kitchen")):
        text = parsed.to_json()
        back = ParsedQuery.from_dict(json.loads(text))
        assert back == parsed
        assert back.to_dict()["constraints"][0]["polarity"] in (1, -1)


def test_from_dict_rejects_bad_input() -> None:
    with pytest.raises(InputError, match="kind"):
        constraint_from_dict({"kind": "colour", "value": "red"})
    with pytest.raises(InputError, match="text"):
        ParsedQuery.from_dict({"target": {}})
    with pytest.raises(InputError, match="labels"):
        Target.from_dict({"labels": "chair"})


def test_map_constraints_visits_nested_ones() -> None:
    parsed = _chain()
    halved = map_constraints(parsed.constraints, lambda c: type(c)(**{**vars(c), "weight": 0.5}))
    weights = [c.weight for c, _ in ParsedQuery(text="x", constraints=halved).walk()]
    assert weights == [0.5, 0.5, 0.5, 0.5]


def test_describe_reads_like_the_request() -> None:
    parsed = _chain()
    assert describe(parsed.constraints[0]) == "NOT attribute colour = red"
    assert describe(parsed.constraints[1]) == "relation on → table"
    assert describe(parsed.constraints[2]) == "floor upstairs"
    assert Target(labels=("chair",), function="sit", attributes=("red",)).describe() == (
        "red chair (to sit)"
    )


def test_default_weights_rank_label_above_details() -> None:
    w = DEFAULT_WEIGHTS
    assert w["label"] > w["function"] > w["relation"] > w["room"] > w["attribute"]
    parsed = parse_rules("the red mug on the table in the kitchen")
    assert [c.weight for c in parsed.constraints] == [1.0, 0.6, 0.8, 0.7]


def test_has_target() -> None:
    assert parse_rules("the red chair").has_target
    assert not ParsedQuery(text="x", no_target_reason="global").has_target
    assert not ParsedQuery(text="x").has_target
