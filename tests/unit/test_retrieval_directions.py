"""Viewer-relative relations (left_of, right_of, in_front_of, behind) decided from box
centres as the viewer sees them; 'facing' keeps the 'near' approximation."""

from __future__ import annotations

import pytest

from inherit_sg.retrieval.constraints import Landmark, RelationConstraint, Target
from inherit_sg.retrieval.directions import directional_all
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.retrieval.viewer import View, ViewerPose
from tests.unit.retrieval_rank import rank, request
from tests.unit.viewer_fixtures import CHAIRS, row_snapshot

FROM_SOUTH = View((3.0, -1.0), (0.0, 1.0), "robot", "south")
FROM_NORTH = View((3.0, 6.0), (0.0, -1.0), "robot", "north")
TABLE = [("obj:t1", 1.0)]


@pytest.fixture(scope="module")
def snap() -> MapSnapshot:
    return row_snapshot()


def test_left_and_right_of_the_table_from_the_south(snap: MapSnapshot) -> None:
    left = directional_all(snap, FROM_SOUTH, list(CHAIRS), "left_of", TABLE)
    right = directional_all(snap, FROM_SOUTH, list(CHAIRS), "right_of", TABLE)
    assert set(left) == {"obj:ch1", "obj:ch2"} and set(right) == {"obj:ch3", "obj:ch4"}
    # ch1's box clears the table's sideways; ch2 overlaps it by a quarter
    assert left["obj:ch1"][0] == pytest.approx(1.0)
    assert 0.3 < left["obj:ch2"][0] < 0.7
    assert "obj:ch1 is 1.50 m left of obj:t1" in left["obj:ch1"][1]


def test_flipping_the_viewer_flips_left_and_right(snap: MapSnapshot) -> None:
    left = directional_all(snap, FROM_NORTH, list(CHAIRS), "left_of", TABLE)
    assert set(left) == {"obj:ch3", "obj:ch4"}
    assert max(left, key=lambda k: left[k][0]) == "obj:ch4"


def test_in_front_of_and_behind(snap: MapSnapshot) -> None:
    ids = [*CHAIRS, "obj:w1", "obj:tv1"]
    front = directional_all(snap, FROM_SOUTH, ids, "in_front_of", TABLE)
    assert front["obj:ch2"][0] == pytest.approx(1.0) and front["obj:ch3"][0] == pytest.approx(1.0)
    assert front["obj:ch1"][0] < front["obj:ch2"][0]  # off to the side
    behind = directional_all(snap, FROM_SOUTH, ids, "behind", TABLE)
    assert "obj:w1" in behind and not set(behind) & set(CHAIRS)
    # from the north the chairs are behind the table
    assert set(directional_all(snap, FROM_NORTH, ids, "behind", TABLE)) >= {"obj:ch2", "obj:ch3"}


def test_far_objects_and_other_rooms_are_not_related(snap: MapSnapshot) -> None:
    right = directional_all(snap, FROM_SOUTH, ["obj:b1", "obj:cb1"], "right_of", TABLE)
    assert set(right) == {"obj:cb1"}


def test_landmark_quality_scales_the_similarity(snap: MapSnapshot) -> None:
    got = directional_all(snap, FROM_SOUTH, ["obj:ch1"], "left_of", [("obj:t1", 0.5)])
    assert got["obj:ch1"][0] == pytest.approx(0.5)


def _relation(predicate: str, label: str) -> RelationConstraint:
    lm = Landmark(target=Target(labels=(label,), noun=label))
    return RelationConstraint(predicate=predicate, landmark=lm)


@pytest.mark.parametrize(
    ("robot", "predicate", "expected"),
    [
        (ViewerPose((3.0, -1.0, 1.0), 90.0), "left_of", "obj:ch1"),
        (ViewerPose((3.0, 6.0, 1.0), -90.0), "left_of", "obj:ch4"),
        (ViewerPose((3.0, -1.0, 1.0), 90.0), "right_of", "obj:ch4"),
        (ViewerPose((3.0, 6.0, 1.0), -90.0), "right_of", "obj:ch1"),
    ],
)
def test_scoring_uses_the_viewer(
    snap: MapSnapshot, robot: ViewerPose, predicate: str, expected: str
) -> None:
    ranked, log = rank(snap, request("chair", _relation(predicate, "table")), robot=robot)
    assert ranked[0].id == expected
    assert ranked[0].terms["c2"].sim == pytest.approx(1.0)
    assert any(line.startswith("viewer: robot pose") for line in log)


def test_facing_keeps_the_near_approximation(snap: MapSnapshot) -> None:
    ranked, _ = rank(
        snap, request("chair", _relation("facing", "table")), robot=ViewerPose((3, -1, 1), 90)
    )
    assert "approximated by 'near'" in ranked[0].terms["c2"].why
