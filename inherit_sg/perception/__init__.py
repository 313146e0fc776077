"""Perception backends behind small protocols: segmenters (dataset instance images,
classical depth + colour, SAM3), visual encoders (offline descriptor, DINOv3, ONNX) and
describers (offline template, VLM endpoint). Heavy model libraries are imported only by
the adapters that need them."""

from inherit_sg.perception.base import (
    Describer,
    Detection,
    ObjectObservation,
    Segmenter,
    VisualEncoder,
    make_detection,
    mask_bbox,
)
from inherit_sg.perception.registry import (
    DESCRIBERS,
    SEGMENTERS,
    VISUAL_ENCODERS,
    create_describer,
    create_segmenter,
    create_visual_encoder,
    register_describer,
    register_segmenter,
    register_visual_encoder,
)

__all__ = [
    "DESCRIBERS",
    "SEGMENTERS",
    "VISUAL_ENCODERS",
    "Describer",
    "Detection",
    "ObjectObservation",
    "Segmenter",
    "VisualEncoder",
    "create_describer",
    "create_segmenter",
    "create_visual_encoder",
    "make_detection",
    "mask_bbox",
    "register_describer",
    "register_segmenter",
    "register_visual_encoder",
]
