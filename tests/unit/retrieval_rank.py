"""Ranking hand-built requests on a snapshot, every object a candidate (candidate
generation against a real store is covered by the integration tests)."""

from __future__ import annotations

from inherit_sg.retrieval.candidates import Candidates
from inherit_sg.retrieval.constraints import Constraint, LabelConstraint, Target, Viewpoint
from inherit_sg.retrieval.graph_checks import GraphChecker, Landmarks
from inherit_sg.retrieval.plan import Compiler, NodeSpec
from inherit_sg.retrieval.query import ParsedQuery, number_constraints
from inherit_sg.retrieval.ranking import rank_spec
from inherit_sg.retrieval.scoring import Scored, Scorer
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.retrieval.viewer import KeyframeViews, ViewerPose
from tests.unit.retrieval_fixtures import hash_similarity


def request(
    label: str,
    *constraints: Constraint,
    viewpoint: Viewpoint | None = None,
    exclude: tuple[str, ...] = (),
) -> ParsedQuery:
    """'the <label>' with ``constraints`` (numbered c2, c3, … after the label)."""
    named = LabelConstraint(labels=(label,), noun=label, text=label)
    return ParsedQuery(
        text=f"the {label} (hand-built)",
        target=Target(labels=(label,), noun=label),
        constraints=number_constraints((named, *constraints)),
        viewpoint=viewpoint,
        exclude_ids=exclude,
    )


def rank(
    snap: MapSnapshot,
    parsed: ParsedQuery,
    *,
    robot: ViewerPose | None = None,
    keyframes: KeyframeViews | None = None,
) -> tuple[list[Scored], list[str]]:
    """Ranked candidates and the trace notes, as the engine would rank them."""
    plan = Compiler(snap, hash_similarity()).compile(parsed)
    scorer = Scorer(snap, GraphChecker(snap), robot=robot, keyframes=keyframes)

    def generate(spec: NodeSpec, marks: dict[str, Landmarks]) -> Candidates:
        cands = Candidates()
        for oid in snap.objects:
            if oid not in spec.exclude_ids:
                cands.add(oid, "test")
        return cands

    log: list[str] = []
    return rank_spec(plan.target, scorer, generate, log), log
