"""Sample scene graphs for the store tests."""

from __future__ import annotations

import dataclasses

import numpy as np

from inherit_sg.model import (
    AreaNode,
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Keyframe,
    Layer,
    Node,
    NodeId,
    ObjectNode,
    ObjectStatus,
    Pose,
    RoomMask,
    RoomNode,
    SceneGraph,
    make_id,
)

VISUAL_DIM = 256
TEXT_DIM = 384


def unit(rng: np.random.Generator, dim: int) -> np.ndarray:
    """A random float32 vector."""
    return rng.normal(size=dim).astype(np.float32)


def make_object(rng: np.random.Generator, i: int, area: str | None = "area:0") -> ObjectNode:
    """Object ``obj:i`` with vectors, attributes and keyframes."""
    x = float(i)
    return ObjectNode(
        id=make_id(Layer.OBJECT, i),
        label=["chair", "table", "lamp", "sofa"][i % 4],
        position=(x, 1.0, 0.5),
        bbox=BBox3D((x - 0.3, 0.7, 0.0), (x + 0.3, 1.3, 1.0)),
        description=f"a {['red', 'blue', 'green'][i % 3]} object number {i}",
        visual_feature=unit(rng, VISUAL_DIM),
        text_embedding=unit(rng, TEXT_DIM),
        keyframe_ids=[f"kf:{i}", "kf:shared"],
        best_keyframe=f"kf:{i}",
        observation_count=i + 1,
        first_seen=0.5 * i,
        last_seen=0.5 * i + 3.0,
        status=ObjectStatus.MISSING if i % 5 == 4 else ObjectStatus.ACTIVE,
        attributes={"colour": ["red", "blue", "green"][i % 3], "size_m": [0.6, 0.6, 1.0], "n": i},
        area_id=NodeId(area) if area else None,
        room_id=NodeId("room:0"),
        floor_id=NodeId("floor:0"),
    )


def sample_graph(seed: int = 0, n_objects: int = 6) -> SceneGraph:
    """Two floors, two rooms (one with a mask), an area and objects, with every edge
    kind; the change log holds everything as new."""
    rng = np.random.default_rng(seed)
    g = SceneGraph()
    g.add_or_update(FloorNode(make_id(Layer.FLOOR, 0), level=0, label="ground", z_max=2.8))
    g.add_or_update(
        FloorNode(make_id(Layer.FLOOR, 1), level=1, label="upper", z_min=2.8, z_max=5.6)
    )
    mask = RoomMask(-1.0, -2.0, 0.05, rng.random((17, 23)) > 0.4)
    g.add_or_update(
        RoomNode(
            make_id(Layer.ROOM, 0),
            "kitchen",
            floor_id=NodeId("floor:0"),
            position=(1.0, 2.0, 0.0),
            summary="a kitchen with a fridge and a stove",
            mask=mask,
            best_view="kf:0",
            text_embedding=unit(rng, TEXT_DIM),
        )
    )
    g.add_or_update(RoomNode(make_id(Layer.ROOM, 1), "hallway", floor_id=NodeId("floor:0")))
    g.add_or_update(
        AreaNode(
            make_id(Layer.AREA, 0),
            "dining area",
            room_id=NodeId("room:0"),
            position=(1.5, 1.0, 0.0),
            summary="table with chairs for eating",
            text_embedding=unit(rng, TEXT_DIM),
        )
    )
    for i in range(n_objects):
        g.add_or_update(make_object(rng, i))
        g.add_edge(Edge.make(EdgeKind.HAS_OBJECT, "area:0", f"obj:{i}"))
        g.add_edge(Edge.make(EdgeKind.SEEN_IN, f"obj:{i}", f"kf:{i}"))
    g.add_edge(Edge.make(EdgeKind.HAS_ROOM, "floor:0", "room:0"))
    g.add_edge(Edge.make(EdgeKind.HAS_ROOM, "floor:0", "room:1"))
    g.add_edge(Edge.make(EdgeKind.HAS_AREA, "room:0", "area:0"))
    g.add_edge(Edge.make(EdgeKind.CONNECTS, "room:0", "room:1", door=(2.0, 0.5, 0.0), width=0.9))
    g.add_edge(Edge.make(EdgeKind.STAIRS, "floor:0", "floor:1"))
    g.add_edge(Edge.make(EdgeKind.RELATION, "obj:0", "obj:1", predicate="near", confidence=0.8))
    g.add_edge(
        Edge.make(
            EdgeKind.RELATION, "obj:0", "obj:1", predicate="left_of", confidence=0.6, method="geom"
        )
    )
    return g


def keyframe(rng: np.random.Generator, i: int, dim: int = 256, session: str = "s1") -> Keyframe:
    """Keyframe ``kf:i`` with a small fake JPEG and a global feature."""
    pose = np.eye(4)
    pose[:3, 3] = [i, 0.0, 1.5]
    return Keyframe(
        id=f"kf:{i}",
        session_id=session,
        timestamp=0.1 * i,
        pose=Pose.from_matrix(pose),
        floor_id=NodeId("floor:0"),
        frame_index=10 * i,
        global_feature=unit(rng, dim),
        jpeg=bytes([0xFF, 0xD8]) + bytes(rng.integers(0, 255, size=32, dtype=np.uint8)),
        width=64,
        height=48,
    )


def assert_same_node(a: Node, b: Node) -> None:
    """Field-by-field equality, vectors compared exactly."""
    assert type(a) is type(b), (a.id, type(a), type(b))
    for f in dataclasses.fields(a):
        va, vb = getattr(a, f.name), getattr(b, f.name)
        if isinstance(va, np.ndarray) or isinstance(vb, np.ndarray):
            assert va is not None and vb is not None, (a.id, f.name)
            assert np.array_equal(va, vb), (a.id, f.name)
        else:
            assert va == vb, (a.id, f.name, va, vb)


def assert_same_graph(a: SceneGraph, b: SceneGraph) -> None:
    """Same nodes (all fields) and same edges (all properties)."""
    assert {n.id for n in a.nodes()} == {n.id for n in b.nodes()}
    for node in a.nodes():
        assert_same_node(node, b.get(node.id))
    assert {e.key for e in a.edges()} == {e.key for e in b.edges()}
    for edge in a.edges():
        assert b.edge(edge.key) == edge, (edge, b.edge(edge.key))
