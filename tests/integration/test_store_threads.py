"""Reads from other threads while the single writer commits."""

from __future__ import annotations

import threading
from pathlib import Path

import numpy as np

from inherit_sg.store import MapStore
from tests.integration.store_data import make_object


def test_readers_run_while_the_writer_commits(tmp_path: Path) -> None:
    rng = np.random.default_rng(21)
    batches = [[make_object(rng, 10 * b + j) for j in range(10)] for b in range(8)]
    errors: list[BaseException] = []
    seen: list[int] = []
    done = threading.Event()
    with MapStore.create(tmp_path / "m") as store:
        store.upsert_nodes(batches[0])

        def read_loop() -> None:
            try:
                while not done.is_set():
                    graph = store.load_graph()  # one snapshot: whole batches only
                    n = len(list(graph.objects()))
                    assert n % 10 == 0, n
                    seen.append(n)
                    q = batches[0][0].visual_feature
                    assert store.vector_search("object_visual", q, k=1)[0][0] == "obj:0"  # type: ignore[arg-type]
                    store.text_search("Object", "object", k=5)
            except BaseException as exc:
                errors.append(exc)

        readers = [threading.Thread(target=read_loop) for _ in range(2)]
        for t in readers:
            t.start()
        try:
            for batch in batches[1:]:
                store.upsert_nodes(batch)
        finally:
            done.set()
            for t in readers:
                t.join(timeout=60)
        assert not errors, errors
        assert seen and max(seen) <= 80
        assert store.stats().nodes["Object"] == 80
