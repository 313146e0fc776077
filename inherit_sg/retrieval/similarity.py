"""Phrase similarity for scoring: cosine of sentence embeddings, graded into [0, 1].

Short phrases (labels, room and area names, function phrases) repeat across requests,
and the text embedder caches every string it has seen, so after warm-up a request costs
a few dictionary lookups and one small matrix product here.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

import numpy as np

# Cosine of MiniLM embeddings at which two labels start to count as related, and at
# which they count as the same thing ("mug"/"bowl" ≈ 0.37, "chair"/"armchair" ≈ 0.73).
LABEL_COS_LO = 0.55
LABEL_COS_HI = 0.95
# Cosine range for longer texts (a phrase against a node's label + description).
TEXT_COS_LO = 0.35
TEXT_COS_HI = 0.75


class Embedder(Protocol):
    """The part of the text embedder retrieval needs."""

    def embed(self, texts: Sequence[str]) -> np.ndarray:
        """(n, dim) unit vectors."""
        ...


def graded(cos: float | np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Cosine mapped linearly from ``[lo, hi]`` onto ``[0, 1]`` (clipped)."""
    return np.clip((np.asarray(cos, dtype=float) - lo) / (hi - lo), 0.0, 1.0)


class PhraseSimilarity:
    """Cosine similarities between phrases, through a (caching) text embedder."""

    def __init__(self, embedder: Embedder) -> None:
        self.embedder = embedder
        self._fixed: dict[str, tuple[tuple[str, ...], np.ndarray]] = {}

    def fixed_vectors(self, key: str, texts: Sequence[str]) -> np.ndarray:
        """Unit vectors of a list of texts that does not change between requests (the
        vocabulary's phrasings), stacked once per ``key`` and kept while the list stays
        the same."""
        wanted = tuple(texts)
        hit = self._fixed.get(key)
        if hit is None or hit[0] != wanted:
            hit = (wanted, self.vectors(wanted))
            self._fixed[key] = hit
        return hit[1]

    def vectors(self, texts: Sequence[str]) -> np.ndarray:
        """Unit vectors of ``texts`` (empty input gives a (0, 0) array)."""
        if not texts:
            return np.zeros((0, 0), dtype=np.float32)
        return np.asarray(self.embedder.embed(list(texts)), dtype=np.float32)

    def matrix(self, queries: Sequence[str], texts: Sequence[str]) -> np.ndarray:
        """(len(queries), len(texts)) cosine similarities."""
        if not queries or not texts:
            return np.zeros((len(queries), len(texts)), dtype=np.float32)
        both = self.vectors([*queries, *texts])
        return both[: len(queries)] @ both[len(queries) :].T

    def best(self, queries: Sequence[str], texts: Sequence[str]) -> np.ndarray:
        """For each of ``texts`` the highest cosine to any of ``queries`` (zeros when
        there are no queries)."""
        mat = self.matrix(queries, texts)
        if mat.shape[0] == 0:
            return np.zeros(len(texts), dtype=np.float32)
        return mat.max(axis=0)
