"""Result JSON contract, trace lines, conversation files and the evaluation helpers."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from inherit_sg.benchmark.metrics.retrieval import (
    GroundTruth,
    Outcome,
    latency,
    oracle_id,
    percentile,
    summarise,
)
from inherit_sg.errors import InputError
from inherit_sg.ingest.synthetic.queries import QueryGT
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.conversation import Conversation
from inherit_sg.retrieval.history import load_conversation, save_conversation
from inherit_sg.retrieval.result import QueryResult, candidate_dict, node_summary
from inherit_sg.retrieval.scoring import Scored, Term
from inherit_sg.retrieval.trace import describe_query, explain_ranking
from tests.fixtures_scenes import small_scene
from tests.unit.retrieval_fixtures import small_snapshot


def test_result_json_has_the_contract_keys() -> None:
    snap = small_snapshot()
    cand = Scored("obj:m1", {"c1": Term("c1", "label", 1.0, 1, 1.0, "label 'mug' is a mug")})
    answer = {**node_summary(snap, "obj:m1"), "score": 1.0}
    result = QueryResult(
        query="the mug",
        answer=answer,
        candidates=[candidate_dict(snap, cand)],
        constraints=parse_rules("the mug").to_dict(),
        trace=["x"],
        timings_ms={"parse": 1.0, "retrieve": 2.0, "verify": 0.0, "total": 3.0},
    )
    data = json.loads(result.to_json())
    assert set(data) == {"query", "answer", "candidates", "constraints", "trace", "timings_ms"}
    assert {"id", "label", "position", "room", "floor", "score"} <= set(data["answer"])
    assert data["answer"]["room"] == "kitchen" and data["answer"]["floor"] == 0
    assert len(data["answer"]["position"]) == 3
    assert data["candidates"][0]["scores"]["c1"]["term"] == 1.0
    assert set(data["timings_ms"]) == {"parse", "retrieve", "verify", "total"}
    assert result.answer_id == "obj:m1" and result.candidate_ids == ["obj:m1"]


def test_trace_explains_kept_and_lower_candidates() -> None:
    snap = small_snapshot()
    top = Scored(
        "obj:m1",
        {
            "c1": Term("c1", "label", 1.0, 1, 1.0, "mug"),
            "c2": Term("c2", "relation", 0.8, 1, 1.0, "on t1"),
        },
    )
    low = Scored(
        "obj:m3",
        {"c1": Term("c1", "label", 1.0, 1, 1.0), "c2": Term("c2", "relation", 0.8, 1, 0.0)},
    )
    off = Scored("obj:m2", {"c1": Term("c1", "label", 1.0, 1, 1.0)}, h_floor=0)
    lines = explain_ranking(snap, [top, low, off], 10)
    assert any("kept" in line and "on t1" in line for line in lines)
    assert any("obj:m3" in line and "c2 +0.00 vs +0.80" in line for line in lines)
    assert any("obj:m2" in line and "floor filter" in line for line in lines)
    lines = describe_query(parse_rules("the mug not on the table"))
    assert lines[0].startswith("parsed by rules")
    assert any("NOT relation on" in line and "p=-1" in line for line in lines)


def test_conversation_file_round_trip(tmp_path: Path) -> None:
    conv = Conversation()
    conv.add_turn(parse_rules("the red chair"), "obj:c3", ("obj:c3", "obj:c1"))
    path = tmp_path / "conv.json"
    save_conversation(conv, path)
    again = load_conversation(path)
    assert len(again.turns) == 1
    assert again.turns[0].answer_id == "obj:c3"
    assert again.turns[0].query.to_dict() == conv.turns[0].query.to_dict()
    assert load_conversation(tmp_path / "missing.json").turns == []
    path.write_text('{"format": "something else"}')
    with pytest.raises(InputError, match="not an INHerit-SG conversation"):
        load_conversation(path)


def test_judging_answers_against_ground_truth() -> None:
    scene = small_scene()
    truth = GroundTruth(scene)
    m1 = next(o for o in scene.objects if o.id == "m1")
    q = QueryGT("q1", "the mug on the table", "B", ["m1"], [list(m1.centroid)])
    hit = truth.judge(q, ("obj:m1", m1.centroid, {"total": 2.0}), oracle_id)
    assert hit.within(0.5) and hit.semantic and hit.distance == 0.0
    near = [m1.centroid[0] + 0.7, m1.centroid[1], m1.centroid[2]]
    miss = truth.judge(q, ("obj:t1", near, {}), oracle_id)
    assert miss.within(1.0) and not miss.within(0.5) and not miss.semantic
    # a built map's node: the nearest ground-truth object decides semantics
    built = truth.judge(q, ("obj:17", m1.centroid, {}), oracle_id)
    assert built.semantic
    none = truth.judge(q, (None, None, {}), oracle_id)
    assert math.isinf(none.distance) and not none.semantic


def test_summaries_and_latency() -> None:
    outs = [
        Outcome("a", "A", "", "x", 0.2, True, {"total": 1.0}),
        Outcome("b", "D", "", "x", 0.7, False, {"total": 3.0}),
        Outcome("c", "F", "", None, math.inf, False, {"total": 2.0}),
    ]
    s = summarise(outs)
    assert s["A-C"]["within_1m"] == 100.0 and s["D"]["within_0.5m"] == 0.0
    assert s["overall"]["n"] == 3 and s["overall"]["within_1m"] == pytest.approx(200 / 3)
    assert s["group_mean"]["within_1m"] == pytest.approx(200 / 3)
    assert math.isnan(s["E"]["within_1m"])
    assert latency(outs)["total"]["p50"] == 2.0
    assert percentile([1.0, 2.0, 3.0, 4.0], 50) == 2.5
