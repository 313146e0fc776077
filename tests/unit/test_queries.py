"""The SQR-style query generator and conversations on a procedural two-floor house."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from collections import Counter
from dataclasses import replace
from pathlib import Path

import pytest

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.synthetic.queries import (
    PAPER_SHARES,
    ConversationGT,
    QueryGT,
    category_shares,
    generate_conversations,
    generate_queries,
    read_conversations,
    read_queries,
    write_conversations,
    write_queries,
)
from inherit_sg.ingest.synthetic.query_text import article, display, labels_for_noun, plural
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.ingest.synthetic.truth import ObjectSpec, SceneIndex, evaluate
from tests.fixtures_scenes import house_scene

SEED = 7


@pytest.fixture(scope="module")
def scene() -> Scene:
    return house_scene(0)


@pytest.fixture(scope="module")
def queries(scene: Scene) -> list[QueryGT]:
    return generate_queries(scene, SEED)


@pytest.fixture(scope="module")
def conversations(scene: Scene) -> list[ConversationGT]:
    return generate_conversations(scene, SEED)


def test_house_fixture_is_big_enough(scene: Scene) -> None:
    assert len({f.index for f in scene.floors}) == 2
    assert len(scene.rooms) == 12
    assert 110 <= sum(1 for o in scene.objects if not o.structural) <= 200


def test_at_least_300_unique_queries(queries: list[QueryGT]) -> None:
    assert len(queries) >= 300
    texts = [q.text.lower() for q in queries]
    assert len(set(texts)) == len(texts)
    assert len({q.id for q in queries}) == len(queries)


def test_every_answer_set_is_exactly_the_evaluated_truth(
    scene: Scene, queries: list[QueryGT]
) -> None:
    index = SceneIndex(scene)
    for q in queries:
        truth = evaluate(scene, ObjectSpec.from_dict(q.gt_constraints), index)
        assert q.target_ids == truth, q.text
        assert q.target_positions == [scene.object(i).centroid for i in truth]


def test_answer_sets_are_small_except_a_few_floor_requests(queries: list[QueryGT]) -> None:
    large = [q for q in queries if len(q.target_ids) > 3]
    assert all(q.category == "A" and q.subcategory == "floor" for q in large)
    assert len(large) <= 0.05 * len(queries)
    assert all(len(q.target_ids) >= 1 for q in queries)


def test_category_shares_match_the_paper(queries: list[QueryGT]) -> None:
    shares = category_shares(queries)
    for group, paper in PAPER_SHARES.items():
        assert abs(shares[group] - paper) <= 0.05, (group, shares[group])
    assert all(shares[c] > 0.05 for c in "ABC")


def test_at_least_eight_templates_per_category(queries: list[QueryGT]) -> None:
    for category in "ABCDEF":
        used = {q.template for q in queries if q.category == category}
        assert len(used) >= 8, (category, used)
        assert all(t.startswith(f"{category}.") for t in used)


def test_texts_are_finished_sentences(queries: list[QueryGT]) -> None:
    for q in queries:
        assert not re.search(r"[{}]|None|\s\s|\bthe the\b|\ba a\b", q.text), q.text
        assert q.text[0].isupper() and q.text[-1] in ".?!", q.text


def test_negations_exclude_something(scene: Scene, queries: list[QueryGT]) -> None:
    index = SceneIndex(scene)
    negations = [q for q in queries if q.category == "D"]
    assert negations
    for q in negations:
        query = ObjectSpec.from_dict(q.gt_constraints)
        assert query.negation_count() == 1, q.text
        without = evaluate(scene, query.positive(), index)
        assert set(q.target_ids) < set(without), q.text


def test_categories_have_their_structure(queries: list[QueryGT]) -> None:
    for q in queries:
        data = q.gt_constraints
        if q.category == "B":
            assert len(data["relations"]) == 1 and "room" not in data
        if q.category == "C":
            levels = ("room" in data) + ("floor" in data) + ("area" in data)
            chained = any("relations" in r["landmark"] for r in data.get("relations", []))
            assert levels + len(data.get("relations", [])) >= 2 or chained, q.text
        if q.category == "E":
            assert data.get("attributes") or data.get("superlative"), q.text
        if q.category == "F":
            assert data.get("function") and not data["labels"], q.text


def test_words_vary(queries: list[QueryGT]) -> None:
    text = " ".join(q.text.lower() for q in queries)
    for phrase in ("could you", "i'm looking for", "where is", "take me to", "please go to"):
        assert phrase in text
    for synonym in ("couch", "cupboard", "upstairs", "downstairs"):
        assert synonym in text
    assert any(word in text for word in ("sitting room", "front room", "washroom", "restroom"))
    assert re.search(r"\b(chairs|books|windows|towels|mirrors|cabinets|cupboards)\b", text)


def test_deterministic_by_seed(scene: Scene, queries: list[QueryGT]) -> None:
    again = generate_queries(scene, SEED)
    assert [q.to_dict() for q in again] == [q.to_dict() for q in queries]
    other = generate_queries(scene, SEED + 1)
    assert [q.text for q in other] != [q.text for q in queries]


def test_requested_count_keeps_shares(scene: Scene) -> None:
    few = generate_queries(scene, 3, n=60)
    assert 55 <= len(few) <= 60
    shares = category_shares(few)
    assert all(abs(shares[g] - p) <= 0.05 for g, p in PAPER_SHARES.items())


def test_single_floor_scene_never_mentions_floors(scene: Scene) -> None:
    ground = replace(
        scene,
        floors=scene.floors[:1],
        rooms=[r for r in scene.rooms if r.floor == 0],
        objects=[o for o in scene.objects if o.floor == 0],
    )
    found = generate_queries(ground, 1)
    assert found
    assert all("floor" not in q.gt_constraints for q in found)
    assert not any(re.search(r"upstairs|downstairs|\w+ floor\b", q.text) for q in found)


def test_write_and_read_round_trip(tmp_path: Path, queries: list[QueryGT]) -> None:
    path = write_queries(tmp_path, queries)
    assert path.name == "queries.jsonl"
    first = json.loads(path.read_text().splitlines()[0])
    assert list(first)[:5] == ["id", "text", "category", "target_ids", "target_positions"]
    back = read_queries(tmp_path)
    assert [q.to_dict() for q in back] == [q.to_dict() for q in queries]


def test_read_rejects_malformed_files(tmp_path: Path) -> None:
    with pytest.raises(DatasetError, match="not found"):
        read_queries(tmp_path / "missing.jsonl")
    bad = tmp_path / "bad.jsonl"
    good = {"id": "q1", "text": "t", "category": "A", "target_ids": ["a"]}
    bad.write_text(json.dumps(good | {"target_positions": [[0, 0, 0]]}) + "\n{oops\n")
    with pytest.raises(DatasetError, match=r"bad\.jsonl:2"):
        read_queries(bad)
    bad.write_text(json.dumps(good | {"target_positions": [[0, 0]]}) + "\n")
    with pytest.raises(DatasetError, match=r"bad\.jsonl:1"):
        read_queries(bad)
    bad.write_text(json.dumps(good | {"category": "Z", "target_positions": [[0, 0, 0]]}))
    with pytest.raises(DatasetError, match="category"):
        read_queries(bad)


def test_conversation_turns_are_verified(scene: Scene, conversations: list[ConversationGT]) -> None:
    assert len(conversations) >= 20
    index = SceneIndex(scene)
    for conv in conversations:
        assert len(conv.turns) >= 2
        for turn in conv.turns:
            truth = evaluate(scene, ObjectSpec.from_dict(turn.gt_constraints), index)
            assert turn.target_ids == truth and truth, turn.text
            assert turn.target_positions == [scene.object(i).centroid for i in truth]


def test_followups_change_the_target(conversations: list[ConversationGT]) -> None:
    kinds = Counter(t.followup for c in conversations for t in c.turns[1:])
    assert set(kinds) == {"other_one", "room_switch", "floor_switch", "refine"}
    for conv in conversations:
        for before, after in zip(conv.turns, conv.turns[1:], strict=False):
            assert after.target_ids != before.target_ids, after.text
            if "other one" in after.text.lower():
                assert after.followup == "other_one"
                assert not set(after.target_ids) & set(before.target_ids), after.text
            if after.followup == "refine":
                assert set(after.target_ids) < set(before.target_ids), after.text


def test_conversations_round_trip_and_determinism(
    tmp_path: Path, scene: Scene, conversations: list[ConversationGT]
) -> None:
    path = write_conversations(tmp_path, conversations)
    assert path.name == "conversations.jsonl"
    assert [c.to_dict() for c in read_conversations(path)] == [c.to_dict() for c in conversations]
    again = generate_conversations(scene, SEED)
    assert [c.to_dict() for c in again] == [c.to_dict() for c in conversations]
    line = json.loads(path.read_text().splitlines()[0])
    assert set(line) == {"id", "turns"}
    assert {"text", "target_ids", "target_positions"} <= set(line["turns"][0])
    (tmp_path / "broken.jsonl").write_text('{"id": "c1"}\n')
    with pytest.raises(DatasetError, match=r"broken\.jsonl:1"):
        read_conversations(tmp_path / "broken.jsonl")


def test_same_output_whatever_the_hash_seed(tmp_path: Path) -> None:
    script = (
        "import json; from tests.fixtures_scenes import small_scene; "
        "from inherit_sg.ingest.synthetic.queries import generate_queries as g; "
        "print(json.dumps([q.to_dict() for q in g(small_scene(), 4)]))"
    )
    root = Path(__file__).resolve().parents[2]
    outputs = set()
    for hash_seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": hash_seed, "PYTHONPATH": str(root)}
        done = subprocess.run(
            [sys.executable, "-c", script], env=env, cwd=root, capture_output=True, check=True
        )
        outputs.add(done.stdout)
    assert len(outputs) == 1 and len(json.loads(outputs.pop())) > 20


def test_text_helpers() -> None:
    assert [plural(w) for w in ("chest of drawers", "bookshelf", "couch", "dish", "tv stand")] == [
        "chests of drawers",
        "bookshelves",
        "couches",
        "dishes",
        "tv stands",
    ]
    assert article("easy chair") == "an" and article("utility room") == "a"
    assert display("where is the tv  stand near the tvs ?") == "Where is the TV stand near the TVs?"
    assert labels_for_noun("lamp", ["lamp", "table lamp", "sofa"]) == ["lamp", "table lamp"]
    assert labels_for_noun("couch", ["sofa", "chair"]) == ["sofa"]
