"""Retrieval benchmark: accuracy of the engine vs the flat baseline, and latency by map size.

Accuracy (SQR-style query sets, paper Table I layout): within 1 m / 0.5 m per category
group (A–C, D, E, F), overall and the mean of the groups, plus semantic accuracy, for
ours and the flat baseline in the same run. Oracle maps are built from the ground truth
of freshly generated houses (``--seeds``; tune on other seeds); ``--built MAP:DATASET``
adds maps built from rendered frames (the queries come from the dataset's scene.json).

Latency: maps of about 100, 1k and 10k objects (several houses side by side), requests
from the houses' query sets, verification off; per-stage p50 / p99 on the first pass
(new phrases are embedded) and on a repeat pass (phrases cached).

Run: ``python bench/retrieval.py [--seeds 101,102,103,104,105] [--scales 100,1000,10000]
[--built MAP:DATASET] [--verify] [--no-areas] [--no-verify-segmenter]
[--out bench/results/retrieval.json]`` (``--seeds ""`` / ``--scales ""`` skip a part; the
two ``--no-*`` switches are the ablations of ``retrieval.use_areas`` and
``retrieval.verify_segmenter``).
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.benchmark.metrics.retrieval import Answer, evaluate, latency, summarise
from inherit_sg.config import Config
from inherit_sg.embed import get_text_embedder
from inherit_sg.exchange.scene_truth import scene_to_graph
from inherit_sg.ingest.synthetic.generate import generate_house
from inherit_sg.ingest.synthetic.queries import QueryGT, generate_queries
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.mapping.node_text import embed_nodes
from inherit_sg.model import BBox3D, Edge, Node, ObjectNode, RoomMask, SceneGraph
from inherit_sg.retrieval.baseline import FlatBaseline
from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.store import MapStore

ROOT = Path(__file__).resolve().parents[1]
HOUSE_SPACING = 60.0  # metres between replicated houses


def write_map(graph: SceneGraph, path: Path) -> Path:
    """Embed node texts and write ``graph`` as a new map."""
    embed_nodes(graph, get_text_embedder())
    with MapStore.create(path) as store:
        store.write_changes(graph)
    return path


def engine_for(store: MapStore, args: argparse.Namespace) -> QueryEngine:
    """The engine of an accuracy run, with the ablation switches of the command line."""
    config = Config()
    config.retrieval.use_areas = not args.no_areas
    config.retrieval.verify_segmenter = not args.no_verify_segmenter
    return QueryEngine(store, config)


def run_queries(engine: QueryEngine, queries: list[QueryGT], scene: Scene, verify: bool) -> dict:
    """Ours and the flat baseline on one map."""
    flat = FlatBaseline(engine)

    def ours(text: str) -> Answer:
        r = engine.query(text, verify=verify)
        return r.answer_id, (r.answer or {}).get("position"), r.timings_ms

    def baseline(text: str) -> Answer:
        r = flat.query(text)
        return r.answer_id, (r.answer or {}).get("position"), r.timings_ms

    mine = evaluate(ours, queries, scene)
    theirs = evaluate(baseline, queries, scene)
    return {"ours": mine, "flat": theirs}


def accuracy(args: argparse.Namespace, work: Path) -> dict[str, Any]:
    """Oracle maps of the --seeds houses (and any --built maps)."""
    outcomes: dict[str, dict[str, list]] = {}
    for seed in args.seeds:
        house = generate_house(seed, args.floors)
        queries = generate_queries(house.scene, seed)
        path = write_map(scene_to_graph(house.scene), work / f"oracle-{seed}")
        with MapStore.open(path) as store:
            res = run_queries(engine_for(store, args), queries, house.scene, args.verify)
        for system, outs in res.items():
            outcomes.setdefault("oracle map", {}).setdefault(system, []).extend(outs)
        print(f"seed {seed}: {len(queries)} requests, {len(house.scene.objects)} objects")
    for spec in args.built:
        map_dir, dataset = spec.split(":", 1)
        scene = Scene.load(dataset)
        queries = generate_queries(scene, scene.seed or 0)
        with MapStore.open(map_dir) as store:
            res = run_queries(engine_for(store, args), queries, scene, args.verify)
        for system, outs in res.items():
            outcomes.setdefault("built map", {}).setdefault(system, []).extend(outs)
    return {
        kind: {system: summarise(outs) for system, outs in by_system.items()}
        for kind, by_system in outcomes.items()
    } | {"latency_ms": {kind: latency(by_system["ours"]) for kind, by_system in outcomes.items()}}


def _rename(node_id: str, k: int) -> str:
    prefix, _, rest = node_id.partition(":")
    return f"{prefix}:h{k}_{rest}"


def _shifted(node: Node, k: int, dx: float) -> Node:
    ref = {
        f: _rename(v, k)
        for f in ("room_id", "area_id", "floor_id")
        if isinstance(v := getattr(node, f, None), str)
    }
    changes: dict[str, Any] = {"id": _rename(node.id, k), **ref}
    if hasattr(node, "position"):
        x, y, z = node.position
        changes["position"] = (x + dx, y, z)
    if isinstance(node, ObjectNode):
        lo, hi = np.asarray(node.bbox.min), np.asarray(node.bbox.max)
        shift = np.array([dx, 0.0, 0.0])
        changes["bbox"] = BBox3D(tuple(lo + shift), tuple(hi + shift))
    mask = getattr(node, "mask", None)
    if isinstance(mask, RoomMask):
        changes["mask"] = RoomMask(mask.origin_x + dx, mask.origin_y, mask.resolution, mask.cells)
    return replace(node, **changes)


def side_by_side(graphs: list[SceneGraph], count: int) -> SceneGraph:
    """``count`` houses in a row, copying ``graphs`` round-robin (ids prefixed h0_, h1_…)."""
    out = SceneGraph()
    for k in range(count):
        base = graphs[k % len(graphs)]
        for node in base.nodes():
            out.add_or_update(_shifted(node, k, k * HOUSE_SPACING))
        for e in base.edges():
            out.add_edge(Edge(e.kind, _rename(e.src, k), _rename(e.dst, k), e.props))
    out.flush_changes()
    return out


def latency_by_scale(args: argparse.Namespace, work: Path) -> list[dict[str, Any]]:
    """Per-stage latency on maps of about each --scales objects."""
    houses = [generate_house(s, args.floors) for s in (201, 202, 203, 204, 205)]
    graphs = [scene_to_graph(h.scene) for h in houses]
    per_house = float(np.mean([len(h.scene.objects) for h in houses]))
    texts = [q.text for h in houses for q in generate_queries(h.scene, h.seed, n=60)]
    texts = texts[: args.requests]
    rows = []
    for scale in args.scales:
        count = max(1, round(scale / per_house))
        graph = side_by_side(graphs, count)
        n_obj = sum(1 for _ in graph.objects())
        t0 = time.perf_counter()
        path = write_map(graph, work / f"scale-{scale}")
        build_s = time.perf_counter() - t0
        with MapStore.open(path) as store:
            engine = QueryEngine(store)
            t0 = time.perf_counter()
            engine.snapshot()
            load_s = time.perf_counter() - t0
            passes = {}
            for name in ("first pass", "repeat pass"):
                timings = [engine.query(t, verify=False).timings_ms for t in texts]
                passes[name] = {
                    stage: {
                        "p50": float(np.percentile([t[stage] for t in timings], 50)),
                        "p99": float(np.percentile([t[stage] for t in timings], 99)),
                    }
                    for stage in ("parse", "retrieve", "total")
                }
        rows.append(
            {
                "objects": n_obj,
                "houses": count,
                "requests": len(texts),
                "map_write_s": build_s,
                "snapshot_load_s": load_s,
                **passes,
            }
        )
        print(f"{n_obj} objects: " + json.dumps(passes))
    return rows


def _table(title: str, summaries: dict[str, dict]) -> None:
    groups = ("A-C", "D", "E", "F", "overall", "group_mean")
    print(f"\n{title}")
    print(f"{'system':8s} {'metric':12s} " + " ".join(f"{g:>10s}" for g in groups))
    for system, s in summaries.items():
        for metric in ("within_1m", "within_0.5m", "semantic"):
            vals = " ".join(f"{s[g][metric]:10.1f}" for g in groups)
            print(f"{system:8s} {metric:12s} {vals}")
    ns = summaries[next(iter(summaries))]
    print(f"{'':8s} {'requests':12s} " + " ".join(f"{ns[g].get('n', 0):10d}" for g in groups))


def main() -> None:
    """Run the benchmark and write the JSON report."""
    ap = argparse.ArgumentParser(description=__doc__)
    ints = lambda s: [int(x) for x in s.split(",") if x]  # noqa: E731
    ap.add_argument("--seeds", type=ints, default=[101, 102, 103, 104, 105])
    ap.add_argument("--floors", type=int, default=2)
    ap.add_argument("--scales", type=ints, default=[100, 1000, 10000])
    ap.add_argument("--requests", type=int, default=200, help="requests per latency scale")
    ap.add_argument("--built", action="append", default=[], help="MAP_DIR:DATASET_DIR")
    ap.add_argument("--verify", action="store_true", help="verify answers (accuracy runs)")
    ap.add_argument("--no-areas", action="store_true", help="ablation: no functional areas")
    ap.add_argument(
        "--no-verify-segmenter", action="store_true", help="ablation: verifier without grounding"
    )
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "retrieval.json")
    args = ap.parse_args()
    report: dict[str, Any] = {
        "seeds": args.seeds,
        "floors": args.floors,
        "verify": args.verify,
        "use_areas": not args.no_areas,
        "verify_segmenter": not args.no_verify_segmenter,
        "built": args.built,
    }
    with tempfile.TemporaryDirectory(prefix="isg-bench-") as tmp:
        work = Path(tmp)
        if args.seeds or args.built:
            report["accuracy"] = accuracy(args, work)
            for kind, summaries in report["accuracy"].items():
                if kind != "latency_ms":
                    _table(f"{kind} (accuracy %)", summaries)
        if args.scales:
            report["latency"] = latency_by_scale(args, work)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=2))
    print(f"\nwritten {args.out}")


if __name__ == "__main__":
    main()
