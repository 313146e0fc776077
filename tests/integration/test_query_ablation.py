"""The two ablation switches of the query engine on a real map: ``retrieval.use_areas``
(functional-area nodes out of the search) and ``retrieval.verify_segmenter`` (the
verifier judges the recorded crop without grounding the target label first)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from inherit_sg.config import Config
from inherit_sg.model import Edge, EdgeKind
from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.store import MapStore
from tests.unit.retrieval_fixtures import give_best_view, write_small_map


def _config(**retrieval: object) -> Config:
    cfg = Config()
    for key, value in retrieval.items():
        setattr(cfg.retrieval, key, value)
    return cfg


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_small_map(tmp_path_factory.mktemp("ablation") / "map")


@pytest.fixture(scope="module")
def store(map_dir: Path) -> Iterator[MapStore]:
    with MapStore.open(map_dir, write=True) as opened:
        yield opened


def test_without_areas_no_area_is_a_candidate(store: MapStore) -> None:
    with_areas = QueryEngine(store, _config(use_areas=True))
    flat = QueryEngine(store, _config(use_areas=False))
    assert with_areas.query("Take me to the sleeping area").answer_id == "area:a_sleep"
    result = flat.query("Take me to the sleeping area")
    assert result.answer_id is None and result.candidates == []
    snap = flat.snapshot()[0]
    assert snap.areas == {} and not snap.use_areas
    # objects keep their rooms and floors, only the area level is gone
    assert snap.room_of["obj:m2"] == "room:kitchen" and snap.area_of["obj:m2"] is None
    assert snap.level_of("obj:tl1") == 1


def test_without_areas_area_constraints_do_not_score(store: MapStore) -> None:
    with_areas = QueryEngine(store, _config(use_areas=True))
    flat = QueryEngine(store, _config(use_areas=False))
    text = "the mug in the cooking area"
    assert with_areas.query(text).answer_id == "obj:m2"
    result = flat.query(text)
    assert {c["id"] for c in result.candidates} == {"obj:m1", "obj:m2", "obj:m3"}
    scores = {c["id"]: c["score"] for c in result.candidates}
    assert len(set(scores.values())) == 1  # nothing tells the three mugs apart any more
    # requests without area words are answered as before
    assert flat.query("the sink under the mirror").answer_id == "obj:sk1"


def test_verification_without_the_segmenter_step(store: MapStore) -> None:
    give_best_view(store, "obj:c3", (190, 40, 40))
    # the recorded detection names something else: grounding the label fails
    seen = Edge.make(EdgeKind.SEEN_IN, "obj:c3", "kf:1", label="table", bbox=[100, 60, 199, 179])
    store.upsert_edges([seen])
    grounded = QueryEngine(store, _config(verify_segmenter=True)).query("the red chair")
    assert grounded.candidates[0]["id"] == "obj:c3"
    assert any("obj:c3: rejected" in line and "table" in line for line in grounded.trace)
    direct = QueryEngine(store, _config(verify_segmenter=False)).query("the red chair")
    assert direct.answer_id == "obj:c3" and direct.answer is not None
    assert direct.answer["verified"] is True
    assert any("grounding skipped" in line for line in direct.trace)
