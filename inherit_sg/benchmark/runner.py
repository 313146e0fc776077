"""One benchmark run over one dataset: map (built here or given), requests, accuracy of
ours vs the flat baseline, ablations, mapping, storage and latency, as one JSON-able
dict (the document ``inherit-sg bench`` writes)."""

from __future__ import annotations

import tempfile
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from inherit_sg import __version__
from inherit_sg.benchmark.ablations import run_ablations
from inherit_sg.benchmark.accuracy import accuracy_table, compare
from inherit_sg.benchmark.latency import stage_latency
from inherit_sg.benchmark.mapping_metrics import build_measured, from_sessions, quality
from inherit_sg.benchmark.queries import load_scene, request_set
from inherit_sg.benchmark.storage import storage_breakdown
from inherit_sg.config import Config
from inherit_sg.errors import DatasetError, MapNotFoundError
from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.store import MapStore

Progress = Callable[[str], None]


@dataclass
class BenchOptions:
    """What to measure and on what."""

    dataset: Path
    map_dir: Path | None = None
    config: Config = field(default_factory=Config)
    overrides: list[str] = field(default_factory=list)
    ablations: bool = True
    max_queries: int | None = None


def _silent(_: str) -> None:
    return None


def _map_counts(store: MapStore) -> dict[str, int]:
    nodes = store.stats().nodes
    return {k.lower(): int(v) for k, v in nodes.items() if k != "Session"}


def measure_map(
    opts: BenchOptions, map_dir: Path, mapping: dict[str, Any], progress: Progress
) -> dict[str, Any]:
    """Everything measured on an existing map (``mapping``: the speed figures)."""
    scene = load_scene(opts.dataset)
    requests = request_set(opts.dataset, scene, opts.max_queries)
    progress(f"{len(requests.queries)} requests ({requests.source})")
    out: dict[str, Any] = {
        "queries": {
            "source": requests.source,
            "generated_from_scene": requests.source == "generated",
            "count": len(requests.queries),
            "available": requests.available,
            "by_category": dict(sorted(Counter(q.category for q in requests.queries).items())),
        }
    }
    with MapStore.open(map_dir, config=opts.config) as store:
        out["map_size"] = _map_counts(store)
        progress("mapping quality")
        out["mapping"] = {**mapping, "quality": quality(store, opts.dataset, scene)}
        progress("storage")
        out["storage"] = storage_breakdown(store)
        engine = QueryEngine(store, opts.config)

        def tick(system: str, done: int, total: int) -> None:
            progress(f"{system}: {done}/{total} requests")

        outcomes = compare(engine, requests.queries, scene, tick)
        out["accuracy"] = accuracy_table(outcomes)
        out["latency_ms"] = {system: stage_latency(outs) for system, outs in outcomes.items()}
        if opts.ablations:
            out["ablations"] = run_ablations(
                store,
                opts.config,
                requests.queries,
                scene,
                lambda name: progress(f"ablation: {name}"),
            )
        else:
            out["ablations"] = {"skipped": "--no-ablations"}
    return out


def run_benchmark(opts: BenchOptions, progress: Progress | None = None) -> dict[str, Any]:
    """Run the whole benchmark on ``opts.dataset`` (building a temporary map when no map
    is given) and return the results document."""
    say = progress or _silent
    if not opts.dataset.is_dir():
        raise DatasetError(f"dataset folder not found: {opts.dataset}")
    load_scene(opts.dataset)  # fail before a long build when there is no ground truth
    t0 = time.perf_counter()
    head: dict[str, Any] = {
        "inherit_sg_version": __version__,
        "dataset": str(opts.dataset),
        "dataset_name": opts.dataset.name,
        "config_overrides": list(opts.overrides),
        "max_queries": opts.max_queries,
    }
    if opts.map_dir is not None:
        if not (opts.map_dir / "map.json").is_file():
            raise MapNotFoundError(f"map not found: {opts.map_dir} (no map.json)")
        with MapStore.open(opts.map_dir, config=opts.config) as store:
            mapping = from_sessions(store)
        body = measure_map(opts, opts.map_dir, mapping, say)
        head["map"] = str(opts.map_dir)
    else:
        with tempfile.TemporaryDirectory(prefix="isg-bench-map-") as tmp:
            map_dir = Path(tmp) / "map"
            say(f"building a map of {opts.dataset}")
            mapping = build_measured(opts.dataset, map_dir, opts.config)
            say(f"built in {mapping['build_s']:.1f} s")
            body = measure_map(opts, map_dir, mapping, say)
        head["map"] = "built by the benchmark (temporary)"
    return {**head, **body, "seconds": time.perf_counter() - t0}
