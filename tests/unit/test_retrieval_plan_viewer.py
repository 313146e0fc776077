"""Plans of requests with a viewpoint, viewer-relative constraints and placements: the
viewpoint's landmark is compiled like a relation's and runs first, the viewer and the
placement steps show in ``--explain``."""

from __future__ import annotations

from inherit_sg.retrieval.constraints import (
    LabelConstraint,
    Landmark,
    PlacementConstraint,
    RelationConstraint,
    Superlative,
    Target,
    Viewpoint,
)
from inherit_sg.retrieval.plan import VIEWPOINT, Compiler, QueryPlan, needs_viewer
from inherit_sg.retrieval.query import ParsedQuery
from tests.unit.retrieval_fixtures import hash_similarity
from tests.unit.retrieval_rank import request
from tests.unit.viewer_fixtures import row_snapshot


def compile_request(parsed: ParsedQuery) -> QueryPlan:
    return Compiler(row_snapshot(), hash_similarity()).compile(parsed)


def _landmark(label: str, *constraints: LabelConstraint) -> Landmark:
    return Landmark(target=Target(labels=(label,), noun=label), constraints=constraints)


def test_viewpoint_is_a_landmark_spec_compiled_first() -> None:
    table = RelationConstraint(predicate="left_of", landmark=_landmark("table"))
    vp = Viewpoint(kind="from", landmark=_landmark("door", LabelConstraint(labels=("door",))))
    plan = compile_request(request("chair", table, viewpoint=vp))
    target = plan.target
    assert list(target.landmarks) == [VIEWPOINT, "c2"]
    sub = target.landmarks[VIEWPOINT]
    assert sub.key == VIEWPOINT and sub.viewpoint is None
    assert [c.id for c in sub.constraints] == ["v1"]  # unnumbered: numbered here
    assert sub.matches["v1"]  # resolved against the map like any landmark
    assert target.viewpoint == vp and target.landmarks["c2"].viewpoint == vp
    assert plan.steps[0].spec == VIEWPOINT
    text = plan.explain()
    assert "[target] viewer: from door (candidates of viewpoint): stand at the best door" in text
    assert "compare box centres with the candidates of c2.landmark as the viewer sees" in text


def test_viewer_and_placement_steps() -> None:
    plan = compile_request(
        request("chair", Superlative(measure="middle"), PlacementConstraint(where="wall"))
    )
    ops = [s.op for s in plan.target.steps]
    assert ops.index("viewer") < ops.index("superlative") and "placement" in ops
    text = plan.explain()
    assert "[target] viewer: the robot's pose when the request gives one" in text
    assert "c3 placement against a wall: measure the footprint" in text
    assert "by position as the viewer sees it" in text


def test_which_specs_need_a_viewer() -> None:
    def needs(*cons: object) -> bool:
        return needs_viewer(compile_request(request("chair", *cons)).target)  # type: ignore[arg-type]

    assert needs(Superlative(measure="ordinal", ordinal=2))
    assert needs(Superlative(measure="closest"))
    assert needs(RelationConstraint(predicate="behind", landmark=_landmark("table")))
    assert not needs(Superlative(measure="closest", landmark=_landmark("table")))
    assert not needs(RelationConstraint(predicate="near", landmark=_landmark("table")))
    assert not needs(PlacementConstraint(where="corner"))
    plan = compile_request(request("chair", PlacementConstraint(where="corner")))
    assert "viewer" not in [s.op for s in plan.target.steps]
