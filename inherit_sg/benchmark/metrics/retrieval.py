"""Retrieval accuracy against an SQR-style query set with ground truth.

For each request the answer's position is compared with the ground-truth targets' (any
of them is correct): accuracy within 1 m and within 0.5 m, per category group (A–C
basic spatial, D negation, E descriptive, F ambiguous / functional) and overall, plus
*semantic accuracy*: the answer is one of the target objects (same id on an oracle map;
for an object of a built map, the ground-truth object nearest to it is a target; a room
or area answer is never semantically right).

Two systems are compared in the same run: ours (:class:`QueryEngine`) and the flat
baseline (:class:`FlatBaseline`). Latency is kept per stage.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from inherit_sg.ingest.synthetic.queries import QueryGT
from inherit_sg.ingest.synthetic.scene import ObjectGT, Scene

GROUPS: dict[str, tuple[str, ...]] = {"A-C": ("A", "B", "C"), "D": ("D",), "E": ("E",), "F": ("F",)}
Answer = tuple[str | None, Sequence[float] | None, dict[str, float]]


@dataclass
class Outcome:
    """How one request was answered."""

    id: str
    category: str
    text: str
    answer_id: str | None
    distance: float
    semantic: bool
    timings_ms: dict[str, float] = field(default_factory=dict)

    def within(self, metres: float) -> bool:
        """Whether the answer lies within ``metres`` of a target."""
        return self.distance <= metres


def _box_distance(obj: ObjectGT, p: Sequence[float]) -> float:
    d = [max(lo - v, 0.0, v - hi) for lo, hi, v in zip(obj.bbox_min, obj.bbox_max, p, strict=True)]
    return math.hypot(*d)


class GroundTruth:
    """Lookups over a scene for judging answers."""

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        self.objects = list(scene.objects)
        self.ids = {o.id for o in self.objects}

    def nearest(self, p: Sequence[float]) -> str | None:
        """Id of the ground-truth object whose box is nearest to ``p``."""
        if not self.objects:
            return None
        return min(self.objects, key=lambda o: (_box_distance(o, p), o.id)).id

    def judge(self, q: QueryGT, answer: Answer, strip: Callable[[str], str]) -> Outcome:
        """The outcome of ``answer`` (node id, position, timings) to ``q``."""
        node_id, pos, timings = answer
        if node_id is None or pos is None:
            return Outcome(q.id, q.category, q.text, node_id, math.inf, False, timings)
        dist = min((math.dist(pos, t) for t in q.target_positions), default=math.inf)
        gt_id = strip(node_id)
        built_object = node_id.startswith("obj:") and gt_id not in self.ids
        semantic = gt_id in q.target_ids or (built_object and self.nearest(pos) in q.target_ids)
        return Outcome(q.id, q.category, q.text, node_id, dist, semantic, timings)


def oracle_id(node_id: str) -> str:
    """Ground-truth id of an oracle-map object id ("obj:o12" → "o12")."""
    return node_id.split(":", 1)[1] if node_id.startswith("obj:") else node_id


def evaluate(
    answer: Callable[[str], Answer],
    queries: Iterable[QueryGT],
    scene: Scene,
    strip: Callable[[str], str] = oracle_id,
) -> list[Outcome]:
    """Answer every request with ``answer`` and judge it."""
    truth = GroundTruth(scene)
    return [truth.judge(q, answer(q.text), strip) for q in queries]


def _share(outcomes: list[Outcome], ok: Callable[[Outcome], bool]) -> float:
    return 100.0 * sum(ok(o) for o in outcomes) / len(outcomes) if outcomes else float("nan")


def summarise(outcomes: list[Outcome]) -> dict[str, Any]:
    """Accuracy (%) within 1 m / 0.5 m and semantic, per group, overall (all requests)
    and the mean of the groups; request counts per group."""
    out: dict[str, Any] = {}
    for name, cats in {**GROUPS, "overall": tuple("ABCDEF")}.items():
        sel = [o for o in outcomes if o.category in cats]
        out[name] = {
            "n": len(sel),
            "within_1m": _share(sel, lambda o: o.within(1.0)),
            "within_0.5m": _share(sel, lambda o: o.within(0.5)),
            "semantic": _share(sel, lambda o: o.semantic),
        }
    groups = [out[g] for g in GROUPS if out[g]["n"]]
    out["group_mean"] = {
        k: statistics.fmean(g[k] for g in groups) if groups else float("nan")
        for k in ("within_1m", "within_0.5m", "semantic")
    }
    return out


def latency(outcomes: list[Outcome]) -> dict[str, dict[str, float]]:
    """p50 / p99 / max per stage (ms) over the outcomes' timings."""
    stages = sorted({k for o in outcomes for k in o.timings_ms})
    out: dict[str, dict[str, float]] = {}
    for stage in stages:
        values = sorted(o.timings_ms[stage] for o in outcomes if stage in o.timings_ms)
        out[stage] = {
            "p50": percentile(values, 50),
            "p99": percentile(values, 99),
            "max": values[-1] if values else float("nan"),
        }
    return out


def percentile(sorted_values: Sequence[float], pct: float) -> float:
    """Linear-interpolated percentile of already sorted values."""
    if not sorted_values:
        return float("nan")
    pos = (len(sorted_values) - 1) * pct / 100.0
    lo, hi = math.floor(pos), math.ceil(pos)
    return sorted_values[lo] + (sorted_values[hi] - sorted_values[lo]) * (pos - lo)
