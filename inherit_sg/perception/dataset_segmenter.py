"""Dataset segmenter: instance masks and labels read from the frame's own per-pixel
instance image (simulator / Replica / HM3D semantics), the offline stand-in for SAM3.

Instance ids are per frame only: they are used here to split one frame's pixels and are
never returned, so nothing downstream can link frames through them. An optional noise
model (missed detections, ragged boundaries, jittered scores) makes the masks look more
like a learned segmenter's.
"""

from __future__ import annotations

import zlib
from collections.abc import Sequence
from dataclasses import dataclass

import cv2
import numpy as np

from inherit_sg.model import Frame
from inherit_sg.perception.base import Detection, make_detection, mask_bbox

_KERNEL = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (3, 3))


@dataclass(frozen=True)
class MaskNoise:
    """Noise model: drop rate, boundary jitter (pixels of random erode/dilate) and score
    spread. Deterministic per (seed, frame)."""

    drop_rate: float = 0.1
    boundary_px: int = 2
    score_sigma: float = 0.1
    seed: int = 0


def _match(label: str, prompts: Sequence[str]) -> bool:
    """A label matches a prompt when either contains the other as whole words."""
    words = f" {label} "
    return any(f" {p} " in words or f" {label} " in f" {p} " for p in prompts)


class DatasetSegmenter:
    """Masks and labels from ``frame.instances`` / ``frame.instance_labels``.

    ``needs_instances``: a frame without instance images is not looked at (finding nothing
    there is no evidence that nothing is there).
    """

    needs_instances = True

    def __init__(
        self,
        min_pixels: int = 50,
        min_fraction: float = 0.0002,
        erosion_px: int = 1,
        ignore_labels: Sequence[str] = (),
        noise: MaskNoise | None = None,
    ) -> None:
        self.name = "dataset"
        self._min_pixels = min_pixels
        self._min_fraction = min_fraction
        self._erosion = erosion_px
        self._ignore = {s.strip().lower() for s in ignore_labels}
        self._noise = noise

    def segment(self, frame: Frame, prompts: Sequence[str] | None = None) -> list[Detection]:
        """One detection per labelled instance id of this frame (id 0 ignored), largest
        first; with ``prompts``, only instances whose label matches one of them."""
        if frame.instances is None:
            return []
        inst = frame.instances
        wanted = [p.strip().lower() for p in prompts] if prompts else None
        floor = max(self._min_pixels, int(self._min_fraction * inst.size))
        ids, counts = np.unique(inst, return_counts=True)
        rng = self._rng(frame)
        out: list[Detection] = []
        for inst_id, count in zip(ids.tolist(), counts.tolist(), strict=True):
            label = frame.instance_labels.get(inst_id, "").strip().lower()
            if inst_id == 0 or count < floor or not label or label in self._ignore:
                continue
            if wanted is not None and not _match(label, wanted):
                continue
            mask = inst == inst_id
            if self._erosion > 0:
                eroded = cv2.erode(mask.view(np.uint8), _KERNEL, iterations=self._erosion)
                mask = eroded.astype(bool)
            score = 1.0
            if rng is not None and self._noise is not None:
                if rng.random() < self._noise.drop_rate:
                    continue
                mask = self._jitter(mask, rng, self._noise.boundary_px)
                score = float(np.clip(1.0 - abs(rng.normal(0.0, self._noise.score_sigma)), 0, 1))
            if np.count_nonzero(mask) < floor:
                continue
            det = make_detection(mask, label, score)
            if det is not None:
                out.append(det)
        out.sort(key=lambda d: d.area, reverse=True)
        return out

    def _rng(self, frame: Frame) -> np.random.Generator | None:
        if self._noise is None:
            return None
        key = zlib.crc32(f"{frame.frame_id}:{frame.index}".encode())
        return np.random.default_rng([self._noise.seed, key])

    @staticmethod
    def _jitter(mask: np.ndarray, rng: np.random.Generator, px: int) -> np.ndarray:
        """Ragged boundary: random erode or dilate, then flip a random half of the band
        of pixels between the eroded and dilated mask (worked on the mask's window)."""
        box = mask_bbox(mask)
        if px <= 0 or box is None:
            return mask
        h, w = mask.shape
        x0, y0, x1, y1 = box
        ys = slice(max(0, y0 - px - 1), min(h, y1 + px + 2))
        xs = slice(max(0, x0 - px - 1), min(w, x1 + px + 2))
        m = mask[ys, xs].astype(np.uint8)
        steps = int(rng.integers(1, px + 1))
        grown = cv2.dilate(m, _KERNEL, iterations=steps)
        shrunk = cv2.erode(m, _KERNEL, iterations=steps)
        band = (grown != shrunk) & (rng.random(m.shape) < 0.5)
        base = grown if rng.random() < 0.5 else shrunk
        out = np.zeros_like(mask, dtype=bool)
        out[ys, xs] = np.where(band, 1 - base, base).astype(bool)
        return out
