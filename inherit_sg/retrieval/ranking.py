"""Rank a plan: resolve its landmark specs recursively, then score the target.

The request's viewpoint (the spec under ``VIEWPOINT``, and what the speaker looks at
from there under ``VIEWPOINT_TOWARD``) is resolved first and its landmark candidates are
shared with every spec below it, so a landmark's own ordinal
("the mug on the leftmost table") is seen from the same viewpoint as the target's.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from inherit_sg.retrieval.candidates import Candidates
from inherit_sg.retrieval.graph_checks import Landmarks
from inherit_sg.retrieval.plan import VIEWPOINT_KEYS, NodeSpec
from inherit_sg.retrieval.scoring import Scored, Scorer, landmark_quality

# Candidates of a spec, given its resolved landmarks.
Generate = Callable[[NodeSpec, dict[str, Landmarks]], Candidates]


def rank_spec(
    target: NodeSpec, scorer: Scorer, generate: Generate, log: list[str]
) -> Sequence[Scored]:
    """Ranked candidates of ``target``; candidate and scoring notes go to ``log``."""
    snap = scorer.snap

    def landmark(sub: NodeSpec, shared: dict[str, Landmarks]) -> Landmarks:
        found = landmark_quality(sub, evaluate(sub, shared))
        shown = ", ".join(
            f"{i} {getattr(snap.node(i), 'label', '')} q={q:.2f}" for i, q in found[:5]
        )
        log.append(f"{sub.key}: {len(found)} landmark candidates ({shown or 'none'})")
        return found

    def evaluate(spec: NodeSpec, shared: dict[str, Landmarks]) -> Sequence[Scored]:
        seen = {k: landmark(spec.landmarks[k], {}) for k in VIEWPOINT_KEYS if k in spec.landmarks}
        if seen:
            shared = seen
        marks: dict[str, Landmarks] = {}
        for key, sub in spec.landmarks.items():
            if key not in VIEWPOINT_KEYS:
                marks[key] = landmark(sub, shared)
        marks.update(shared)
        cands = generate(spec, marks)
        log.extend(cands.notes)
        ranked, notes = scorer.score(spec, cands, marks)
        log.extend(notes)
        return ranked

    return evaluate(target, {})
