"""Row codecs of nodes and edges (no database)."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.errors import InputError
from inherit_sg.model import Edge, EdgeKind, Pose, Session
from inherit_sg.store import codec, edges
from tests.integration.store_data import assert_same_node, keyframe, sample_graph


def test_nodes_round_trip_through_rows() -> None:
    graph = sample_graph()
    for node in graph.nodes():
        row = codec.node_row(node)
        assert set(row) == set(codec.columns(node.layer.table))
        back = codec.node_from_row(node.layer.table, row)
        for attr in ("visual_feature", "text_embedding"):  # vectors live in their own tables
            if hasattr(node, attr):
                setattr(back, attr, getattr(node, attr))
        assert_same_node(node, back)
    table = codec.node_table("Object", list(graph.objects()))
    assert table.num_rows == 6 and table.schema.field("keyframe_ids").type.value_type == "string"


def test_attributes_must_be_json() -> None:
    obj = next(sample_graph().objects())
    obj.attributes = {"np": np.float32(1.5), "arr": np.arange(2), "bad": object()}
    with pytest.raises(InputError, match=f"attributes of {obj.id}"):
        codec.node_row(obj)
    obj.attributes.pop("bad")
    assert codec.node_row(obj)["attributes"] == '{"arr": [0, 1], "np": 1.5}'


def test_keyframes_and_sessions_round_trip() -> None:
    kf = keyframe(np.random.default_rng(0), 3)
    back = codec.keyframe_from_row(codec.keyframe_row(kf))
    assert back.pose == kf.pose and back.frame_index == 30 and back.jpeg is None
    assert isinstance(back.pose, Pose)
    s = Session("session:1", "run", started=1.0, finished=None, dataset="d", frames=3)
    row = codec.session_row(s)
    assert row["label"] == "run" and codec.session_from_row(row) == s


def test_edges_round_trip_and_identity() -> None:
    rel = Edge.make(EdgeKind.RELATION, "obj:1", "obj:2", predicate="on", confidence=0.5, k=[1, 2])
    row = edges.edge_row(rel)
    assert row["predicate"] == "on" and row["props"] == '{"k": [1, 2]}'
    assert edges.edge_from_row(EdgeKind.RELATION, row) == rel
    door = Edge.make(EdgeKind.CONNECTS, "room:1", "room:2", door=np.array([1.0, 2.0, 0.0]))
    back = edges.edge_from_row(EdgeKind.CONNECTS, edges.edge_row(door))
    assert back.prop("door") == (1.0, 2.0, 0.0) and back.key == door.key
    plain = Edge.make(EdgeKind.HAS_ROOM, "floor:0", "room:1")
    assert edges.edge_row(plain)["props"] is None
    assert edges.edge_from_row(EdgeKind.HAS_ROOM, edges.edge_row(plain)) == plain
    groups = edges.dedupe(
        [
            rel,
            Edge.make(EdgeKind.RELATION, "obj:1", "obj:2", predicate="near"),
            Edge.make(EdgeKind.RELATION, "obj:1", "obj:2", predicate="on", confidence=0.9),
            plain,
        ]
    )
    assert len(groups[EdgeKind.RELATION]) == 2 and len(groups[EdgeKind.HAS_ROOM]) == 1
    assert {e.prop("confidence") for e in groups[EdgeKind.RELATION]} == {0.9, None}
