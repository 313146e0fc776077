"""The rule parser against a hand-written table of requests (tests/data/parse_cases.jsonl).

Each case names only what matters for it; a key that is absent is not checked.
Categories: A in room / on floor, B one landmark, C chained, D negation, E descriptive /
superlative, F implicit / functional, G global, R robustness (word order, politeness,
synonyms, plurals, unknown nouns, emphasis), V follow-ups parsed alone, T follow-ups
resolved against a conversation history.
"""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

from inherit_sg.retrieval import (
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    Landmark,
    ParsedQuery,
    RelationConstraint,
    parse_rules,
)
from inherit_sg.retrieval.conversation import Conversation

CASES_FILE = Path(__file__).resolve().parents[1] / "data" / "parse_cases.jsonl"
CASES = [json.loads(line) for line in CASES_FILE.read_text().splitlines() if line.strip()]


def _attrs(constraints: tuple[Constraint, ...] | list[Constraint]) -> list[list[Any]]:
    return [[c.key, c.value, c.negated] for c in constraints if isinstance(c, AttributeConstraint)]


def _check_landmark(lm: Landmark, label: str | None, where: str) -> None:
    if label is not None:
        assert label in lm.target.labels, f"{where}: landmark {lm.target.labels} lacks {label}"


def _check_relations(found: list[Constraint], expected: list[dict[str, Any]], where: str) -> None:
    rels = [c for c in found if isinstance(c, RelationConstraint)]
    assert len(rels) == len(expected), f"{where}: relations {rels}"
    for rel, exp in zip(rels, expected, strict=True):
        assert rel.predicate == exp["predicate"], f"{where}: predicate {rel.predicate}"
        assert rel.negated == exp.get("negated", False), f"{where}: negation of {rel.predicate}"
        _check_landmark(rel.landmark, exp.get("landmark"), where)
        if "landmark2" in exp:
            assert rel.landmark2 is not None, f"{where}: no second landmark"
            _check_landmark(rel.landmark2, exp["landmark2"], where)
        if exp.get("landmark_anaphor"):
            assert rel.landmark.target.anaphor, f"{where}: landmark is not 'it'"
        if "landmark_ids" in exp:
            assert list(rel.landmark.target.node_ids) == exp["landmark_ids"]
        if "landmark_attributes" in exp:
            assert _attrs(rel.landmark.constraints) == exp["landmark_attributes"]
        if "chain" in exp:
            _check_relations(list(rel.landmark.constraints), exp["chain"], f"{where} > chain")


def check(parsed: ParsedQuery, exp: dict[str, Any]) -> None:
    """Assert every expectation present in ``exp`` on ``parsed``."""
    if exp.get("no_target"):
        assert parsed.no_target_reason is not None and not parsed.has_target
        return
    assert parsed.no_target_reason is None, parsed.no_target_reason
    t = parsed.target
    cons = parsed.constraints
    simple = {
        "layer": t.layer,
        "function": t.function,
        "any": t.any,
        "plural": t.plural,
        "quantity": t.quantity,
        "noun": t.noun,
        "anaphor": t.anaphor,
        "reference": parsed.reference,
        "node_ids": list(t.node_ids),
        "exclude_ids": list(parsed.exclude_ids),
    }
    for key, value in simple.items():
        if key in exp:
            assert value == exp[key], f"{key}: {value!r} != {exp[key]!r}"
    if "negated" in exp:  # whether anything at all is ruled out
        assert any(c.negated for c in cons) == exp["negated"], cons
    if "labels" in exp:
        assert sorted(t.labels) == sorted(exp["labels"])
    if "labels_include" in exp:
        assert set(exp["labels_include"]) <= set(t.labels), t.labels
    if "functions" in exp:
        assert [c.function for c in cons if c.kind == "function"] == exp["functions"]  # type: ignore[union-attr]
    if "attributes" in exp:
        assert _attrs(cons) == exp["attributes"]
    if "rooms" in exp:
        rooms = [[c.type, c.negated] for c in cons if c.kind == "room"]  # type: ignore[union-attr]
        assert rooms == exp["rooms"]
    if "areas" in exp:
        areas = [[c.label, c.negated] for c in cons if c.kind == "area"]  # type: ignore[union-attr]
        assert areas == exp["areas"]
    if "placements" in exp:
        found = [[c.where, c.negated] for c in cons if c.kind == "placement"]  # type: ignore[union-attr]
        assert found == exp["placements"]
    if "floors" in exp:
        floors = [
            [c.level if c.level is not None else c.relative, c.negated]
            for c in cons
            if isinstance(c, FloorConstraint)
        ]
        assert floors == exp["floors"]
    if "relations" in exp:
        _check_relations(list(cons), exp["relations"], "relations")
    if "superlative" in exp and exp["superlative"] is None:
        assert not parsed.of_kind("superlative")
    elif "superlative" in exp:
        sups = parsed.of_kind("superlative")
        assert len(sups) == 1, sups
        sup = sups[0]
        measure, landmark, ordinal, direction = exp["superlative"]
        assert (sup.measure, sup.ordinal, sup.direction) == (measure, ordinal, direction)  # type: ignore[union-attr]
        if landmark is None:
            assert sup.landmark is None  # type: ignore[union-attr]
        else:
            _check_landmark(sup.landmark, landmark, "superlative")  # type: ignore[union-attr,arg-type]
    if "excluded" in exp:
        excluded = [c for c in parsed.of_kind("label") if c.negated]
        assert [list(c.labels) for c in excluded] == [exp["excluded"]]  # type: ignore[union-attr]
    if "viewpoint" in exp:  # [kind, standpoint label, what the speaker looks at or None]
        kind, label, toward = exp["viewpoint"]
        vp = parsed.viewpoint
        assert vp is not None and vp.kind == kind, vp
        _check_landmark(vp.landmark, label, "viewpoint")
        if toward is None:
            assert vp.toward is None, vp.toward
        else:
            assert vp.toward is not None, vp
            _check_landmark(vp.toward, toward, "toward")
    for cid, weight in exp.get("weights", {}).items():
        found = parsed.find(cid)
        assert found is not None and found.weight == pytest.approx(weight), (cid, found)


@pytest.mark.parametrize("case", CASES, ids=[c["id"] for c in CASES])
def test_case(case: dict[str, Any]) -> None:
    conversation = Conversation()
    for text, answer in case.get("history", []):
        conversation.add_turn(conversation.resolve(parse_rules(text)), answer)
    parsed = conversation.resolve(parse_rules(case["text"]))
    check(parsed, case["expect"])


def test_table_is_large_and_covers_every_category() -> None:
    counts = Counter(c["cat"] for c in CASES)
    assert len(CASES) >= 150
    assert len({c["id"] for c in CASES}) == len(CASES)
    for cat in "ABCDEFGRVT":
        assert counts[cat] >= 5, (cat, counts)


def test_constraint_ids_are_unique_and_numbered() -> None:
    for case in CASES:
        parsed = parse_rules(case["text"])
        ids = [c.id for c, _ in parsed.walk()]
        assert len(ids) == len(set(ids)), case["id"]
        top = [c.id for c in parsed.constraints]
        assert top == [f"c{i}" for i in range(1, len(top) + 1)], case["id"]
