"""Placements measured on room floor masks: against a wall, in a corner, in the centre;
rooms without a mask count as unknown."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.model import RoomMask
from inherit_sg.retrieval.constraints import PlacementConstraint
from inherit_sg.retrieval.placement import PlacementMeter, RoomField, wall_grade
from inherit_sg.retrieval.scoring import UNKNOWN_SIM
from inherit_sg.retrieval.snapshot import MapSnapshot
from tests.unit.retrieval_rank import rank, request
from tests.unit.viewer_fixtures import row_snapshot


@pytest.fixture(scope="module")
def meter() -> PlacementMeter:
    return PlacementMeter(row_snapshot())


def test_wall_grade() -> None:
    assert [wall_grade(d) for d in (0.0, 0.25, 0.625, 1.0, 3.0)] == pytest.approx(
        [1.0, 1.0, 0.5, 0.0, 0.0]
    )


@pytest.mark.parametrize(
    ("node", "where", "lo", "hi"),
    [
        ("obj:cb1", "wall", 1.0, 1.0),  # 0.15 m from the east wall
        ("obj:p1", "wall", 1.0, 1.0),
        ("obj:t1", "wall", 0.0, 0.0),  # 2.2 m from the nearest wall
        ("obj:ch2", "wall", 0.0, 0.0),
        ("obj:p1", "corner", 1.0, 1.0),  # 0.1 m from both walls
        ("obj:cb1", "corner", 0.0, 0.0),  # on a wall, 2 m from the next
        ("obj:bin1", "corner", 0.2, 0.4),  # by the north wall, 0.8 m from the west one
        ("obj:t1", "centre", 0.95, 1.0),
        ("obj:ch2", "centre", 0.3, 0.65),
        ("obj:p1", "centre", 0.0, 0.0),
    ],
)
def test_placements(meter: PlacementMeter, node: str, where: str, lo: float, hi: float) -> None:
    sim, why = meter.sim(node, where)
    assert sim is not None and lo <= sim <= hi, why
    assert "room:living" in why


def test_no_mask_no_value(meter: PlacementMeter) -> None:
    assert meter.sim("obj:b1", "wall") == (
        None,
        "not in a room with a floor mask; placement unknown",
    )
    assert meter.sim("room:living", "centre")[0] is None


def test_holes_left_by_furniture_are_filled() -> None:
    cells = np.ones((40, 50), dtype=bool)
    cells[15:25, 20:30] = False  # a 1 m x 1 m block occupied in a free-space mask
    fld = RoomField.of(RoomMask(0.0, 0.0, 0.1, cells))
    assert fld is not None
    # the block's own footprint is 1.5 m from the walls, not on a boundary
    assert fld.wall_distance((2.0, 1.5), (3.0, 2.5)) == pytest.approx(1.5, abs=0.1)
    assert fld.ray((2.0, 1.5), (3.0, 2.5), 0, 1) == pytest.approx(2.0, abs=0.01)
    assert fld.ray((2.0, 1.5), (3.0, 2.5), 1, -1) == pytest.approx(1.5, abs=0.01)
    assert fld.centroid == pytest.approx((2.5, 2.0)) and fld.extent == pytest.approx(5.0)
    assert RoomField.of(RoomMask(0.0, 0.0, 0.1, np.zeros((3, 3), dtype=bool))) is None


def test_scoring_ranks_by_placement() -> None:
    snap: MapSnapshot = row_snapshot()
    ranked, _ = rank(snap, request("trash can", PlacementConstraint(where="corner")))
    assert ranked[0].id == "obj:bin1"  # nearer the north-west corner than bin2
    ranked, _ = rank(snap, request("bench", PlacementConstraint(where="wall")))
    term = ranked[0].terms["c2"]
    assert term.sim == UNKNOWN_SIM and "placement unknown" in term.why


def test_a_kind_that_stands_in_the_middle_prefers_the_middle() -> None:
    from inherit_sg.retrieval.constraints import LabelConstraint
    from inherit_sg.retrieval.plan import usual_placement
    from tests.unit.retrieval_fixtures import floor_snapshot

    asked = (LabelConstraint(id="c1", labels=("kitchen island",), noun="kitchen island"),)
    # the map names no kitchen island: the counter in the middle of the kitchen is meant
    (placed,) = usual_placement(asked, row_snapshot())
    assert isinstance(placed, PlacementConstraint) and placed.where == "centre"
    assert placed.weight < 0.5 and placed.id == "c1~placed"
    # a map that has one: no hint; nor when the request says where it stands itself
    island = floor_snapshot([("i1", "kitchen island", 0.0, 0.0, None)])
    assert usual_placement(asked, island) == ()
    said = (*asked, PlacementConstraint(id="c2", where="wall"))
    assert usual_placement(said, row_snapshot()) == ()
    # kinds with no typical placement get none
    chair = (LabelConstraint(id="c1", labels=("chair",), noun="chair"),)
    assert usual_placement(chair, row_snapshot()) == ()
    # only the kind asked for says where it stands: "light" lists chandeliers among its
    # kinds, yet a light may hang anywhere
    light = (LabelConstraint(id="c1", labels=("light", "chandelier"), noun="light"),)
    assert usual_placement(light, row_snapshot()) == ()
