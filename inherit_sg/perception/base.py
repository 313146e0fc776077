"""Protocols and result types of the perception backends (segmenters, visual encoders,
describers).

The mapping pipeline depends only on these: which backend runs is a configuration
choice resolved by :mod:`inherit_sg.perception.registry`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from inherit_sg.errors import InputError
from inherit_sg.model import Frame


@dataclass(frozen=True)
class Detection:
    """One instance mask found in a frame.

    ``mask`` is (H, W) bool at the frame's resolution; ``bbox_xyxy`` is the inclusive
    pixel box ``(x0, y0, x1, y1)`` of the mask; ``label`` is lower-case ("object" when
    the segmenter is class-agnostic); ``score`` is in [0, 1].
    """

    mask: np.ndarray
    label: str
    score: float
    bbox_xyxy: tuple[int, int, int, int]

    @property
    def area(self) -> int:
        """Number of mask pixels."""
        return int(np.count_nonzero(self.mask))


def mask_bbox(mask: np.ndarray) -> tuple[int, int, int, int] | None:
    """Inclusive ``(x0, y0, x1, y1)`` box of the true pixels of ``mask``; None if empty."""
    rows = np.flatnonzero(mask.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(mask.any(axis=0))
    return int(cols[0]), int(rows[0]), int(cols[-1]), int(rows[-1])


def make_detection(mask: np.ndarray, label: str, score: float) -> Detection | None:
    """Detection with its box computed from ``mask``; None when the mask is empty."""
    box = mask_bbox(mask)
    if box is None:
        return None
    return Detection(
        mask=np.asarray(mask, dtype=bool),
        label=label.strip().lower(),
        score=float(score),
        bbox_xyxy=box,
    )


@dataclass(frozen=True)
class ObjectObservation:
    """What a describer sees of one object.

    ``rgb`` (h, w, 3) uint8 and ``mask`` (h, w) bool are the crop around the object;
    ``extent`` is the object's 3D size in metres (x, y, z with z up) from
    back-projection; ``room`` is the label of the room it is in, when known;
    ``round_footprint``: its floor-plan outline is round (a bin, a round table).
    """

    label: str
    rgb: np.ndarray
    mask: np.ndarray
    extent: tuple[float, float, float]
    room: str | None = None
    round_footprint: bool = False

    def __post_init__(self) -> None:
        if self.rgb.ndim != 3 or self.rgb.shape[2] != 3 or self.rgb.dtype != np.uint8:
            raise InputError(
                f"observation of {self.label!r}: rgb must be HxWx3 uint8, got "
                f"{self.rgb.shape} {self.rgb.dtype}"
            )
        if self.mask.shape != self.rgb.shape[:2]:
            raise InputError(
                f"observation of {self.label!r}: mask {self.mask.shape} does not match "
                f"rgb {self.rgb.shape[:2]}"
            )

    @classmethod
    def from_frame(
        cls,
        frame: Frame,
        detection: Detection,
        extent: tuple[float, float, float],
        room: str | None = None,
        margin: int = 4,
        round_footprint: bool = False,
    ) -> ObjectObservation:
        """Crop ``detection`` (plus ``margin`` pixels) out of ``frame``."""
        x0, y0, x1, y1 = detection.bbox_xyxy
        h, w = detection.mask.shape
        ys = slice(max(0, y0 - margin), min(h, y1 + margin + 1))
        xs = slice(max(0, x0 - margin), min(w, x1 + margin + 1))
        return cls(
            label=detection.label,
            rgb=np.ascontiguousarray(frame.rgb[ys, xs]),
            mask=np.ascontiguousarray(detection.mask[ys, xs]),
            extent=extent,
            room=room,
            round_footprint=round_footprint,
        )


@runtime_checkable
class Segmenter(Protocol):
    """Finds object instance masks in a frame."""

    name: str

    def segment(self, frame: Frame, prompts: Sequence[str] | None = None) -> list[Detection]:
        """Detections in ``frame``; with ``prompts``, only objects matching those labels."""
        ...


@runtime_checkable
class VisualEncoder(Protocol):
    """Maps masked image crops and whole images to L2-normalised float32 vectors.

    ``dim`` is the size of object features, ``image_dim`` that of whole-image features.
    """

    name: str
    dim: int
    image_dim: int

    def encode(self, rgb: np.ndarray, masks: Sequence[np.ndarray]) -> np.ndarray:
        """(len(masks), dim) features, one per mask over the (H, W, 3) uint8 image."""
        ...

    def encode_image(self, rgb: np.ndarray) -> np.ndarray:
        """(dim,) global feature of the whole image (keyframe gating, place recall)."""
        ...


@runtime_checkable
class Describer(Protocol):
    """Writes a short natural-language description of an observed object."""

    name: str

    def describe(self, obs: ObjectObservation) -> str:
        """One-sentence description of ``obs``."""
        ...


def check_image(rgb: np.ndarray, what: str = "image") -> np.ndarray:
    """Validate an (H, W, 3) uint8 image; raise InputError naming ``what`` otherwise."""
    if rgb.ndim != 3 or rgb.shape[2] != 3:
        raise InputError(f"{what} must be HxWx3, got shape {rgb.shape}")
    if rgb.dtype != np.uint8:
        raise InputError(f"{what} must be uint8, got {rgb.dtype}")
    return rgb


def check_masks(masks: Sequence[np.ndarray], shape: tuple[int, int], what: str = "mask") -> None:
    """Validate that every mask is 2-D with the image's (H, W)."""
    for i, m in enumerate(masks):
        if m.shape != shape:
            raise InputError(f"{what} {i} has shape {m.shape}, image is {shape}")


def l2_normalise(x: np.ndarray, eps: float = 1e-12) -> np.ndarray:
    """Row-wise L2 normalisation (works on 1-D and 2-D arrays) as float32."""
    x = np.asarray(x, dtype=np.float32)
    norm = np.linalg.norm(x, axis=-1, keepdims=True)
    return (x / np.maximum(norm, eps)).astype(np.float32)


def blind_without_instances(segmenter: object) -> bool:
    """Whether ``segmenter`` sees nothing in frames that carry no instance images (the
    dataset segmenter: such frames are no evidence that a place is empty)."""
    return bool(getattr(segmenter, "needs_instances", False))
