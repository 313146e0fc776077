"""DINOv3 adapter: transformers ``DINOv3ViTModel`` from a local directory
(``perception.model_dir / "dinov3"``) as the visual encoder.

Each mask becomes a square crop around it (outside-mask pixels set to the mean colour,
so they normalise to zero), resized to a multiple of the patch size; the feature is the
mask-weighted mean of the patch tokens (weights = mask coverage per patch) or the CLS
token, L2-normalised. Whole images keep their aspect ratio and give the CLS token.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import InputError
from inherit_sg.perception.base import check_image, check_masks, l2_normalise
from inherit_sg.perception.hf import load_local, offline_transformers
from inherit_sg.perception.preprocess import (
    IMAGENET_MEAN,
    IMAGENET_STD,
    masked_crop,
    patch_weights,
    round_to_multiple,
    to_batch,
)


def read_mean_std(path: Path) -> tuple[list[float], list[float]]:
    """Normalisation from ``preprocessor_config.json`` when present, else ImageNet's."""
    f = path / "preprocessor_config.json"
    if f.is_file():
        data = json.loads(f.read_text(encoding="utf-8"))
        return list(data.get("image_mean", IMAGENET_MEAN)), list(
            data.get("image_std", IMAGENET_STD)
        )
    return list(IMAGENET_MEAN), list(IMAGENET_STD)


class DinoV3Encoder:
    """Visual encoder backed by a local DINOv3 ViT checkpoint."""

    def __init__(
        self,
        model_dir: str | Path,
        input_size: int = 224,
        pooling: str = "mask",
        device: str = "cpu",
        batch_size: int = 16,
    ) -> None:
        if pooling not in ("mask", "cls"):
            raise InputError(f"DINOv3 pooling must be 'mask' or 'cls', got {pooling!r}")
        path = Path(model_dir)
        transformers = offline_transformers()
        import torch

        self._torch = torch
        self._model = load_local(transformers.DINOv3ViTModel, path, "DINOv3").eval().to(device)
        cfg = self._model.config
        self._patch = int(cfg.patch_size)
        self._prefix = 1 + int(getattr(cfg, "num_register_tokens", 0))
        self._size = round_to_multiple(input_size, self._patch)
        self._mean, self._std = read_mean_std(path)
        self._pooling = pooling
        self._device = device
        self._batch = max(1, batch_size)
        self.name = "dinov3"
        self.dim = int(cfg.hidden_size)
        self.image_dim = self.dim

    @classmethod
    def from_config(cls, config: Config) -> DinoV3Encoder:
        """Load from ``perception.model_dir / "dinov3"``."""
        from inherit_sg.perception.registry import model_path

        p = config.perception
        path = model_path(config, "dinov3", "DINOv3 encoder")
        return cls(path, input_size=p.encoder_input_size, device=p.device)

    def _forward(self, batch: np.ndarray) -> Any:
        with self._torch.inference_mode():
            pixels = self._torch.from_numpy(batch).to(self._device)
            return self._model(pixel_values=pixels).last_hidden_state.float().cpu().numpy()

    def encode(self, rgb: np.ndarray, masks: Sequence[np.ndarray]) -> np.ndarray:
        """(len(masks), dim) L2-normalised features of the masked crops."""
        check_image(rgb)
        check_masks(masks, rgb.shape[:2])
        out = np.zeros((len(masks), self.dim), dtype=np.float32)
        fill = tuple(self._mean)
        for start in range(0, len(masks), self._batch):
            chunk = masks[start : start + self._batch]
            crops = [masked_crop(rgb, np.asarray(m, dtype=bool), self._size, fill) for m in chunk]
            tokens = self._forward(
                to_batch([c for c, _ in crops], self._size, self._size, self._mean, self._std)
            )
            for i, (_, coverage) in enumerate(crops):
                weights = patch_weights(coverage, self._patch)
                if self._pooling == "cls" or weights.sum() <= 1e-6:
                    out[start + i] = tokens[i, 0]
                else:
                    patches = tokens[i, self._prefix : self._prefix + weights.size]
                    out[start + i] = weights @ patches / weights.sum()
        return l2_normalise(out)

    def encode_image(self, rgb: np.ndarray) -> np.ndarray:
        """(dim,) CLS feature of the whole image, aspect ratio kept."""
        check_image(rgb)
        h, w = rgb.shape[:2]
        scale = self._size / min(h, w)
        th, tw = (
            round_to_multiple(h * scale, self._patch),
            round_to_multiple(w * scale, self._patch),
        )
        tokens = self._forward(to_batch([rgb], th, tw, self._mean, self._std))
        return l2_normalise(tokens[0, 0])
