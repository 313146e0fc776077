"""Vector search against numpy brute force, before and after updates, with and
without candidate filtering, on both the exact and the HNSW path."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.errors import InputError, MapError
from inherit_sg.model import AreaNode, Layer, ObjectNode, make_id
from inherit_sg.store import MapStore
from inherit_sg.store import search as search_mod
from inherit_sg.store.indexes import VECTOR_INDEXES
from tests.integration.store_data import make_object


def brute_force(vectors: dict[str, np.ndarray], query: np.ndarray, k: int) -> list[str]:
    ids = sorted(vectors)
    mat = np.stack([vectors[i] for i in ids]).astype(np.float64)
    mat /= np.linalg.norm(mat, axis=1, keepdims=True)
    dist = 1.0 - mat @ (query / np.linalg.norm(query))
    return [ids[i] for i in np.argsort(dist, kind="stable")[:k]]


def clustered(rng: np.random.Generator, n: int, dim: int) -> np.ndarray:
    centres = rng.normal(size=(max(n // 20, 4), dim))
    return (centres[rng.integers(0, len(centres), n)] + 0.3 * rng.normal(size=(n, dim))).astype(
        np.float32
    )


def objects(rng: np.random.Generator, n: int) -> list[ObjectNode]:
    vis, txt = clustered(rng, n, 256), clustered(rng, n, 384)
    out = []
    for i in range(n):
        obj = make_object(rng, i)
        obj.visual_feature, obj.text_embedding = vis[i], txt[i]
        out.append(obj)
    return out


@pytest.fixture(params=["exact", "hnsw"])
def exact_limit(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> str:
    """Run each test on the in-memory exact path and on Kuzu's HNSW index."""
    if request.param == "hnsw":
        monkeypatch.setattr(search_mod, "EXACT_MAX_ROWS", 0)
    return str(request.param)


def test_nearest_neighbours_match_brute_force(tmp_path: Path, exact_limit: str) -> None:
    rng = np.random.default_rng(11)
    objs = objects(rng, 300)
    with MapStore.create(tmp_path / "m") as store:
        store.upsert_nodes(objs)
        visual = {o.id: o.visual_feature for o in objs}
        text = {o.id: o.text_embedding for o in objs}
        for _ in range(10):
            q = objs[int(rng.integers(0, 300))].visual_feature + 0.2 * rng.normal(size=256)
            hits = store.vector_search("object_visual", q, k=10)
            assert [h[0] for h in hits] == brute_force(visual, q, 10)  # type: ignore[arg-type]
            assert all(a[1] <= b[1] for a, b in itertools.pairwise(hits))
            qt = rng.normal(size=384).astype(np.float32)
            hits_t = store.vector_search("object_text", qt, k=5)
            assert [h[0] for h in hits_t] == brute_force(text, qt, 5)  # type: ignore[arg-type]
        q = objs[7].visual_feature
        top = store.vector_search("object_visual", q, k=1)
        assert top[0][0] == objs[7].id and top[0][1] == pytest.approx(0.0, abs=1e-5)


def test_search_follows_updates_and_deletes(tmp_path: Path, exact_limit: str) -> None:
    rng = np.random.default_rng(12)
    objs = objects(rng, 120)
    with MapStore.create(tmp_path / "m") as store:
        store.upsert_nodes(objs)
        visual = {o.id: o.visual_feature for o in objs}
        for obj in objs[:40]:  # new vectors: delete + insert under the index
            obj.visual_feature = rng.normal(size=256).astype(np.float32)
            visual[obj.id] = obj.visual_feature
        objs[40].visual_feature = None  # no vector any more
        del visual[objs[40].id]
        store.upsert_nodes(objs[:41])
        store.delete_nodes([o.id for o in objs[41:60]])
        for o in objs[41:60]:
            del visual[o.id]
        assert store.stats().vectors["object_visual"] == len(visual)
        for i in range(15):
            q = objs[i].visual_feature if i < 5 else rng.normal(size=256).astype(np.float32)
            hits = store.vector_search("object_visual", q, k=8)  # type: ignore[arg-type]
            assert [h[0] for h in hits] == brute_force(visual, q, 8)  # type: ignore[arg-type]
        store.close()
        with MapStore.open(tmp_path / "m") as reopened:
            q = objs[3].visual_feature
            assert reopened.vector_search("object_visual", q, k=1)[0][0] == objs[3].id  # type: ignore[arg-type]


