"""The viewer: ViewerPose validation, View geometry, and the choice of view in order —
the request's viewpoint, the robot's pose, the keyframe that saw most candidates, the
room's centre."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from inherit_sg.errors import InputError
from inherit_sg.model import Pose
from inherit_sg.retrieval.constraints import Landmark, Target, Viewpoint
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.retrieval.viewer import (
    KeyframeViews,
    View,
    ViewerPose,
    ViewFinder,
    camera_heading,
)
from tests.unit.viewer_fixtures import CHAIRS, camera_pose, load_pose, row_snapshot


@pytest.fixture(scope="module")
def snap() -> MapSnapshot:
    return row_snapshot()


def viewpoint(kind: str, label: str) -> Viewpoint:
    return Viewpoint(kind=kind, landmark=Landmark(target=Target(labels=(label,), noun=label)))


# ------------------------------------------------------------------ ViewerPose
def test_viewer_pose_accepts_numbers_and_heads_by_yaw() -> None:
    pose = ViewerPose((1, 2.5, 0), 90)
    assert pose.position == (1.0, 2.5, 0.0) and pose.yaw_deg == 90.0
    assert pose.forward == pytest.approx((0.0, 1.0))
    assert ViewerPose((0, 0, 0), 450).forward == pytest.approx((0.0, 1.0))
    assert ViewerPose.from_dict(pose.to_dict()) == pose
    assert ViewerPose.parse(" 1, 2.5 ,0, 90") == pose


@pytest.mark.parametrize(
    ("position", "yaw", "field"),
    [
        ((1.0, 2.0), 0.0, "position"),
        ((1.0, 2.0, 3.0, 4.0), 0.0, "position"),
        ("abc", 0.0, "position"),
        ((1.0, math.nan, 0.0), 0.0, "position[1]"),
        ((1.0, 2.0, math.inf), 0.0, "position[2]"),
        ((True, 2.0, 0.0), 0.0, "position[0]"),
        ((1.0, "2", 0.0), 0.0, "position[1]"),
        ((2e6, 0.0, 0.0), 0.0, "position"),
        ((1.0, 2.0, 0.0), "x", "yaw_deg"),
        ((1.0, 2.0, 0.0), math.inf, "yaw_deg"),
        ((1.0, 2.0, 0.0), None, "yaw_deg"),
    ],
)
def test_viewer_pose_validation_names_the_field(position: object, yaw: object, field: str) -> None:
    with pytest.raises(InputError, match=re.escape(field)):
        ViewerPose(position, yaw)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "data",
    [None, [1, 2, 3], {"position": [1, 2, 3]}, {"position": "1,2,3", "yaw_deg": 0}, {"position": [1, 2, 3], "yaw_deg": 0, "pitch": 1}],
)  # fmt: skip
def test_viewer_pose_from_bad_dicts(data: object) -> None:
    with pytest.raises(InputError, match="viewer"):
        ViewerPose.from_dict(data)


@pytest.mark.parametrize("text", ["1,2,3", "1,2,3,4,5", "a,b,c,d", "", "1,2,nan,0"])
def test_viewer_pose_parse_rejects_bad_text(text: str) -> None:
    with pytest.raises(InputError, match="viewer"):
        ViewerPose.parse(text)


# ------------------------------------------------------------------------ View
def test_view_right_lateral_and_depth() -> None:
    view = View((1.0, 1.0), (0.0, 1.0), "robot", "test")  # looking north: east is right
    assert view.right == (1.0, -0.0)
    pts = np.array([[2.0, 1.0], [1.0, 3.0], [0.0, 0.0]])
    assert view.lateral(pts) == pytest.approx([1.0, 0.0, -1.0])
    assert view.depth(pts) == pytest.approx([0.0, 2.0, -1.0])
    assert view.distance(pts) == pytest.approx([1.0, 2.0, math.sqrt(2.0)])


def test_camera_heading_level_and_looking_down() -> None:
    assert camera_heading(camera_pose(0, 0, 30.0)) == pytest.approx(
        (math.cos(math.radians(30)), math.sin(math.radians(30)))
    )
    # straight down, image "up" (-y of the camera) along world +x
    down = np.eye(4)
    down[:3, 0], down[:3, 1], down[:3, 2] = (0, -1, 0), (-1, 0, 0), (0, 0, -1)
    assert camera_heading(Pose.from_matrix(down)) == pytest.approx((1.0, 0.0))


# --------------------------------------------------------------- view choice
def test_viewpoint_facing_looks_from_behind_the_group(snap: MapSnapshot) -> None:
    finder = ViewFinder(
        snap, viewpoint=viewpoint("facing", "window"), viewpoint_marks=[("obj:w1", 1.0)]
    )
    view = finder.view(list(CHAIRS))
    assert view is not None and view.source == "viewpoint"
    assert view.why == "facing window obj:w1"
    assert view.forward == pytest.approx((0.0, 1.0), abs=1e-3)
    # centroid (3, 1.5), spread 1.5, backed off by spread + 1 m
    assert view.position == pytest.approx((3.0, -1.0), abs=1e-2)


def test_viewpoint_from_stands_at_the_landmark(snap: MapSnapshot) -> None:
    finder = ViewFinder(
        snap, viewpoint=viewpoint("from", "door"), viewpoint_marks=[("obj:d1", 1.0)]
    )
    view = finder.view(list(CHAIRS))
    assert view is not None and view.why == "from door obj:d1"
    assert view.position == pytest.approx((0.05, 3.5), abs=1e-6)
    towards = np.array([3.0 - 0.05, 1.5 - 3.5])
    assert view.forward == pytest.approx(tuple(towards / np.linalg.norm(towards)), abs=1e-3)


def test_viewpoint_back_to_looks_away_from_the_landmark(snap: MapSnapshot) -> None:
    finder = ViewFinder(
        snap, viewpoint=viewpoint("back_to", "window"), viewpoint_marks=[("obj:w1", 1.0)]
    )
    view = finder.view(list(CHAIRS))
    assert view is not None and view.why == "back to window obj:w1"
    assert view.position == pytest.approx((3.0, 1.5), abs=1e-6)
    assert view.forward == pytest.approx((0.0, -1.0), abs=1e-3)


def test_seated_looks_the_way_the_seat_faces_into_its_room(snap: MapSnapshot) -> None:
    # "sitting on the cabinet" (against the east wall): looking west, to the room's centre,
    # whatever the group; the chairs' own centroid would say south-west
    finder = ViewFinder(
        snap, viewpoint=viewpoint("seated", "cabinet"), viewpoint_marks=[("obj:cb1", 1.0)]
    )
    view = finder.view(["obj:ch1", "obj:ch2"])
    assert view is not None and view.why == "seated on cabinet obj:cb1, looking into its room"
    assert view.position == pytest.approx((5.7, 2.5), abs=1e-6)
    assert view.forward == pytest.approx((-1.0, 0.0), abs=1e-3)
    assert view.lateral(np.array([[3.0, 4.0]]))[0] > 0  # north is on the right


def test_seated_without_a_room_looks_at_the_group(snap: MapSnapshot) -> None:
    roomless = MapSnapshot(**{**snap.__dict__, "room_of": {}})
    finder = ViewFinder(
        roomless, viewpoint=viewpoint("seated", "door"), viewpoint_marks=[("obj:d1", 1.0)]
    )
    view = finder.view(list(CHAIRS))
    assert view is not None and view.why == "seated door obj:d1"
    towards = np.array([3.0 - 0.05, 1.5 - 3.5])
    assert view.forward == pytest.approx(tuple(towards / np.linalg.norm(towards)), abs=1e-3)


@pytest.mark.parametrize(
    ("quality", "why"),
    [
        # "standing at the door looking at the cabinet": east, not towards the chairs
        (1.0, "at door obj:d1, looking at cabinet obj:cb1"),
        # a weak match of what is looked at ("the headboard") is not used
        (0.1, "from door obj:d1"),
    ],
)
def test_standing_at_a_landmark_looking_at_another(
    snap: MapSnapshot, quality: float, why: str
) -> None:
    vp = Viewpoint(
        kind="from",
        landmark=Landmark(target=Target(labels=("door",), noun="door")),
        toward=Landmark(target=Target(labels=("cabinet",), noun="cabinet")),
    )
    finder = ViewFinder(
        snap, viewpoint=vp, viewpoint_marks=[("obj:d1", 1.0)], toward_marks=[("obj:cb1", quality)]
    )
    view = finder.view(list(CHAIRS))
    assert view is not None and view.why == why
    seen = (5.7, 2.5) if quality == 1.0 else (3.0, 1.5)  # the cabinet, else the chairs
    towards = np.array([seen[0] - 0.05, seen[1] - 3.5])
    assert view.forward == pytest.approx(tuple(towards / np.linalg.norm(towards)), abs=1e-3)


def test_viewpoint_takes_the_nearest_of_equally_good_landmarks(snap: MapSnapshot) -> None:
    marks = [("obj:b1", 1.0), ("obj:cb1", 0.98), ("obj:tv1", 0.5)]  # b1 is farther
    finder = ViewFinder(snap, viewpoint=viewpoint("facing", "thing"), viewpoint_marks=marks)
    view = finder.view(list(CHAIRS))
    assert view is not None and view.why.endswith("obj:cb1")


def test_missing_viewpoint_falls_back_to_the_robot(snap: MapSnapshot) -> None:
    robot = ViewerPose((3.0, -1.0, 1.2), 90.0)
    finder = ViewFinder(snap, viewpoint=viewpoint("facing", "piano"), robot=robot)
    view = finder.view(list(CHAIRS))
    assert view is not None and view.source == "robot"
    assert "no piano found" in view.why and "robot pose at (3.00, -1.00)" in view.why
    assert view.position == (3.0, -1.0) and view.forward == pytest.approx((0.0, 1.0))


def test_keyframe_that_saw_most_of_the_group(snap: MapSnapshot) -> None:
    finder = ViewFinder(snap, keyframes=KeyframeViews(snap, load_pose))
    view = finder.view(list(CHAIRS))
    assert view is not None and view.source == "keyframe"
    assert view.why == "keyframe kf:south, which saw 4 of 4 candidates"
    assert view.position == pytest.approx((3.0, -1.0))
    assert view.forward == pytest.approx((0.0, 1.0), abs=1e-6)


def test_keyframe_poses_are_loaded_once(snap: MapSnapshot) -> None:
    calls: list[str] = []

    def load(kf: str) -> Pose | None:
        calls.append(kf)
        return load_pose(kf)

    views = KeyframeViews(snap, load)
    for group in (list(CHAIRS), list(CHAIRS[:3])):
        ViewFinder(snap, keyframes=views).view(group)
    assert calls == ["kf:south"]
    assert views.seen_by("obj:ch4") == {"kf:south", "kf:north"}


def test_unknown_keyframe_pose_falls_back_to_the_room(snap: MapSnapshot) -> None:
    finder = ViewFinder(snap, keyframes=KeyframeViews(snap, lambda kf: None))
    view = finder.view(list(CHAIRS))
    assert view is not None and view.source == "room"


def test_room_centre_looks_at_the_group() -> None:
    snap = row_snapshot(seen=False)
    finder = ViewFinder(snap, keyframes=KeyframeViews(snap, load_pose))
    view = finder.view(list(CHAIRS))
    assert view is not None and view.source == "room"
    assert view.why == "centre of living room room:living, looking at the candidates"
    assert view.position == pytest.approx((3.0, 2.5))
    assert view.forward == pytest.approx((0.0, -1.0))
    # the table stands at the room's centre: no direction, look along +y
    at_centre = finder.view(["obj:t1"])
    assert at_centre is not None and at_centre.forward == (0.0, 1.0)
    assert finder.view([]) is None


def test_a_standpoint_in_the_room_of_what_is_looked_at_wins() -> None:
    from tests.unit.retrieval_fixtures import floor_snapshot

    # "sitting on the settee in the den looking at the telly": two settees match, only
    # one room has a telly; the other settee is nearer the candidates
    snap = floor_snapshot(
        [
            ("sofa_den", "sofa", 0.0, 0.0, "den"),
            ("sofa_tv", "sofa", 10.0, 0.0, "tv"),
            ("telly", "tv", 12.0, 0.0, "tv"),
            ("cushion_den", "cushion", 1.0, 0.0, "den"),
            ("cushion_tv", "cushion", 9.0, 0.0, "tv"),
        ],
        {"den": ("family room", 0.0), "tv": ("tv room", 10.0)},
    )
    vp = Viewpoint(
        kind="seated",
        landmark=Landmark(target=Target(labels=("sofa",), noun="settee")),
        toward=Landmark(target=Target(labels=("tv",), noun="telly")),
    )
    marks = [("obj:sofa_den", 1.0), ("obj:sofa_tv", 1.0)]
    finder = ViewFinder(
        snap, viewpoint=vp, viewpoint_marks=marks, toward_marks=[("obj:telly", 1.0)]
    )
    view = finder.view(["obj:cushion_den", "obj:cushion_tv"])
    assert view is not None and view.anchor == "obj:sofa_tv"
    assert view.forward == pytest.approx((1.0, 0.0), abs=1e-3)  # towards the telly
    # said nothing about what is looked at: the nearer settee, as before
    plain = ViewFinder(snap, viewpoint=viewpoint("seated", "sofa"), viewpoint_marks=marks)
    near = plain.view(["obj:cushion_den"])
    assert near is not None and near.anchor == "obj:sofa_den"
