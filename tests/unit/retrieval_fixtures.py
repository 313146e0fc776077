"""Shared pieces of the retrieval tests: a deterministic word-hashing embedder (unit
tests need no model), the oracle scene graph of the hand-built ``small_scene`` and a
helper that writes it as a real map (Kuzu + LanceDB) with real MiniLM embeddings."""

from __future__ import annotations

import hashlib
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from inherit_sg.exchange.scene_truth import scene_to_graph
from inherit_sg.model import SceneGraph
from inherit_sg.retrieval.similarity import PhraseSimilarity
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from tests.fixtures_scenes import small_scene

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


def hash_similarity() -> PhraseSimilarity:
    """Phrase similarity over :class:`HashEmbedder`."""
    return PhraseSimilarity(HashEmbedder())


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