def test_candidate_subset_is_exact(tmp_path: Path, exact_limit: str) -> None:
    rng = np.random.default_rng(13)
    objs = objects(rng, 200)
    with MapStore.create(tmp_path / "m") as store:
        store.upsert_nodes(objs)
        visual_all = {o.id: o.visual_feature for o in objs}
        subset = {o.id for o in objs[::7]} | {"obj:9999"}  # unknown ids are ignored
        visual = {o.id: o.visual_feature for o in objs if o.id in subset}
        for _ in range(5):
            q = rng.normal(size=256).astype(np.float32)
            hits = store.vector_search("object_visual", q, k=6, ids=subset)
            assert [h[0] for h in hits] == brute_force(visual, q, 6)  # type: ignore[arg-type]
        pair = {objs[3].id, objs[150].id}  # small subsets are read by id
        hits = store.vector_search("object_visual", q, k=5, ids=pair)
        assert [h[0] for h in hits] == brute_force({i: visual_all[i] for i in pair}, q, 5)
        assert store.vector_search("object_visual", q, k=5, ids=[]) == []


def test_area_and_room_text_and_errors(tmp_path: Path) -> None:
    rng = np.random.default_rng(14)
    areas = [
        AreaNode(
            make_id(Layer.AREA, i),
            f"area {i}",
            text_embedding=rng.normal(size=384).astype(np.float32),
        )
        for i in range(12)
    ]
    with MapStore.create(tmp_path / "m") as store:
        assert store.vector_search("room_text", rng.normal(size=384), k=3) == []
        store.upsert_nodes(areas)
        q = areas[4].text_embedding
        assert store.vector_search("area_text", q, k=1)[0][0] == "area:4"  # type: ignore[arg-type]
        with pytest.raises(InputError, match="unknown vector index"):
            store.vector_search("object_colour", q, k=1)  # type: ignore[arg-type]
        with pytest.raises(InputError, match="384"):
            store.vector_search("area_text", np.ones(10), k=1)
        assert store.vector_search("area_text", q, k=0) == []  # type: ignore[arg-type]


def test_search_index_is_derived_and_rebuilt(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(search_mod, "EXACT_MAX_ROWS", 0)  # use the HNSW index
    rng = np.random.default_rng(15)
    objs = objects(rng, 80)
    path = tmp_path / "m"
    with MapStore.create(path) as store:
        store.upsert_nodes(objs)
    for name in ("index.kuzu", "index.kuzu.wal"):
        (path / name).unlink(missing_ok=True)  # lost, or stale after a crash
    q = objs[5].visual_feature
    with MapStore.open(path) as store:  # read-only: exact scans of the graph's vectors
        assert store.vector_search("object_visual", q, k=1)[0][0] == objs[5].id  # type: ignore[arg-type]
        with pytest.raises(MapError, match="for writing"):
            store.text_search("Object", "chair", k=3)
    with MapStore.open(path, write=True) as store:  # a writer rebuilds it from the graph
        assert store.stats().bytes_index > 0
    with MapStore.open(path) as store:
        assert store._index is not None and store._index.has_hnsw(VECTOR_INDEXES["object_visual"])
        assert store.vector_search("object_visual", q, k=1)[0][0] == objs[5].id  # type: ignore[arg-type]
        assert {h[0] for h in store.text_search("Object", "chair", k=100)} == {
            o.id for o in objs if o.label == "chair"
        }
