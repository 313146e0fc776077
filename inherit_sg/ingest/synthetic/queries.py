"""An SQR-style query set with verified answer sets (``queries.jsonl``, DESIGN.md §4).

Categories follow HM3DSem-SQR (spec §IV-A): A–C basic spatial relations (A: in a room or
on a floor; B: relative to one landmark; C: chained constraints across levels), D
negation, E descriptive (colour, material, size, superlatives), F ambiguous or implicit
(functions: "somewhere to sit near the TV"). Shares match the paper's (``PAPER_SHARES``).

Every query carries its structured form (``gt_constraints``, an ``ObjectSpec``) and its
answer set is exactly ``truth.evaluate(scene, gt_constraints)``: all acceptable targets
with their centroids. Answer sets hold 1–3 objects, except a few A requests scoped by a
floor only ("a chair on the second floor", up to ``MAX_FLOOR_ANSWERS``). A negation
always excludes something: without its negated constraint the answer set is larger.
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from inherit_sg.ingest.synthetic.jsonl import read_jsonl, write_jsonl
from inherit_sg.ingest.synthetic.query_conversations import (
    CONVERSATIONS_FILE,
    ConversationGT,
    TurnGT,
    generate_conversations,
    read_conversations,
    write_conversations,
)
from inherit_sg.ingest.synthetic.query_mining import SceneFacts
from inherit_sg.ingest.synthetic.query_selection import (
    Candidate,
    collect,
    fit_quotas,
    select_and_render,
)
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.ingest.synthetic.truth import SceneIndex

__all__ = [
    "CONVERSATIONS_FILE",
    "PAPER_SHARES",
    "QUERIES_FILE",
    "ConversationGT",
    "QueryGT",
    "TurnGT",
    "category_shares",
    "default_query_count",
    "generate_conversations",
    "generate_queries",
    "read_conversations",
    "read_queries",
    "write_conversations",
    "write_queries",
]

QUERIES_FILE = "queries.jsonl"
PAPER_SHARES = {"A-C": 0.404, "D": 0.268, "E": 0.100, "F": 0.228}
CATEGORIES = ("A", "B", "C", "D", "E", "F")


@dataclass
class QueryGT:
    """One ground-truth request: any of ``target_ids`` is a correct answer."""

    id: str
    text: str
    category: str
    target_ids: list[str]
    target_positions: list[list[float]]
    subcategory: str = ""
    template: str = ""
    gt_constraints: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """The ``queries.jsonl`` line (contract fields first)."""
        return {
            "id": self.id,
            "text": self.text,
            "category": self.category,
            "target_ids": list(self.target_ids),
            "target_positions": [list(p) for p in self.target_positions],
            "subcategory": self.subcategory,
            "template": self.template,
            "gt_constraints": self.gt_constraints,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> QueryGT:
        """Inverse of :meth:`to_dict`; only the contract fields are required."""
        category = str(data["category"])
        if category not in CATEGORIES:
            raise ValueError(f"category {category!r} is not one of {CATEGORIES}")
        ids = [str(x) for x in data["target_ids"]]
        positions = [[float(v) for v in p] for p in data["target_positions"]]
        if len(ids) != len(positions) or any(len(p) != 3 for p in positions):
            raise ValueError("target_positions must hold one [x, y, z] per target id")
        return cls(
            id=str(data["id"]),
            text=str(data["text"]),
            category=category,
            target_ids=ids,
            target_positions=positions,
            subcategory=str(data.get("subcategory", "")),
            template=str(data.get("template", "")),
            gt_constraints=dict(data.get("gt_constraints", {})),
        )


def default_query_count(scene: Scene) -> int:
    """Three requests per non-structural object (at least 20)."""
    return max(20, 3 * sum(1 for o in scene.objects if not o.structural))


def generate_queries(scene: Scene, seed: int, n: int | None = None) -> list[QueryGT]:
    """Up to ``n`` verified requests (default :func:`default_query_count`), deterministic.

    Fewer come back when the scene cannot support ``n`` distinct requests at the paper's
    category shares; the shares are kept either way.
    """
    rng = random.Random(seed)
    index = SceneIndex(scene)
    facts = SceneFacts(scene, index, rng)
    wanted = default_query_count(scene) if n is None else n
    pools = collect(facts, fit_quotas(wanted, None))
    chosen = select_and_render(pools, fit_quotas(wanted, pools), rng)
    rng.shuffle(chosen)
    return [_to_query(i + 1, c) for i, c in enumerate(chosen)]


def _to_query(number: int, cand: Candidate) -> QueryGT:
    return QueryGT(
        id=f"q{number:04d}",
        text=cand.text,
        category=cand.category,
        target_ids=[o.id for o in cand.answer],
        target_positions=[[float(v) for v in o.centroid] for o in cand.answer],
        subcategory=cand.subcategory,
        template=cand.template,
        gt_constraints=cand.spec.to_dict(),
    )


def category_shares(queries: list[QueryGT]) -> dict[str, float]:
    """Fraction of queries per category "A"–"F", plus "A-C" for the three together."""
    total = max(1, len(queries))
    shares = {c: sum(1 for q in queries if q.category == c) / total for c in CATEGORIES}
    shares["A-C"] = shares["A"] + shares["B"] + shares["C"]
    return shares


def write_queries(path: str | Path, queries: list[QueryGT]) -> Path:
    """Write ``queries`` as JSON lines to ``path`` (a file, or a folder → queries.jsonl)."""
    return write_jsonl(path, QUERIES_FILE, (x.to_dict() for x in queries))


def read_queries(path: str | Path) -> list[QueryGT]:
    """Read a ``queries.jsonl`` file (or the one in a folder)."""
    return read_jsonl(path, QUERIES_FILE, QueryGT.from_dict, "query")
