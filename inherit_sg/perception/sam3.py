"""SAM3 adapter: text-prompted instance segmentation with transformers ``Sam3Model``
loaded from a local directory (``perception.model_dir / "sam3"``).

The directory holds the model (``config.json`` + weights), its CLIP tokenizer, and
optionally the processor config (``preprocessor_config.json`` or
``processor_config.json``) for input size and normalisation. Images are preprocessed
by hand (square resize, rescale, normalise); the vision features are computed once per
frame and shared by all prompts, which run in batches. Scores are the query logit times
the presence logit (both sigmoid); masks are upsampled to the frame and thresholded;
overlapping detections across prompts are suppressed by mask IoU.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.config import Config
from inherit_sg.model import Frame
from inherit_sg.perception.base import Detection, make_detection
from inherit_sg.perception.hf import load_local, offline_transformers
from inherit_sg.perception.preprocess import HALF_MEAN, HALF_STD, to_batch

DEFAULT_PROMPTS: tuple[str, ...] = (
    "chair", "armchair", "sofa", "table", "desk", "bed", "nightstand", "cabinet",
    "wardrobe", "dresser", "shelf", "bookshelf", "counter", "sink", "stove", "refrigerator",
    "toilet", "bathtub", "shower", "mirror", "lamp", "tv", "monitor", "laptop", "keyboard",
    "plant", "vase", "painting", "picture", "clock", "pillow", "blanket", "rug", "curtain",
    "window", "door", "box", "bag", "bottle", "cup", "mug", "bowl", "book", "trash can",
    "washing machine", "microwave", "oven", "stool", "bench", "towel",
)  # fmt: skip


def read_image_processing(
    path: Path, default_size: int
) -> tuple[int, int, list[float], list[float]]:
    """(height, width, mean, std) from a saved processor config, else SAM3's defaults."""
    cfg: dict[str, Any] = {}
    for name in ("preprocessor_config.json", "processor_config.json"):
        f = path / name
        if f.is_file():
            data = json.loads(f.read_text(encoding="utf-8"))
            cfg = data.get("image_processor", data)
            break
    size = cfg.get("size") or {}
    h = int(size.get("height", size.get("shortest_edge", default_size)))
    w = int(size.get("width", size.get("shortest_edge", default_size)))
    return h, w, list(cfg.get("image_mean", HALF_MEAN)), list(cfg.get("image_std", HALF_STD))


def suppress(dets: list[Detection], iou: float, limit: int) -> list[Detection]:
    """Greedy mask-IoU suppression, best score first, at most ``limit`` kept."""
    kept: list[Detection] = []
    for d in sorted(dets, key=lambda d: d.score, reverse=True):
        if len(kept) >= limit:
            break
        overlap = any(
            int(np.count_nonzero(d.mask & k.mask)) / max(1, int(np.count_nonzero(d.mask | k.mask)))
            > iou
            for k in kept
        )
        if not overlap:
            kept.append(d)
    return kept


class Sam3Segmenter:
    """Text-prompted segmenter backed by a local SAM3 checkpoint."""

    def __init__(
        self,
        model_dir: str | Path,
        prompts: Sequence[str] = (),
        score_threshold: float = 0.4,
        mask_threshold: float = 0.5,
        device: str = "cpu",
        prompt_batch: int = 16,
        max_detections: int = 64,
        nms_iou: float = 0.7,
    ) -> None:
        self.name = "sam3"
        path = Path(model_dir)
        transformers = offline_transformers()
        import torch

        self._model = load_local(transformers.Sam3Model, path, "SAM3").eval().to(device)
        self._tokenizer = load_local(transformers.AutoTokenizer, path, "SAM3 tokenizer")
        self._torch = torch
        self._device = device
        cfg = self._model.config
        default = cfg.vision_config.backbone_config.image_size
        self._h, self._w, self._mean, self._std = read_image_processing(path, int(default))
        self._max_len = min(32, int(cfg.text_config.max_position_embeddings))
        self.prompts = [p.strip().lower() for p in prompts if p.strip()] or list(DEFAULT_PROMPTS)
        self.score_threshold = score_threshold
        self.mask_threshold = mask_threshold
        self._batch = max(1, prompt_batch)
        self._max_det = max_detections
        self._nms_iou = nms_iou

    @classmethod
    def from_config(cls, config: Config) -> Sam3Segmenter:
        """Load from ``perception.model_dir / "sam3"`` with the configured thresholds."""
        from inherit_sg.perception.registry import model_path

        p = config.perception
        return cls(
            model_path(config, "sam3", "SAM3 segmenter"),
            prompts=p.prompts,
            score_threshold=p.score_threshold,
            mask_threshold=p.mask_threshold,
            device=p.device,
        )

    def segment(self, frame: Frame, prompts: Sequence[str] | None = None) -> list[Detection]:
        """Detections for ``prompts`` (default: the configured vocabulary), each
        labelled with the prompt that found it."""
        torch = self._torch
        words = [p.strip().lower() for p in (prompts or self.prompts) if p.strip()]
        if not words:
            return []
        h, w = frame.rgb.shape[:2]
        pixels = torch.from_numpy(to_batch([frame.rgb], self._h, self._w, self._mean, self._std))
        found: list[Detection] = []
        with torch.inference_mode():
            vision = self._model.get_vision_features(pixel_values=pixels.to(self._device))
            for start in range(0, len(words), self._batch):
                chunk = words[start : start + self._batch]
                found.extend(self._run(vision, chunk, (h, w)))
        return suppress(found, self._nms_iou, self._max_det)

    def _run(self, vision: Any, words: list[str], size: tuple[int, int]) -> list[Detection]:
        torch = self._torch
        from transformers.models.sam3.modeling_sam3 import Sam3VisionEncoderOutput

        n = len(words)
        shared = Sam3VisionEncoderOutput(
            last_hidden_state=vision.last_hidden_state.expand(n, -1, -1),
            fpn_hidden_states=tuple(t.expand(n, -1, -1, -1) for t in vision.fpn_hidden_states),
            fpn_position_encoding=tuple(
                t.expand(n, -1, -1, -1) for t in vision.fpn_position_encoding
            ),
        )
        tokens = self._tokenizer(
            words,
            padding="max_length",
            max_length=self._max_len,
            truncation=True,
            return_tensors="pt",
        )
        out = self._model(
            vision_embeds=shared,
            input_ids=tokens["input_ids"].to(self._device),
            attention_mask=tokens["attention_mask"].to(self._device),
        )
        scores = out.pred_logits.sigmoid()
        if out.presence_logits is not None:
            scores = scores * out.presence_logits.sigmoid()
        keep = (scores > self.score_threshold).nonzero().tolist()
        if not keep:
            return []
        rows = torch.tensor([k[0] for k in keep])
        cols = torch.tensor([k[1] for k in keep])
        logits = out.pred_masks[rows, cols].unsqueeze(0).float()
        probs = torch.nn.functional.interpolate(
            logits, size=size, mode="bilinear", align_corners=False
        )
        masks = (probs[0].sigmoid() > self.mask_threshold).cpu().numpy()
        dets: list[Detection] = []
        for (b, q), mask in zip(keep, masks, strict=True):
            det = make_detection(mask, words[b], float(scores[b, q]))
            if det is not None:
                dets.append(det)
        return dets
