"""Two-stage association of a keyframe's observations with existing object nodes
(paper §III-C "Incremental Geometric-Semantic Association").

Stage 1 matches unambiguous observations: strong 3D overlap and strong visual
similarity. Stage 2 adapts to the object type:

* the same label — semantic consistency first: a relaxed spatial test (boxes touch after
  growing by a margin, or centres close);
* a different label (new to the map, or a synonym) — text-embedding similarity of the
  labels plus a tight distance;
* open-vocabulary / class-agnostic detections — a strict visual threshold plus distance.

Each keyframe is solved as one assignment problem (Hungarian), so two observations from
the same image never fuse into the same node: two chairs side by side stay two chairs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from inherit_sg.mapping.backproject import Observation
from inherit_sg.mapping.tracked import TrackedObject

GENERIC_LABELS = frozenset({"object", "thing", "unknown", "item"})


@dataclass(frozen=True)
class AssociationParams:
    """Thresholds of the association (metres and cosine similarities)."""

    strong_overlap: float = 0.3  # stage 1: intersection / smaller box volume
    strong_visual: float = 0.8  # stage 1: visual cosine similarity
    relaxed_margin: float = 0.15  # stage 2 (known label): grow boxes by this before testing contact
    relaxed_distance: float = 0.5  # stage 2 (known label): or centres this close
    text_similarity: float = 0.75  # stage 2 (new label): label embedding similarity
    new_label_distance: float = 0.4
    strict_visual: float = 0.9  # stage 2 (open vocabulary)
    open_vocab_distance: float = 0.4


@dataclass(frozen=True)
class Match:
    """An observation index matched to a node, with the stage and rule that decided it."""

    observation: int
    node_id: str
    stage: int
    rule: str
    score: float


def _boxes(objs: Sequence[TrackedObject]) -> tuple[np.ndarray, np.ndarray]:
    lo = np.array([o.node.bbox.min for o in objs], dtype=float).reshape(-1, 3)
    hi = np.array([o.node.bbox.max for o in objs], dtype=float).reshape(-1, 3)
    return lo, hi


def _overlap_ratio(lo: np.ndarray, hi: np.ndarray, olo: np.ndarray, ohi: np.ndarray) -> np.ndarray:
    """Intersection volume over the smaller box volume, for one box against many."""
    inter = np.prod(np.clip(np.minimum(hi, ohi) - np.maximum(lo, olo), 0, None), axis=1)
    vol = np.prod(np.maximum(hi - lo, 1e-3), axis=1)
    ovol = float(np.prod(np.maximum(ohi - olo, 1e-3)))
    return np.asarray(inter / np.minimum(vol, ovol))


def _touches(
    lo: np.ndarray, hi: np.ndarray, olo: np.ndarray, ohi: np.ndarray, margin: float
) -> np.ndarray:
    return np.asarray(np.all((lo - margin <= ohi) & (olo - margin <= hi), axis=1))


def associate(
    observations: Sequence[Observation],
    candidates: Sequence[TrackedObject],
    params: AssociationParams,
    label_similarity: Callable[[str, str], float],
) -> list[Match]:
    """Match observations to candidate nodes; unmatched observations become new nodes."""
    if not observations or not candidates:
        return []
    lo, hi = _boxes(candidates)
    centres = (lo + hi) / 2
    feats = [o.node.visual_feature for o in candidates]
    labels = [o.label for o in candidates]
    n_obs, n_nodes = len(observations), len(candidates)
    score = np.full((n_obs, n_nodes), -np.inf)
    rule = np.empty((n_obs, n_nodes), dtype=object)
    for i, obs in enumerate(observations):
        olo, ohi = np.asarray(obs.bbox.min), np.asarray(obs.bbox.max)
        overlap = _overlap_ratio(lo, hi, olo, ohi)
        dist = np.linalg.norm(centres - obs.centroid, axis=1)
        near = dist < 3.0
        if not near.any():
            continue
        if obs.visual_feature is not None:
            vis = np.array([float(obs.visual_feature @ f) if f is not None else 0.0 for f in feats])
        else:
            vis = np.zeros(n_nodes)
        touch = _touches(lo, hi, olo, ohi, params.relaxed_margin)
        generic = obs.label in GENERIC_LABELS
        for j in np.nonzero(near)[0]:
            if overlap[j] >= params.strong_overlap and vis[j] >= params.strong_visual:
                same = 0.5 if labels[j] == obs.label else 0.0
                score[i, j], rule[i, j] = 2.0 + overlap[j] + vis[j] + same, "overlap+visual"
            elif generic or labels[j] in GENERIC_LABELS:
                if vis[j] >= params.strict_visual and dist[j] <= params.open_vocab_distance:
                    score[i, j], rule[i, j] = 1.0 + vis[j] - dist[j], "open-vocabulary visual"
            elif labels[j] == obs.label:
                if touch[j] or dist[j] <= params.relaxed_distance:
                    score[i, j], rule[i, j] = (
                        1.0 + overlap[j] - 0.5 * dist[j],
                        "same label, relaxed distance",
                    )
            elif dist[j] <= params.new_label_distance:
                sim = label_similarity(obs.label, labels[j])
                if sim >= params.text_similarity:
                    score[i, j], rule[i, j] = 0.5 + sim - dist[j], "label embedding + distance"
    allowed = np.isfinite(score)
    if not allowed.any():
        return []
    cost = np.where(allowed, -score, 1e6)
    rows, cols = linear_sum_assignment(cost)
    return [
        Match(
            int(r),
            candidates[c].id,
            1 if rule[r, c] == "overlap+visual" else 2,
            str(rule[r, c]),
            float(score[r, c]),
        )
        for r, c in zip(rows, cols, strict=True)
        if allowed[r, c]
    ]
