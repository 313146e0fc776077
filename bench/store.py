"""Map store benchmark: insert throughput, vector/text query latency and bytes on disk
per object, at 1k, 10k and 100k objects (``--quick``: 1k and 10k).

Vectors are clustered (like real features; uniform random vectors are the worst case
for HNSW recall) in 256-d (visual) and 384-d (text). Each size is loaded with one bulk
``upsert_nodes`` call (the path an import takes), then 500 more objects are added in
batches of 50 (the mapping path), then ``vector_search`` and ``text_search`` are timed.
Bytes count ``graph.kuzu`` and ``index.kuzu`` (the graph keeps the vectors, the index
a mirror of them with HNSW; see ``inherit_sg/store/search_index.py``) and exclude
keyframe images (no keyframes are stored) and the empty map;
Kuzu also gives each table and index a first allocation of ~1 MB when it first gets
rows, which dominates at 1k objects. Pages freed by checkpoints stay in the file and
are reused by later writes (the file stops growing), so they are reported apart.
Prints one block per size and writes ``bench/results/store.json``.

    python bench/store.py [--quick] [--queries 200] [--out bench/results/store.json]
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.model import BBox3D, NodeId, ObjectNode
from inherit_sg.store import MapStore
from inherit_sg.store.search import EXACT_MAX_ROWS
from inherit_sg.store.stats import graph_bytes

LABELS = ["chair", "table", "lamp", "sofa", "bed", "plant", "cup", "book", "tv", "sink"]
COLOURS = ["red", "blue", "green", "white", "black", "wooden", "metal", "grey"]


def clustered(rng: np.random.Generator, n: int, dim: int) -> np.ndarray:
    """n vectors around n/50 random centres."""
    centres = rng.normal(size=(max(n // 50, 8), dim)).astype(np.float32)
    noise = 0.5 * rng.normal(size=(n, dim)).astype(np.float32)
    return centres[rng.integers(0, len(centres), n)] + noise


def make_objects(rng: np.random.Generator, start: int, n: int) -> list[ObjectNode]:
    """Objects ``obj:start`` … with both vectors, attributes and keyframe references."""
    vis, txt = clustered(rng, n, 256), clustered(rng, n, 384)
    xyz = rng.uniform(-20, 20, size=(n, 3))
    out = []
    for j in range(n):
        i = start + j
        label, colour = LABELS[i % len(LABELS)], COLOURS[(i // 3) % len(COLOURS)]
        x, y, z = (float(v) for v in xyz[j])
        out.append(
            ObjectNode(
                id=NodeId(f"obj:{i}"),
                label=label,
                position=(x, y, z),
                bbox=BBox3D((x - 0.3, y - 0.3, z - 0.4), (x + 0.3, y + 0.3, z + 0.4)),
                description=f"a {colour} {label} near the wall",
                visual_feature=vis[j],
                text_embedding=txt[j],
                keyframe_ids=[f"kf:{i // 4}", f"kf:{i // 4 + 1}"],
                best_keyframe=f"kf:{i // 4}",
                observation_count=3,
                attributes={"colour": colour, "size": "medium"},
                area_id=NodeId(f"area:{i // 20}"),
                room_id=NodeId(f"room:{i // 100}"),
                floor_id=NodeId("floor:0"),
            )
        )
    return out


def free_bytes(path: Path) -> int:
    """Pages on Kuzu's free lists (graph and index databases): space freed by
    checkpoints and reused by later ones."""
    import kuzu

    total = 0
    for name in ("graph.kuzu", "index.kuzu"):
        db = kuzu.Database(str(path / name), read_only=True)
        conn = kuzu.Connection(db)
        res = conn.execute("CALL FSM_INFO() RETURN sum(num_pages)")
        assert isinstance(res, kuzu.QueryResult)
        pages = res.get_next()[0]
        conn.close()
        db.close()
        total += int(pages or 0) * 4096
    return total


def percentiles(samples: list[float]) -> dict[str, float]:
    """p50/p99 in milliseconds."""
    arr = np.asarray(samples) * 1000.0
    return {"p50_ms": float(np.percentile(arr, 50)), "p99_ms": float(np.percentile(arr, 99))}


def recall_at_10(
    store: MapStore, index: str, mat: np.ndarray, ids: list[str], queries: np.ndarray
) -> tuple[dict[str, float], float]:
    """Latency of ``vector_search`` and its recall@10 against numpy brute force."""
    normed = mat / np.linalg.norm(mat, axis=1, keepdims=True)
    times, hits = [], 0
    for q in queries:
        t0 = time.perf_counter()
        got = store.vector_search(index, q, k=10)
        times.append(time.perf_counter() - t0)
        truth = np.argsort(1.0 - normed @ (q / np.linalg.norm(q)))[:10]
        hits += len({ids[i] for i in truth} & {g[0] for g in got})
    return percentiles(times), hits / (10 * len(queries))


def bench_size(n: int, n_queries: int, workdir: Path) -> dict[str, Any]:
    """Everything measured on one map of ``n`` objects."""
    rng = np.random.default_rng(n)
    path = workdir / f"map_{n}"
    out: dict[str, Any] = {"objects": n}
    with MapStore.create(path) as store:
        pass
    empty_bytes = graph_bytes(path)
    objs = make_objects(rng, 0, n)
    with MapStore.open(path, write=True) as store:
        t0 = time.perf_counter()
        store.upsert_nodes(objs)
        out["bulk_load_objects_per_s"] = n / (time.perf_counter() - t0)
    out["bytes_graph_empty_map"] = empty_bytes
    out["bytes_per_object_bulk"] = (graph_bytes(path) - empty_bytes) / n
    out["bytes_graph_total"] = graph_bytes(path)
    extra, batch = 500, 50
    more = make_objects(rng, n, extra)
    with MapStore.open(path, write=True) as store:
        t0 = time.perf_counter()
        for s in range(0, extra, batch):
            store.upsert_nodes(more[s : s + batch])
        out[f"insert_objects_per_s_batches_of_{batch}"] = extra / (time.perf_counter() - t0)
    everything = objs + more
    total, free = graph_bytes(path), free_bytes(path)
    out["bytes_graph_after_batches"] = total
    out["bytes_free_pages_after_batches"] = free
    out["bytes_per_object_live_after_batches"] = (total - free - empty_bytes) / len(everything)
    ids = [o.id for o in everything]
    with MapStore.open(path) as store:
        out["search_path"] = "exact" if len(ids) <= EXACT_MAX_ROWS else "hnsw"
        for index, attr, dim in (
            ("object_visual", "visual_feature", 256),
            ("object_text", "text_embedding", 384),
        ):
            mat = np.stack([getattr(o, attr) for o in everything])
            picks = rng.integers(0, len(everything), n_queries)
            queries = mat[picks] + 0.3 * rng.normal(size=(n_queries, dim)).astype(np.float32)
            store.vector_search(index, queries[0], k=10)  # warm caches
            lat, recall = recall_at_10(store, index, mat, ids, queries)
            out[f"{index}_query"] = {**lat, "recall_at_10": recall}
        subset = rng.choice(ids, size=min(500, len(ids)), replace=False).tolist()
        times = []
        for q in queries[: max(n_queries // 4, 10)]:
            t0 = time.perf_counter()
            store.vector_search("object_text", q, k=10, ids=subset)
            times.append(time.perf_counter() - t0)
        out["filtered_500_query"] = percentiles(times)
        times = []
        for i in range(max(n_queries // 4, 10)):
            t0 = time.perf_counter()
            store.text_search(
                "Object", f"{COLOURS[i % len(COLOURS)]} {LABELS[i % len(LABELS)]}", k=10
            )
            times.append(time.perf_counter() - t0)
        out["text_search"] = percentiles(times)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="1k and 10k objects only")
    parser.add_argument("--queries", type=int, default=200)
    parser.add_argument(
        "--out", type=Path, default=Path(__file__).parent / "results" / "store.json"
    )
    args = parser.parse_args()
    sizes = [1_000, 10_000] if args.quick else [1_000, 10_000, 100_000]
    results = []
    with tempfile.TemporaryDirectory(prefix="isg-bench-store-") as tmp:
        for n in sizes:
            t0 = time.perf_counter()
            res = bench_size(n, args.queries, Path(tmp))
            res["wall_s"] = time.perf_counter() - t0
            results.append(res)
            print(f"--- {n} objects ({res['wall_s']:.0f} s)")
            for key, value in res.items():
                print(f"  {key}: {json.dumps(value) if isinstance(value, dict) else value}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"store": results}, indent=2) + "\n", encoding="utf-8")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
