"""Random edits of a scene graph, persisted with write_changes after each round: the
stored graph must always equal the in-memory one (nodes, vectors, edges, text index)."""

from __future__ import annotations

import random
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.model import Edge, EdgeKind, ObjectNode, SceneGraph
from inherit_sg.store import MapStore
from tests.integration.store_data import assert_same_graph, make_object, sample_graph

WORDS = ["red", "blue", "chair", "table", "lamp", "wooden", "small", "door"]


def edit(graph: SceneGraph, rnd: random.Random, rng: np.random.Generator, next_id: int) -> int:
    """One round of random additions, updates, merges, removals and edge changes."""
    objects = [o.id for o in graph.objects()]
    for _ in range(rnd.randint(1, 6)):
        graph.add_or_update(make_object(rng, next_id))
        graph.add_edge(Edge.make(EdgeKind.HAS_OBJECT, "area:0", f"obj:{next_id}"))
        next_id += 1
    for oid in rnd.sample(objects, min(len(objects), 4)):
        obj = graph.get(oid)
        assert isinstance(obj, ObjectNode)
        choice = rnd.random()
        if choice < 0.3:
            obj.label = rnd.choice(WORDS)
        elif choice < 0.5:
            obj.visual_feature = (
                None if obj.visual_feature is not None else rng.normal(size=256).astype(np.float32)
            )
        elif choice < 0.7:
            obj.text_embedding = rng.normal(size=384).astype(np.float32)
        else:
            obj.position = (rnd.random(), rnd.random(), 0.5)
        graph.touch(oid)
    objects = [o.id for o in graph.objects()]
    if len(objects) > 4 and rnd.random() < 0.5:
        keep, drop = rnd.sample(objects, 2)
        graph.merge_nodes(keep, drop)
        objects.remove(drop)
    if len(objects) > 4 and rnd.random() < 0.5:
        graph.remove(rnd.choice(objects))
        objects = [o.id for o in graph.objects()]
    for _ in range(3):
        a, b = rnd.sample(objects, 2)
        graph.add_edge(
            Edge.make(
                EdgeKind.RELATION,
                a,
                b,
                predicate=rnd.choice(["near", "on"]),
                confidence=rnd.random(),
            )
        )
    relations = list(graph.edges(EdgeKind.RELATION))
    if relations:
        gone = rnd.choice(relations)
        graph.remove_edge(gone.kind, gone.src, gone.dst, str(gone.prop("predicate", "")))
    return next_id


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_rounds_round_trip(tmp_path: Path, seed: int) -> None:
    rnd, rng = random.Random(seed), np.random.default_rng(seed)
    graph = sample_graph(seed=seed)
    next_id = 100
    with MapStore.create(tmp_path / "m") as store:
        store.write_changes(graph)
        for _ in range(8):
            next_id = edit(graph, rnd, rng, next_id)
            store.write_changes(graph)
            assert_same_graph(graph, store.load_graph())
        labelled = {
            o.id for o in graph.objects() if o.label == "lamp" or "lamp" in o.description.split()
        }
        assert {h[0] for h in store.text_search("Object", "lamp", k=500)} == labelled
    with MapStore.open(tmp_path / "m") as store:
        assert_same_graph(graph, store.load_graph())
