"""ONNX adapter: any image feature extractor exported to ONNX, run with onnxruntime.

The model takes one NCHW float32 image batch and returns features: (N, D) directly,
(N, T, D) token sequences (the first token is used, e.g. a ViT's CLS) or (N, D, h, w)
feature maps (global average). Input size comes from the model when static, otherwise
from ``input_size``. Normalisation is ImageNet's unless a sidecar ``<model>.json`` gives
``image_mean`` / ``image_std`` (and optionally ``size``).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import ModelUnavailableError
from inherit_sg.perception.base import check_image, check_masks, l2_normalise
from inherit_sg.perception.preprocess import IMAGENET_MEAN, IMAGENET_STD, masked_crop, to_batch


def _static(value: Any) -> int | None:
    return value if isinstance(value, int) and value > 0 else None


class OnnxEncoder:
    """Visual encoder backed by a local ``.onnx`` file."""

    def __init__(
        self,
        model_path: str | Path,
        input_size: int = 224,
        batch_size: int = 16,
        providers: Sequence[str] = ("CPUExecutionProvider",),
    ) -> None:
        path = Path(model_path)
        if not path.is_file():
            raise ModelUnavailableError(f"ONNX encoder: {path} does not exist")
        try:
            import onnxruntime as ort
        except ImportError as exc:
            raise ModelUnavailableError(f"ONNX encoder needs onnxruntime: {exc}") from None
        try:
            self._session = ort.InferenceSession(str(path), providers=list(providers))
        except Exception as exc:  # onnxruntime raises its own untyped errors
            raise ModelUnavailableError(f"ONNX encoder: cannot load {path}: {exc}") from exc
        inp = self._session.get_inputs()[0]
        if len(inp.shape) != 4:
            raise ModelUnavailableError(f"ONNX encoder {path}: input must be NCHW, got {inp.shape}")
        self._input = inp.name
        sidecar = path.with_suffix(".json")
        meta = json.loads(sidecar.read_text(encoding="utf-8")) if sidecar.is_file() else {}
        size = int(meta.get("size", input_size))
        self._h = _static(inp.shape[2]) or size
        self._w = _static(inp.shape[3]) or size
        self._mean = list(meta.get("image_mean", IMAGENET_MEAN))
        self._std = list(meta.get("image_std", IMAGENET_STD))
        self._batch = 1 if _static(inp.shape[0]) == 1 else max(1, batch_size)
        self.name = "onnx"
        self.dim = int(self._run(np.zeros((1, 3, self._h, self._w), dtype=np.float32)).shape[1])
        self.image_dim = self.dim

    @classmethod
    def from_config(cls, config: Config) -> OnnxEncoder:
        """Load ``perception.onnx_path`` or ``model_dir / "visual_encoder.onnx"``."""
        from inherit_sg.perception.registry import model_path

        p = config.perception
        path = (
            Path(p.onnx_path)
            if p.onnx_path
            else model_path(config, "visual_encoder.onnx", "ONNX encoder")
        )
        return cls(path, input_size=p.encoder_input_size)

    def _run(self, batch: np.ndarray) -> np.ndarray:
        out = np.asarray(self._session.run(None, {self._input: batch})[0], dtype=np.float32)
        if out.ndim == 3:
            return out[:, 0]
        if out.ndim == 4:
            return out.mean(axis=(2, 3))
        if out.ndim != 2:
            raise ModelUnavailableError(f"ONNX encoder: unsupported output shape {out.shape}")
        return out

    def _features(self, images: list[np.ndarray]) -> np.ndarray:
        parts = [
            self._run(
                to_batch(images[i : i + self._batch], self._h, self._w, self._mean, self._std)
            )
            for i in range(0, len(images), self._batch)
        ]
        return np.concatenate(parts) if parts else np.zeros((0, self.dim), dtype=np.float32)

    def encode(self, rgb: np.ndarray, masks: Sequence[np.ndarray]) -> np.ndarray:
        """(len(masks), dim) L2-normalised features of the masked crops."""
        check_image(rgb)
        check_masks(masks, rgb.shape[:2])
        side = max(self._h, self._w)
        crops = [masked_crop(rgb, np.asarray(m, dtype=bool), side, self._mean)[0] for m in masks]
        return l2_normalise(self._features(crops))

    def encode_image(self, rgb: np.ndarray) -> np.ndarray:
        """(dim,) feature of the whole image."""
        check_image(rgb)
        return l2_normalise(self._features([rgb])[0])
