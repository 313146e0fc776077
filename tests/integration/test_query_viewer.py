"""The query engine on a real map (Kuzu + LanceDB) of the row-of-chairs room, with
requests built by hand (the text parser is covered elsewhere): the robot's pose, the
keyframe that saw the chairs (its pose read from the store), the request's viewpoint,
placements and parts, with the viewer in the trace and the plan."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.mapping.node_text import embed_nodes
from inherit_sg.model import Keyframe
from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    Landmark,
    PlacementConstraint,
    Superlative,
    Target,
    Viewpoint,
)
from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.retrieval.viewer import ViewerPose
from inherit_sg.store import MapStore
from tests.unit.retrieval_fixtures import HashEmbedder
from tests.unit.retrieval_rank import request
from tests.unit.viewer_fixtures import KEYFRAME_POSES, row_graph

LEFTMOST = Superlative(measure="ordinal", ordinal=1, direction="left")


class FixedParser:
    """A parser that answers every text with one hand-built request."""

    name = "rules"

    def __init__(self) -> None:
        self.parsed = request("chair", LEFTMOST)

    def parse(self, text: str) -> ParsedQuery:
        return self.parsed


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("viewer") / "map"
    graph = row_graph()
    embed_nodes(graph, HashEmbedder())
    keyframes = [
        Keyframe(kf, "s1", float(i), pose, global_feature=np.ones(256, np.float32))
        for i, (kf, pose) in enumerate(sorted(KEYFRAME_POSES.items()))
    ]
    with MapStore.create(path) as store:
        store.add_keyframes(keyframes)
        store.write_changes(graph)
    return path


@pytest.fixture()
def engine(map_dir: Path) -> Iterator[tuple[QueryEngine, FixedParser]]:
    parser = FixedParser()
    store = MapStore.open(map_dir)
    yield QueryEngine(store, parser=parser, embedder=HashEmbedder()), parser
    store.close()


def test_robot_pose_decides_left(engine: tuple[QueryEngine, FixedParser]) -> None:
    eng, _ = engine
    south = eng.query("the leftmost chair", verify=False, viewer=ViewerPose((3, -1, 1.2), 90))
    north = eng.query("the leftmost chair", verify=False, viewer=ViewerPose((3, 6, 1.2), -90))
    assert (south.answer_id, north.answer_id) == ("obj:ch1", "obj:ch4")
    assert "robot pose given: (3.00, 6.00, 1.20), heading -90°" in north.trace
    assert any(line.startswith("viewer: robot pose at (3.00, 6.00)") for line in north.trace)


def test_without_a_pose_the_keyframe_is_read_from_the_store(
    engine: tuple[QueryEngine, FixedParser],
) -> None:
    eng, _ = engine
    result = eng.query("the leftmost chair", verify=False, explain=True)
    assert result.answer_id == "obj:ch1", result.trace
    assert "viewer: keyframe kf:south, which saw 4 of 4 candidates (for target c2)" in result.trace
    assert result.explain is not None and "viewer: the robot's pose" in result.explain


def test_the_requests_viewpoint_is_planned_and_scored_first(
    engine: tuple[QueryEngine, FixedParser],
) -> None:
    eng, parser = engine
    tv = Landmark(target=Target(labels=("tv",), noun="tv"))
    parser.parsed = request("chair", LEFTMOST, viewpoint=Viewpoint(kind="facing", landmark=tv))
    result = eng.query("facing the tv, the leftmost chair", verify=False, explain=True)
    assert result.answer_id == "obj:ch4", result.trace
    assert "viewpoint: facing tv" in result.trace
    assert any(line.startswith("viewer: facing tv obj:tv1") for line in result.trace)
    at = next(i for i, line in enumerate(result.trace) if line.startswith("viewpoint: 1 landmark"))
    assert at < next(i for i, line in enumerate(result.trace) if line.startswith("target:"))
    assert result.explain is not None
    assert "[viewpoint] cypher" in result.explain and "viewer: facing tv" in result.explain
    assert result.constraints["viewpoint"]["kind"] == "facing"


def test_placements_and_parts_through_the_engine(
    engine: tuple[QueryEngine, FixedParser],
) -> None:
    eng, parser = engine
    parser.parsed = request("trash can", PlacementConstraint(where="corner"))
    result = eng.query("the bin in the corner", verify=False, explain=True)
    assert result.answer_id == "obj:bin1", result.trace
    assert (
        result.explain is not None
        and "c2 placement in a corner: measure the footprint" in result.explain
    )
    parser.parsed = request("trash can", AttributeConstraint(key="part", value="yellow lid"))
    result = eng.query("the bin with the yellow lid", verify=False)
    assert result.answer_id == "obj:bin1"
    assert result.candidates[0]["scores"]["c2"]["why"] == "description mentions 'lid'"
