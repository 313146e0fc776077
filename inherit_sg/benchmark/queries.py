"""The request set of a benchmark: the dataset's ``queries.jsonl``, or requests generated
from its ``scene.json`` when it has none; optionally a category-balanced subset."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.synthetic.queries import QueryGT, generate_queries, read_queries
from inherit_sg.ingest.synthetic.scene import Scene

QUERIES_FILE = "queries.jsonl"


@dataclass
class RequestSet:
    """Requests with ground truth and where they came from."""

    queries: list[QueryGT]
    source: str  # "dataset" (queries.jsonl) or "generated" (from scene.json)
    available: int  # requests before any --max-queries cut


def load_scene(dataset: Path) -> Scene:
    """The dataset's ground truth (DatasetError naming the folder when it has none)."""
    if not (dataset / "scene.json").is_file():
        raise DatasetError(f"dataset {dataset}: no scene.json ground truth to benchmark against")
    return Scene.load(dataset)


def balanced_subset(queries: list[QueryGT], limit: int | None) -> list[QueryGT]:
    """At most ``limit`` requests taken round-robin over the categories (in file order
    within each), so a small cut still covers every category."""
    if limit is None or limit >= len(queries):
        return list(queries)
    by_cat: dict[str, list[QueryGT]] = {}
    for q in queries:
        by_cat.setdefault(q.category, []).append(q)
    queues = [by_cat[c] for c in sorted(by_cat)]
    out: list[QueryGT] = []
    depth = 0
    while len(out) < limit:
        for queue in queues:
            if depth < len(queue) and len(out) < limit:
                out.append(queue[depth])
        depth += 1
    return out


def request_set(dataset: Path, scene: Scene, limit: int | None = None) -> RequestSet:
    """The dataset's requests (or generated ones), cut to ``limit`` when given."""
    if (dataset / QUERIES_FILE).is_file():
        queries, source = read_queries(dataset / QUERIES_FILE), "dataset"
    else:
        queries, source = generate_queries(scene, scene.seed or 0), "generated"
    return RequestSet(balanced_subset(queries, limit), source, len(queries))
