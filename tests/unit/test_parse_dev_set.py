"""The offline parser on the development set (tests/data/dev_requests, 1530 requests
written the way people talk; see docs/dev_requests.md): targets and negations right
at least 95 % of the time, no negation made up beyond a handful, no crash, and each
constraint kind mostly found."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.benchmark.metrics.parse import Report, evaluate, load_requests
from inherit_sg.retrieval.rules import parse_uncached

DEV = Path(__file__).resolve().parents[1] / "data" / "dev_requests"
FORMS = (
    "copula", "there_is", "imperative", "question", "bare_np", "multi_sentence",
    "relative_clause", "negation", "conjunction", "viewpoint", "ordinal", "counting",
    "comparative", "superlative", "between", "closest", "farthest", "wall", "corner",
    "centre", "support", "containment", "part", "not_but", "except", "synonym",
    "open_vocabulary", "room", "floor", "function", "attribute", "relation", "typo",
)  # fmt: skip
# Recall of each constraint kind today (rounded down), so that a change that loses
# one shows here; targets and negations have the bar of 95 %.
KIND_RECALL = {
    "attribute": 0.75, "floor": 0.9, "function": 0.75, "ordinal": 0.7, "part": 0.4,
    "placement": 0.6, "relation": 0.75, "room": 0.75, "superlative": 0.9, "viewpoint": 0.7,
}  # fmt: skip


@pytest.fixture(scope="module")
def report() -> Report:
    return evaluate(load_requests(sorted(DEV.glob("*.jsonl"))), parse_uncached)


def test_set_is_large_and_covers_every_form(report: Report) -> None:
    assert report.n >= 600
    ids = [j.id for j in report.judgements]
    assert len(ids) == len(set(ids))
    seen = {form for j in report.judgements for form in j.forms}
    assert set(FORMS) <= seen, set(FORMS) - seen


def test_targets_right(report: Report) -> None:
    wrong = [f"{j.id}: {j.text}" for j in report.judgements if not j.target_ok]
    assert report.target_accuracy >= 0.95, wrong


def test_negations_right(report: Report) -> None:
    assert report.negation_recall >= 0.95
    assert report.negation_accuracy >= 0.95
    assert report.negations_invented <= 5


def test_nothing_crashes(report: Report) -> None:
    assert not report.crashes, [(j.id, j.error) for j in report.crashes]


@pytest.mark.parametrize("kind", sorted(KIND_RECALL))
def test_constraint_kinds_found(report: Report, kind: str) -> None:
    found, wanted = report.constraint_recall()[kind]
    assert wanted and found / wanted >= KIND_RECALL[kind], (kind, found, wanted)
