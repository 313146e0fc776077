"""The LLM roles' answer models: strict schemas to send, clear errors on answers that are
off (the parser then falls back to the rules)."""

from __future__ import annotations

from typing import Any

import pytest

from inherit_sg.errors import InputError
from inherit_sg.retrieval.llm_answers import Decomposition, Weights, strict_schema, validated
from inherit_sg.retrieval.llm_roles import DECOMPOSE_SCHEMA, NEGATION_SCHEMA, WEIGHT_SCHEMA


def _objects(node: Any) -> list[dict[str, Any]]:
    found = []
    if isinstance(node, dict):
        if isinstance(node.get("properties"), dict):
            found.append(node)
        for value in node.values():
            found += _objects(value)
    elif isinstance(node, list):
        for value in node:
            found += _objects(value)
    return found


@pytest.mark.parametrize("schema", [DECOMPOSE_SCHEMA, NEGATION_SCHEMA, WEIGHT_SCHEMA])
def test_schemas_are_strict(schema: dict[str, Any]) -> None:
    objects = _objects(schema)
    assert objects
    for obj in objects:
        assert obj["required"] == list(obj["properties"]) and obj["additionalProperties"] is False
        for prop in obj["properties"].values():
            assert not {"default", "minimum", "maximum"} & set(prop)


def test_answers_are_checked_and_the_error_names_the_field() -> None:
    ok = validated(
        Decomposition,
        {"target": {"layer": "object", "labels": ["mug"]},
         "constraints": [{"kind": "relation", "predicate": "next to",
                          "landmark": {"labels": ["sofa"], "constraints": []}}]},
        "decomposer",
    )  # fmt: skip
    assert ok.constraints[0].predicate == "next_to" and ok.reference == "none"
    with pytest.raises(InputError, match=r"constraints\[0\]\.kind: .*\(got 'colour'\)"):
        validated(Decomposition, {"target": {}, "constraints": [{"kind": "colour"}]}, "decomposer")
    with pytest.raises(InputError, match=r"llm weight assigner: weights\[0\]\.weight"):
        validated(Weights, {"weights": [{"id": "c1", "weight": 3}]}, "weight assigner")
    with pytest.raises(InputError, match="target"):
        validated(Decomposition, {"constraints": []}, "decomposer")
    assert strict_schema(Weights)["required"] == ["weights"]
