"""All 500 real requests of the Embodied-RAG benchmark parse cleanly.

Every request yields a target or an explicit no-object-target result; explicit requests
name a label or a function; global ones ("How does this space encourage …") are
recognised as having no object target.
"""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

import pytest

from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.query import ParsedQuery


@pytest.fixture(scope="module")
def requests() -> list[dict[str, str]]:
    real = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "real"
    path = real / "queries" / "embodied_rag_queries.jsonl"
    if not path.is_file():
        pytest.skip(f"real queries not found at {path}")
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


@pytest.fixture(scope="module")
def parsed(requests: list[dict[str, str]]) -> list[tuple[dict[str, str], ParsedQuery]]:
    return [(r, parse_rules(r["query"])) for r in requests]


def test_all_requests_parse(parsed: list[tuple[dict[str, str], ParsedQuery]]) -> None:
    assert len(parsed) == 500
    for request, result in parsed:
        assert result.has_target or result.no_target_reason, request["query"]
        assert result.parser == "rules"


def test_explicit_requests_name_a_label_or_function(
    parsed: list[tuple[dict[str, str], ParsedQuery]],
) -> None:
    explicit = [(r, p) for r, p in parsed if r["type"] == "explicit"]
    assert len(explicit) == 125
    for request, result in explicit:
        assert result.no_target_reason is None, request["query"]
        assert result.target.labels or result.target.function, request["query"]


def test_global_requests_have_no_object_target(
    parsed: list[tuple[dict[str, str], ParsedQuery]],
) -> None:
    outcome = Counter(
        (r["type"], p.no_target_reason is not None) for r, p in parsed if r["type"] != "explicit"
    )
    assert outcome[("global", True)] == 125
    assert outcome[("implicit", True)] == 0


def test_implicit_requests_mostly_yield_a_function(
    parsed: list[tuple[dict[str, str], ParsedQuery]],
) -> None:
    implicit = [p for r, p in parsed if r["type"] == "implicit"]
    with_function = sum(1 for p in implicit if p.target.function)
    assert with_function / len(implicit) > 0.9


@pytest.mark.parametrize(
    ("text", "label", "place"),
    [
        ("Where is the recycle bin located in the office workspace?", "recycle bin", "office workspace"),
        ("Where is the security scanner in the entry control zone?", "security scanner", "entry control zone"),
        ("Where are the napkin holders located in the cafeteria dining space?", "napkin holder", "cafeteria dining space"),
    ],
)  # fmt: skip
def test_explicit_examples(text: str, label: str, place: str) -> None:
    result = parse_rules(text)
    assert result.target.labels == (label,)
    assert [c.label for c in result.of_kind("area")] == [place]  # type: ignore[union-attr]
