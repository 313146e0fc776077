"""A small living room for the viewer, ordinal, direction, placement and part tests.

Room ``living`` spans x 0–6, y 0–5 (a rectangular floor mask); room ``hall`` (x 6–9)
has no mask. Four chairs stand in a row along x at y = 1.5 (``ch1`` x = 1.5 … ``ch4``
x = 4.5), the table ``t1`` in the middle of the room (3, 2.5), the window ``w1`` on the
north wall, the TV ``tv1`` on the south wall, the door ``d1`` on the west wall, the
cabinet ``cb1`` against the east wall, the plant ``p1`` in the south-west corner, a bin
``bin1`` (grey, "with a yellow lid") and a grey bin ``bin2`` by the north wall, and a
bench ``b1`` in the hall.

Two keyframes saw the chairs: ``kf:south`` from (3, -1) looking north (+y) saw all four;
``kf:north`` from (3, 6) looking south saw two.
"""

from __future__ import annotations

import math

import numpy as np

from inherit_sg.exchange.scene_truth import scene_to_graph
from inherit_sg.ingest.synthetic.scene import FloorGT, ObjectGT, RoomGT, Scene
from inherit_sg.model import Edge, EdgeKind, ObjectNode, Pose, RoomNode, SceneGraph
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot

CHAIRS = ("obj:ch1", "obj:ch2", "obj:ch3", "obj:ch4")

# id, label, room, centre xy, (w, d, h), bottom above the floor, colour
_OBJECTS = (
    ("ch1", "chair", "living", (1.5, 1.5), (0.5, 0.5, 0.9), 0.0, "red"),
    ("ch2", "chair", "living", (2.5, 1.5), (0.5, 0.5, 0.9), 0.0, "red"),
    ("ch3", "chair", "living", (3.5, 1.5), (0.5, 0.5, 0.9), 0.0, "red"),
    ("ch4", "chair", "living", (4.5, 1.5), (0.5, 0.5, 0.9), 0.0, "red"),
    ("t1", "table", "living", (3.0, 2.5), (1.0, 0.6, 0.74), 0.0, "brown"),
    ("w1", "window", "living", (3.0, 4.95), (1.2, 0.1, 1.2), 0.9, "white"),
    ("tv1", "tv", "living", (3.0, 0.1), (1.2, 0.1, 0.7), 0.8, "black"),
    ("d1", "door", "living", (0.05, 3.5), (0.1, 0.9, 2.05), 0.0, "white"),
    ("cb1", "cabinet", "living", (5.7, 2.5), (0.5, 1.0, 0.9), 0.0, "brown"),
    ("p1", "plant", "living", (0.3, 0.3), (0.4, 0.4, 1.0), 0.0, "green"),
    ("bin1", "trash can", "living", (1.0, 4.7), (0.4, 0.4, 0.6), 0.0, "grey"),
    ("bin2", "trash can", "living", (2.0, 4.7), (0.4, 0.4, 0.6), 0.0, "blue"),
    ("b1", "bench", "hall", (7.5, 2.5), (1.2, 0.4, 0.45), 0.0, "brown"),
)


def _rect(x0: float, y0: float, x1: float, y1: float) -> list[list[float]]:
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def row_scene() -> Scene:
    """The ground truth of the room described in the module docstring."""
    scene = Scene(name="row", seed=None)
    scene.floors = [FloorGT(0, 0.0, 3.0)]
    scene.rooms = [
        RoomGT("living", "living room", 0, _rect(0, 0, 6, 5), "living room"),
        RoomGT("hall", "hallway", 0, _rect(6, 0, 9, 5), "hallway"),
    ]
    for n, (oid, label, room, (x, y), (w, d, h), z0, colour) in enumerate(_OBJECTS, start=1):
        scene.objects.append(
            ObjectGT(
                id=oid,
                instance_id=n,
                label=label,
                room_id=room,
                floor=0,
                centroid=[x, y, z0 + h / 2],
                bbox_min=[x - w / 2, y - d / 2, z0],
                bbox_max=[x + w / 2, y + d / 2, z0 + h],
                attributes={"colour": colour},
                structural=label in ("door", "window"),
            )
        )
    return scene


def camera_pose(x: float, y: float, heading_deg: float, z: float = 1.2) -> Pose:
    """An OpenCV camera (x right, y down, z forward) at (x, y, z) looking horizontally
    towards ``heading_deg`` (counter-clockwise from +x)."""
    h = math.radians(heading_deg)
    fwd = np.array([math.cos(h), math.sin(h), 0.0])
    right = np.array([fwd[1], -fwd[0], 0.0])
    down = np.array([0.0, 0.0, -1.0])
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, down, fwd, (x, y, z)
    return Pose.from_matrix(m)


KEYFRAME_POSES = {
    "kf:south": camera_pose(3.0, -1.0, 90.0),
    "kf:north": camera_pose(3.0, 6.0, -90.0),
}
_SEEN = {"kf:south": CHAIRS, "kf:north": ("obj:ch3", "obj:ch4")}


def row_graph(*, seen: bool = True) -> SceneGraph:
    """Oracle graph of :func:`row_scene`: the hall's mask removed, ``bin1`` described
    with its lid, and (``seen``) the SEEN_IN records of the two keyframes."""
    graph = scene_to_graph(row_scene())
    hall = graph.get("room:hall")
    assert isinstance(hall, RoomNode)
    hall.mask = None
    bin1 = graph.get("obj:bin1")
    assert isinstance(bin1, ObjectNode)
    bin1.description = "a grey trash can with a yellow lid, in the living room"
    if seen:
        for kf, ids in _SEEN.items():
            for oid in ids:
                graph.add_edge(Edge.make(EdgeKind.SEEN_IN, oid, kf, label="chair", score=0.9))
    return graph


def row_snapshot(*, seen: bool = True) -> MapSnapshot:
    """Snapshot of :func:`row_graph`."""
    return build_snapshot(row_graph(seen=seen), (1,))


def load_pose(keyframe_id: str) -> Pose | None:
    """The stored pose of a keyframe of this scene (None for others)."""
    return KEYFRAME_POSES.get(keyframe_id)
