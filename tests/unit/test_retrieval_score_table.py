"""The columnar scorer ranks as the per-candidate reference key does, and its lazily
built rows read like plain scored candidates."""

from __future__ import annotations

import pytest

from inherit_sg.retrieval.constraints import LabelConstraint, Landmark, RelationConstraint, Target
from inherit_sg.retrieval.score_table import HINT_WEIGHT, ScoreTable
from inherit_sg.retrieval.scoring import Scored, _kind_first
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from tests.unit.retrieval_fixtures import small_graph
from tests.unit.test_retrieval_scoring import rank

REQUESTS = [
    "the mug",
    "the red mug on the table",
    "a chair not in the kitchen",
    "the largest table",
    "something to sit on upstairs",
    "the mug next to the sink in the kitchen",
]


@pytest.fixture(scope="module")
def snap() -> MapSnapshot:
    return build_snapshot(small_graph(), (1,))


def _plain(cand: Scored) -> Scored:
    return Scored(cand.id, dict(cand.terms), cand.h_floor, cand.found_by)


@pytest.mark.parametrize("text", REQUESTS)
def test_order_matches_the_reference_key(snap: MapSnapshot, text: str) -> None:
    ranked = rank(snap, text)
    assert ranked
    plain = [_plain(c) for c in ranked]
    assert [c.id for c in sorted(plain, key=_kind_first(plain, snap))] == [c.id for c in ranked]


@pytest.mark.parametrize("text", REQUESTS)
def test_rows_read_like_plain_candidates(snap: MapSnapshot, text: str) -> None:
    ranked = rank(snap, text)
    table_scores = [c.score for c in ranked]  # before the terms are built
    plain = [_plain(c) for c in ranked]
    assert [c.score for c in plain] == table_scores
    assert [(c.id, c.terms, c.h_floor, c.found_by) for c in ranked] == [
        (c.id, c.terms, c.h_floor, c.found_by) for c in plain
    ]
    first = ranked[0]
    term = next(iter(first.terms.values()))
    term.sim += 1.0  # a built row's terms are its own, and its score follows them
    assert first.score == pytest.approx(table_scores[0] + term.polarity * term.weight)


def test_hints_are_left_out_of_the_scores_a_superlative_tiers_on() -> None:
    table = ScoreTable(["obj:a", "obj:b"], [["cypher"], ["cypher"]])
    table.add(LabelConstraint(id="c1", labels=("stool",)), [1.0, 1.0])
    sink = Landmark(target=Target(labels=("sink",), noun="sink"))
    hint = RelationConstraint(id="c2", predicate="near", landmark=sink, weight=HINT_WEIGHT)
    table.add(hint, [0.5, 0.0])
    assert table.columns["c2"].is_hint() and not table.columns["c1"].is_hint()
    assert table.scores().tolist() == pytest.approx([1.2, 1.0])
    assert table.scores(hints=False).tolist() == pytest.approx([1.0, 1.0])
    firm = RelationConstraint(id="c3", predicate="near", landmark=sink, weight=0.8)
    assert not table.add(firm, [0.0, 0.0]).is_hint()
