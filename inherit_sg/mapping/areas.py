"""Functional areas (L2): spatial clusters of a room's objects, named by what they hold
(paper §III-B: "objects are spatially clustered into functional area nodes ... an LLM
then processes the textual semantics of these clusters to derive functional labels").

Clustering is single-linkage on the horizontal gap between object footprints; objects
standing on another object always join its cluster. The offline labeller scores each
rule of the area vocabulary (``areas.toml``, :func:`inherit_sg.vocab.areas.area_rules`)
by the labels present.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

from inherit_sg.model import ObjectNode
from inherit_sg.vocab.areas import area_rules
from inherit_sg.wording import with_article

CLUSTER_GAP = 0.8


def cluster_objects(
    objects: Sequence[ObjectNode],
    gap: float = CLUSTER_GAP,
    compatible: np.ndarray | None = None,
) -> list[list[ObjectNode]]:
    """Group objects whose footprints come within ``gap`` metres (transitively); with
    ``compatible`` (an n × n boolean matrix), only compatible pairs link."""
    n = len(objects)
    if n == 0:
        return []
    lo = np.array([o.bbox.min for o in objects], dtype=float)
    hi = np.array([o.bbox.max for o in objects], dtype=float)
    dx = np.maximum(0, np.maximum(lo[:, None, 0] - hi[None, :, 0], lo[None, :, 0] - hi[:, None, 0]))
    dy = np.maximum(0, np.maximum(lo[:, None, 1] - hi[None, :, 1], lo[None, :, 1] - hi[:, None, 1]))
    linked = np.hypot(dx, dy) <= gap
    if compatible is not None:
        linked &= compatible
    _, labels = connected_components(csr_matrix(linked), directed=False)
    groups: dict[int, list[ObjectNode]] = {}
    for obj, lab in zip(objects, labels, strict=True):
        groups.setdefault(int(lab), []).append(obj)
    # stable order: by the smallest object id number in each group
    return sorted(groups.values(), key=lambda g: min(o.id for o in g))


def label_area(labels: Sequence[str]) -> str:
    """Functional label of a cluster from its object labels (offline rules)."""
    present = Counter(labels)
    best, best_score = "", 0.0
    for name, (anchors, support) in area_rules().items():
        score = 2.0 * sum(present[a] > 0 for a in anchors) + sum(present[s] > 0 for s in support)
        if sum(present[a] > 0 for a in anchors) == 0:
            score *= 0.25
        if score > best_score:
            best, best_score = name, score
    if best_score >= 2.0:
        return best
    dominant = present.most_common(1)[0][0] if present else "open"
    return f"{dominant} area"


def summarise_area(label: str, labels: Sequence[str]) -> str:
    """One-sentence summary listing what the area holds."""
    counts = Counter(labels)
    parts = [
        f"{n} {lab}s" if n > 1 else f"a {lab}"
        for lab, n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))
    ]
    if not parts:
        return f"An empty {label}."
    listing = parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]
    return f"{with_article(label, capital=True)} with {listing}."
