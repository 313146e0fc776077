"""Typed model: value types, ids, room masks and the in-memory scene graph."""

from __future__ import annotations

import math

import numpy as np
import pytest

from inherit_sg.errors import FrameError, NodeNotFoundError
from inherit_sg.model import (
    AreaNode,
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Frame,
    Intrinsics,
    Layer,
    ObjectNode,
    Pose,
    RoomMask,
    RoomNode,
    SceneGraph,
    layer_of,
    make_id,
)


def _obj(key: int, label: str = "chair", at: tuple[float, float, float] = (0, 0, 0)) -> ObjectNode:
    return ObjectNode(
        id=make_id(Layer.OBJECT, key),
        label=label,
        position=at,
        bbox=BBox3D.from_center_size(at, (0.5, 0.5, 0.5)),
        keyframe_ids=[f"kf{key}"],
    )


def test_ids_carry_their_layer() -> None:
    assert make_id(Layer.ROOM, 3) == "room:3"
    assert layer_of("obj:12") is Layer.OBJECT
    assert Layer.AREA.table == "Area"
    assert EdgeKind.HAS_OBJECT.endpoints == ("Area", "Object")
    with pytest.raises(ValueError):
        layer_of("kf:1")


def test_pose_rejects_nan_and_non_rigid() -> None:
    m = np.eye(4)
    m[0, 3] = math.nan
    with pytest.raises(FrameError, match="NaN"):
        Pose.from_matrix(m)
    with pytest.raises(FrameError, match="rotation"):
        Pose.from_matrix(np.diag([2.0, 1.0, 1.0, 1.0]))
    with pytest.raises(FrameError, match="4x4"):
        Pose.from_matrix(np.eye(3))


def test_pose_transforms_points() -> None:
    m = np.eye(4)
    m[:3, 3] = [1.0, 2.0, 3.0]
    pose = Pose.from_matrix(m)
    assert np.allclose(pose.transform_points(np.zeros((1, 3))), [[1, 2, 3]])
    assert pose.to_list()[3] == 1.0


def test_intrinsics_validation_and_scaling() -> None:
    k = Intrinsics(640, 480, 320.0, 320.0, 319.5, 239.5)
    half = k.scaled(0.5)
    assert (half.width, half.height, half.fx, half.cx) == (320, 240, 160.0, 159.5)
    assert Intrinsics.from_dict(k.to_dict()) == k
    with pytest.raises(FrameError, match="missing key 'fx'"):
        Intrinsics.from_dict({"width": 1, "height": 1})
    with pytest.raises(FrameError):
        Intrinsics(0, 480, 1, 1, 0, 0)


def test_bbox_geometry() -> None:
    a = BBox3D((0, 0, 0), (2, 2, 2))
    b = BBox3D((1, 1, 1), (3, 3, 3))
    assert a.volume == 8.0
    assert a.intersection_volume(b) == 1.0
    assert a.iou(b) == pytest.approx(1 / 15)
    assert a.union(b) == BBox3D((0, 0, 0), (3, 3, 3))
    assert a.contains((1, 1, 1)) and not a.contains((2.5, 0, 0))
    with pytest.raises(ValueError):
        BBox3D((1, 0, 0), (0, 1, 1))


def test_room_mask_round_trip() -> None:
    cells = np.zeros((7, 11), dtype=bool)
    cells[2:5, 3:9] = True
    mask = RoomMask(-1.0, 2.0, 0.05, cells)
    back = RoomMask.from_bytes(mask.to_bytes())
    assert back == mask
    assert mask.area_m2 == pytest.approx(18 * 0.05**2)
    assert mask.contains_xy(-1.0 + 4 * 0.05 + 0.01, 2.0 + 3 * 0.05 + 0.01)
    assert not mask.contains_xy(-1.0, 2.0)


def test_frame_validation_names_the_problem() -> None:
    k = Intrinsics(4, 3, 2.0, 2.0, 1.5, 1.0)
    good = Frame(
        0, "f0", 0.0, np.zeros((3, 4, 3), np.uint8), np.ones((3, 4), np.float32), Pose.identity(), k
    )
    assert good.validate() is good
    bad = Frame(
        0, "f1", 0.0, np.zeros((4, 4, 3), np.uint8), np.ones((3, 4), np.float32), Pose.identity(), k
    )
    with pytest.raises(FrameError, match=r"'f1'.*intrinsics say 4x3"):
        bad.validate()
    nan_depth = np.ones((3, 4), np.float32)
    nan_depth[0, 0] = np.nan
    with pytest.raises(FrameError, match="NaN"):
        Frame(0, "f2", 0.0, np.zeros((3, 4, 3), np.uint8), nan_depth, Pose.identity(), k).validate()


