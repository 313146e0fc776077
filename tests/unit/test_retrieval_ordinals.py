"""Ordinals, "the middle one" and "closest to you" on a row of four chairs seen from
known poses: flipping the viewer flips the answer."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.retrieval.constraints import Landmark, Superlative, Target, Viewpoint
from inherit_sg.retrieval.ordinals import nth, place
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.retrieval.viewer import KeyframeViews, View, ViewerPose
from tests.unit.retrieval_rank import rank, request
from tests.unit.viewer_fixtures import CHAIRS, load_pose, row_snapshot

SOUTH = ViewerPose((3.0, -1.0, 1.2), 90.0)  # looking north: ch1 on the left
NORTH = ViewerPose((3.0, 6.0, 1.2), -90.0)  # looking south: ch4 on the left
WEST = ViewerPose((-1.0, 1.5, 1.2), 0.0)  # looking east along the row: ch1 in front


@pytest.fixture(scope="module")
def snap() -> MapSnapshot:
    return row_snapshot()


def ordinal(k: int, direction: str | None = None) -> Superlative:
    return Superlative(measure="ordinal", ordinal=k, direction=direction)


def top(snap: MapSnapshot, sup: Superlative, **kwargs: object) -> str:
    ranked, _ = rank(snap, request("chair", sup), **kwargs)  # type: ignore[arg-type]
    return ranked[0].id


@pytest.mark.parametrize(
    ("sup", "robot", "expected"),
    [
        (ordinal(1, "left"), SOUTH, "obj:ch1"),
        (ordinal(1, "left"), NORTH, "obj:ch4"),
        (ordinal(3, "left"), SOUTH, "obj:ch3"),
        (ordinal(3, "left"), NORTH, "obj:ch2"),
        (ordinal(1, "right"), SOUTH, "obj:ch4"),
        (ordinal(2, "right"), NORTH, "obj:ch2"),
        (ordinal(-1, "left"), SOUTH, "obj:ch4"),
        (ordinal(1, "front"), WEST, "obj:ch1"),
        (ordinal(1, "back"), WEST, "obj:ch4"),
        (ordinal(2), WEST, "obj:ch2"),
        (Superlative(measure="closest"), WEST, "obj:ch1"),
        (Superlative(measure="farthest"), WEST, "obj:ch4"),
    ],
)
def test_position_seen_from_the_robot(
    snap: MapSnapshot, sup: Superlative, robot: ViewerPose, expected: str
) -> None:
    assert top(snap, sup, robot=robot) == expected


def test_others_fall_off_with_rank_distance(snap: MapSnapshot) -> None:
    ranked, log = rank(snap, request("chair", ordinal(1, "left")), robot=SOUTH)
    sims = {c.id: c.terms["c2"].sim for c in ranked if c.id in CHAIRS}
    assert sims == pytest.approx(
        {"obj:ch1": 1.0, "obj:ch2": 0.25, "obj:ch3": 0.5 / 3, "obj:ch4": 0.125}
    )
    assert ranked[0].terms["c2"].why.startswith("#1 of 4 by lateral (-1.50 m)")
    assert "viewer: robot pose at (3.00, -1.00), heading 90° (for target c2)" in log


def test_an_ordinal_beyond_the_tier_takes_the_last(snap: MapSnapshot) -> None:
    ranked, log = rank(snap, request("chair", ordinal(6, "left")), robot=SOUTH)
    assert ranked[0].id == "obj:ch4"
    assert any("only 4 candidate(s) in the tier for the 6th from the left" in n for n in log)


def test_middle_of_an_odd_and_an_even_row(snap: MapSnapshot) -> None:
    middle = Superlative(measure="middle")
    odd, _ = rank(snap, request("chair", middle, exclude=("obj:ch4",)), robot=SOUTH)
    assert odd[0].id == "obj:ch2"
    # four chairs: ch2 and ch3 are central; the one nearer the viewer scores best
    for robot, first, second in (
        (ViewerPose((2.0, -1.0, 1.0), 90.0), "obj:ch2", "obj:ch3"),
        (ViewerPose((4.0, -1.0, 1.0), 90.0), "obj:ch3", "obj:ch2"),
    ):
        ranked, _ = rank(snap, request("chair", middle), robot=robot)
        sims = {c.id: c.terms["c2"].sim for c in ranked}
        assert [c.id for c in ranked[:2]] == [first, second]
        assert sims[first] == 1.0 and sims[second] == pytest.approx(0.9)
        assert sims["obj:ch1"] < 0.5 and sims["obj:ch4"] < 0.5


def test_keyframe_view_when_no_pose_is_given(snap: MapSnapshot) -> None:
    views = KeyframeViews(snap, load_pose)
    ranked, log = rank(snap, request("chair", ordinal(1, "left")), keyframes=views)
    assert ranked[0].id == "obj:ch1"
    assert "viewer: keyframe kf:south, which saw 4 of 4 candidates (for target c2)" in log


def _viewpoint(kind: str, label: str) -> Viewpoint:
    return Viewpoint(kind=kind, landmark=Landmark(target=Target(labels=(label,), noun=label)))


@pytest.mark.parametrize(
    ("kind", "label", "sup", "expected"),
    [
        ("facing", "window", ordinal(1, "left"), "obj:ch1"),
        ("back_to", "window", ordinal(1, "left"), "obj:ch4"),
        ("facing", "tv", ordinal(1, "left"), "obj:ch4"),
        ("from", "door", ordinal(1, "front"), "obj:ch1"),
        ("facing", "door", ordinal(1, "front"), "obj:ch4"),
    ],
)
def test_the_requests_viewpoint_wins_over_the_robot(
    snap: MapSnapshot, kind: str, label: str, sup: Superlative, expected: str
) -> None:
    parsed = request("chair", sup, viewpoint=_viewpoint(kind, label))
    ranked, log = rank(snap, parsed, robot=NORTH)  # the robot would see it the other way
    assert ranked[0].id == expected, log
    assert any(line.startswith(f"viewer: {kind.replace('_', ' ')} {label}") for line in log)
    assert any(line.startswith("viewpoint: ") and "landmark candidates" in line for line in log)


def test_ordinal_from_a_landmark_counts_outwards_from_it(snap: MapSnapshot) -> None:
    door = Landmark(target=Target(labels=("door",), noun="door"))
    sup = Superlative(measure="ordinal", ordinal=2, landmark=door)
    assert top(snap, sup, robot=NORTH) == "obj:ch2"


def test_place_directly() -> None:
    view = View((0.0, 0.0), (0.0, 1.0), "robot", "test")
    xy = np.array([[1.0, 2.0], [-1.0, 2.0], [0.0, 2.0]])
    got = place(Superlative(measure="middle"), ["a", "b", "c"], xy, view)
    assert got.sims == pytest.approx([0.25, 0.25, 1.0]) and got.note is None
    assert [nth(k) for k in (1, 2, 3, 4, 11, 22, -1, -2)] == [
        "1st", "2nd", "3rd", "4th", "11th", "22nd", "last", "2nd from last"
    ]  # fmt: skip
