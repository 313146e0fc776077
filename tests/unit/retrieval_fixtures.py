"""Shared pieces of the retrieval tests: a deterministic word-hashing embedder (unit
tests need no model), the oracle scene graph of the hand-built ``small_scene`` and a
helper that writes it as a real map (Kuzu + LanceDB) with real MiniLM embeddings."""

from __future__ import annotations

import hashlib
import re
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from inherit_sg.exchange.scene_truth import scene_to_graph
from inherit_sg.model import (
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    RoomNode,
    SceneGraph,
    make_id,
)
from inherit_sg.retrieval.similarity import PhraseSimilarity
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from tests.fixtures_scenes import small_scene

if TYPE_CHECKING:
    from inherit_sg.store import MapStore

DIM = 384


class HashEmbedder:
    """Bag of hashed words and character trigrams: phrases sharing words or word parts
    get a positive cosine, unrelated ones about zero. Deterministic, instant."""

    name = "hash"
    dim = DIM

    def _vec(self, text: str) -> np.ndarray:
        v = np.zeros(DIM, dtype=np.float32)
        for word in re.findall(r"[a-z0-9]+", text.lower()):
            grams = [word] + [word[i : i + 3] for i in range(max(1, len(word) - 2))]
            for g in grams:
                h = int(hashlib.md5(g.encode()).hexdigest()[:8], 16)
                v[h % DIM] += 1.0 if g == word else 0.5
        n = float(np.linalg.norm(v))
        return v / n if n > 0 else v

    def embed(self, texts: Sequence[str]) -> np.ndarray:
        """(n, DIM) unit vectors."""
        return np.stack([self._vec(t) for t in texts]) if texts else np.zeros((0, DIM))


def small_graph() -> SceneGraph:
    """Oracle scene graph of ``small_scene`` (no embeddings)."""
    return scene_to_graph(small_scene())


def small_snapshot() -> MapSnapshot:
    """Snapshot of :func:`small_graph`."""
    return build_snapshot(small_graph(), (1,))


def floor_snapshot(
    objects: Sequence[tuple[str, str, float, float, str | None]],
    rooms: dict[str, tuple[str, float]] | None = None,
    doors: Sequence[tuple[str, str]] = (),
) -> MapSnapshot:
    """A one-floor snapshot: ``rooms`` as ``key: (label, x of its centre)``, objects as
    ``(key, label, x, y, room key or None)``, each 0.5 m wide and 1 m tall; ``doors``
    are the pairs of room keys that open onto each other."""
    g = SceneGraph()
    floor = FloorNode(make_id(Layer.FLOOR, 0), 0, "ground", 0.0, 2.8)
    g.add_or_update(floor)
    for key, (label, x) in (rooms or {}).items():
        room = RoomNode(make_id(Layer.ROOM, key), label, floor_id=floor.id, position=(x, 1, 0))
        g.add_or_update(room)
        g.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor.id, room.id))
    for a, b in doors:
        g.add_edge(Edge.make(EdgeKind.CONNECTS, make_id(Layer.ROOM, a), make_id(Layer.ROOM, b)))
    for key, label, x, y, room_key in objects:
        g.add_or_update(
            ObjectNode(
                make_id(Layer.OBJECT, key),
                label,
                (x, y, 0.5),
                BBox3D((x - 0.25, y - 0.25, 0.0), (x + 0.25, y + 0.25, 1.0)),
                room_id=make_id(Layer.ROOM, room_key) if room_key else None,
                floor_id=floor.id,
            )
        )
    return build_snapshot(g, (1,))


def hash_similarity() -> PhraseSimilarity:
    """Phrase similarity over :class:`HashEmbedder`."""
    return PhraseSimilarity(HashEmbedder())


def patch_jpeg(colour: tuple[int, int, int]) -> bytes:
    """A 320×240 grey JPEG with a ``colour`` patch in the box (100, 60)–(199, 179)."""
    import cv2

    img = np.full((240, 320, 3), 128, dtype=np.uint8)
    img[60:180, 100:200] = colour
    ok, buf = cv2.imencode(".jpg", img[..., ::-1])
    assert ok
    return buf.tobytes()


def give_best_view(store: MapStore, node_id: str, colour: tuple[int, int, int]) -> None:
    """Store keyframe ``kf:1`` (:func:`patch_jpeg` of ``colour``) and make it the best
    and only view of object ``node_id``."""
    from inherit_sg.model import Keyframe, ObjectNode, Pose

    eye = Pose(tuple(float(v) for v in np.eye(4).ravel()))
    kf = Keyframe(
        "kf:1",
        "s1",
        0.0,
        eye,
        jpeg=patch_jpeg(colour),
        width=320,
        height=240,
        global_feature=np.ones(256, np.float32),
    )
    store.add_keyframes([kf])
    node = store.get_node(node_id)
    assert isinstance(node, ObjectNode)
    node.best_keyframe, node.keyframe_ids = "kf:1", ["kf:1"]
    store.upsert_nodes([node])


def write_small_map(path: Path) -> Path:
    """Create a map of ``small_scene`` with real text embeddings at ``path``."""
    from inherit_sg.embed import get_text_embedder
    from inherit_sg.mapping.node_text import embed_nodes
    from inherit_sg.store import MapStore

    graph = small_graph()
    embed_nodes(graph, get_text_embedder())
    with MapStore.create(path) as store:
        store.write_changes(graph)
    return path
