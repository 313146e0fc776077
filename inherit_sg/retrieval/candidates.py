"""Candidate generation: run a spec's generation steps against the map store.

Cypher steps select nodes by label or by their place in the hierarchy; the vector and
full-text steps are fallbacks that run only when the steps before them found nothing
(a word the lexicon does not know, a label the map spells differently). Node ids the
store returns but the snapshot does not know (a write raced with the request) are
ignored.

Label selection (``CYPHER_OBJECTS_BY_LABEL``) is answered from the snapshot's label index:
Kuzu has no secondary index, so the statement scans the whole Object table (about 10 ms
at 100k objects) to return what the snapshot of the same map version holds, in the same
order. Other statements run in Kuzu, their ids read through Arrow.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from inherit_sg.errors import MapError
from inherit_sg.mapping.relations import NEAR_GAP
from inherit_sg.retrieval.graph_checks import Landmarks
from inherit_sg.retrieval.plan import CYPHER_OBJECTS_BY_LABEL, NodeSpec, Step
from inherit_sg.retrieval.similarity import TEXT_COS_HI, TEXT_COS_LO, PhraseSimilarity, graded
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.store import MapStore

# Full-text hits count as this much label evidence at most (BM25 is not a similarity).
FULLTEXT_MAX = 0.4
# Candidates the vector and full-text steps return per request.
TEXT_K = 20
# Cosine range of visual features that grades appearance similarity into [0, 1].
VISUAL_COS_LO = 0.3
VISUAL_COS_HI = 0.95


@dataclass
class Candidates:
    """Nodes found for one spec: which steps found each, and text evidence from the
    vector / full-text steps (graded into [0, 1])."""

    found_by: dict[str, list[str]] = field(default_factory=dict)
    text_sim: dict[str, float] = field(default_factory=dict)
    visual_sim: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def add(self, node_id: str, how: str) -> None:
        """Record that ``how`` found ``node_id``."""
        self.found_by.setdefault(node_id, []).append(how)


def _known(snap: MapSnapshot, layer: str, node_id: str) -> bool:
    if layer == "object":
        return node_id in snap.objects
    if layer == "room":
        return node_id in snap.rooms
    return node_id in (snap.areas if layer == "area" else snap.floors)


class CandidateGenerator:
    """Executes generation steps for one map."""

    def __init__(self, store: MapStore, snap: MapSnapshot, sim: PhraseSimilarity) -> None:
        self.store = store
        self.snap = snap
        self.sim = sim

    def generate(self, spec: NodeSpec, landmarks: dict[str, Landmarks] | None = None) -> Candidates:
        """Candidates of ``spec`` (its exclusions removed); ``landmarks`` are the ranked
        landmark candidates a ``neighbours`` step expands."""
        out = Candidates()
        for step in spec.steps:
            if step.op not in ("pinned", "cypher", "neighbours", "visual", "vector", "fulltext"):
                continue
            if step.fallback and out.found_by:
                continue
            before = len(out.found_by)
            if step.op == "neighbours":
                assert step.constraint is not None
                self._neighbours(step, (landmarks or {}).get(step.constraint, ()), out)
            else:
                self._run(step, spec, out)
            out.notes.append(f"{spec.key}: {step.op} found {len(out.found_by) - before} new")
        for node_id in spec.exclude_ids:
            if out.found_by.pop(node_id, None) is not None:
                out.notes.append(f"{spec.key}: dropped {node_id} (excluded by the conversation)")
        if spec.image is not None and out.found_by:
            hits = self.store.vector_search(
                "object_visual", spec.image, len(out.found_by), ids=list(out.found_by)
            )
            out.visual_sim = {
                i: float(graded(1.0 - d, VISUAL_COS_LO, VISUAL_COS_HI)) for i, d in hits
            }
        return out

    def _neighbours(self, step: Step, landmarks: Landmarks, out: Candidates) -> None:
        """Objects next to the landmark candidates: RELATION edges traversed in Kuzu,
        plus objects close enough for a geometric relation where edges are missing."""
        ids = [lid for lid, _ in landmarks]
        if not ids:
            return
        assert step.cypher is not None
        for node_id in self.store.cypher_column(step.cypher, {"landmarks": ids}):
            if str(node_id) in self.snap.objects:
                out.add(str(node_id), "RELATION neighbour")
        snap = self.snap
        for lid in ids:
            j = snap.obj_index.get(lid)
            if j is None:
                continue
            dx = np.maximum(
                0.0, np.maximum(snap.lo[:, 0] - snap.hi[j, 0], snap.lo[j, 0] - snap.hi[:, 0])
            )
            dy = np.maximum(
                0.0, np.maximum(snap.lo[:, 1] - snap.hi[j, 1], snap.lo[j, 1] - snap.hi[:, 1])
            )
            close = (np.hypot(dx, dy) <= NEAR_GAP) & (snap.level == snap.level[j])
            for i in np.flatnonzero(close):
                if i != j and snap.obj_ids[i] not in out.found_by:
                    out.add(snap.obj_ids[i], "close to a landmark")

    def _select(self, step: Step, layer: str) -> list[str]:
        """Ids a ``cypher`` step selects that the snapshot knows, in the store's order."""
        assert step.cypher is not None
        if step.cypher == CYPHER_OBJECTS_BY_LABEL and layer == "object":
            return self.snap.objects_with_labels(list(step.params["labels"]))
        ids = [str(i) for i in self.store.cypher_column(step.cypher, step.params)]
        return [i for i in ids if _known(self.snap, layer, i)]

    def _run(self, step: Step, spec: NodeSpec, out: Candidates) -> None:
        layer = spec.layer
        if step.op == "pinned":
            for node_id in spec.target.node_ids:
                if self.snap.node(node_id) is not None:
                    out.add(node_id, "pinned")
        elif step.op == "cypher":
            assert step.cypher is not None
            found = out.found_by
            for node_id in self._select(step, layer):
                if node_id not in found:
                    found[node_id] = ["cypher"]
        elif step.op == "visual":
            assert spec.image is not None
            for node_id, dist in self.store.vector_search("object_visual", spec.image, TEXT_K):
                if node_id in self.snap.objects:
                    out.add(node_id, f"visual (cos {1.0 - dist:.2f})")
        elif step.op == "vector":
            assert step.index is not None and step.query_text
            vec = self.sim.vectors([step.query_text])[0]
            for node_id, dist in self.store.vector_search(step.index, vec, TEXT_K):
                value = float(graded(1.0 - dist, TEXT_COS_LO, TEXT_COS_HI))
                if value > 0.0 and _known(self.snap, layer, node_id):
                    out.add(node_id, f"vector (cos {1.0 - dist:.2f})")
                    out.text_sim[node_id] = max(out.text_sim.get(node_id, 0.0), value)
        elif step.op == "fulltext":
            assert step.index is not None and step.query_text
            try:
                hits = self.store.text_search(step.index, step.query_text, TEXT_K)
            except MapError as exc:  # a stale or damaged derived index: go on without it
                out.notes.append(f"{step.spec}: full-text search skipped ({exc.message})")
                hits = []
            top = max((s for _, s in hits), default=0.0)
            for node_id, score in hits:
                if top > 0.0 and _known(self.snap, layer, node_id):
                    out.add(node_id, f"full-text (bm25 {score:.2f})")
                    value = FULLTEXT_MAX * score / top
                    out.text_sim[node_id] = max(out.text_sim.get(node_id, 0.0), value)