def _hierarchy() -> SceneGraph:
    g = SceneGraph()
    g.add_or_update(FloorNode(make_id(Layer.FLOOR, 0), level=0))
    g.add_or_update(RoomNode(make_id(Layer.ROOM, 0), "kitchen", floor_id=make_id(Layer.FLOOR, 0)))
    g.add_or_update(AreaNode(make_id(Layer.AREA, 0), "cooking area"))
    g.add_edge(Edge.make(EdgeKind.HAS_ROOM, "floor:0", "room:0"))
    g.add_edge(Edge.make(EdgeKind.HAS_AREA, "room:0", "area:0"))
    for i in range(3):
        g.add_or_update(_obj(i, at=(float(i), 0.0, 0.0)))
        g.add_edge(Edge.make(EdgeKind.HAS_OBJECT, "area:0", f"obj:{i}"))
    g.add_edge(Edge.make(EdgeKind.RELATION, "obj:0", "obj:1", predicate="next to", confidence=0.9))
    g.add_edge(Edge.make(EdgeKind.RELATION, "obj:0", "obj:1", predicate="near", confidence=0.7))
    return g


def test_graph_hierarchy_and_neighbours() -> None:
    g = _hierarchy()
    assert g.parent("obj:1") == "area:0"
    assert g.children("room:0") == ["area:0"]
    assert sorted(g.children("area:0")) == ["obj:0", "obj:1", "obj:2"]
    assert g.neighbours("obj:0", [EdgeKind.RELATION]) == ["obj:1"]
    # two predicates between the same pair are two edges
    assert len(g.out_edges("obj:0", EdgeKind.RELATION)) == 2
    assert len(list(g.nodes(Layer.OBJECT))) == 3
    with pytest.raises(NodeNotFoundError):
        g.get("obj:99")
    with pytest.raises(NodeNotFoundError):
        g.add_edge(Edge.make(EdgeKind.RELATION, "obj:0", "obj:99", predicate="on"))


def test_change_tracking_and_flush() -> None:
    g = _hierarchy()
    first = g.flush_changes()
    assert len(first.new_nodes) == 6 and len(first.new_edges) == 7
    assert g.changes.empty

    obj = g.get("obj:2")
    obj.label = "stool"
    g.touch("obj:2")
    g.remove("obj:1")
    g.add_or_update(_obj(7))
    changes = g.flush_changes()
    assert changes.updated_nodes == {"obj:2"}
    assert changes.removed_nodes == {"obj:1"}
    assert changes.new_nodes == {"obj:7"}
    # removing obj:1 removed its hierarchy edge and both relation edges
    assert ("HAS_OBJECT", "area:0", "obj:1", "") in changes.removed_edges
    assert ("RELATION", "obj:0", "obj:1", "near") in changes.removed_edges


def test_new_then_removed_leaves_no_trace() -> None:
    g = _hierarchy()
    g.flush_changes()
    g.add_or_update(_obj(9))
    g.remove("obj:9")
    assert g.changes.empty


def test_merge_nodes_redirects_edges_and_fuses_observations() -> None:
    g = _hierarchy()
    g.add_edge(Edge.make(EdgeKind.RELATION, "obj:2", "obj:1", predicate="near", confidence=0.5))
    g.flush_changes()
    kept = g.merge_nodes("obj:0", "obj:1")
    assert isinstance(kept, ObjectNode)
    assert "obj:1" not in g
    assert kept.observation_count == 2
    assert kept.keyframe_ids == ["kf0", "kf1"]
    assert kept.bbox.max[0] == pytest.approx(1.25)
    # obj:2 -near-> obj:1 became obj:2 -near-> obj:0; obj:0 -> obj:1 relations became self-loops: dropped
    assert g.neighbours("obj:2", [EdgeKind.RELATION], "out") == ["obj:0"]
    assert not [e for e in g.out_edges("obj:0", EdgeKind.RELATION) if e.dst == "obj:0"]
    changes = g.flush_changes()
    assert "obj:1" in changes.removed_nodes and "obj:0" in changes.updated_nodes
    with pytest.raises(ValueError, match="cannot merge"):
        g.merge_nodes("obj:0", "area:0")


def test_pose_rejects_an_implausible_translation() -> None:
    m = np.eye(4)
    m[0, 3] = 1e308
    with pytest.raises(FrameError, match="implausible"):
        Pose.from_matrix(m)
    m[0, 3] = 9_000.0  # a campus-sized walk is fine
    assert Pose.from_matrix(m).translation[0] == 9_000.0
