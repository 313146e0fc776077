"""Object kinds a segmenter mistakes for one another (label confusions of the noise
model)."""

from __future__ import annotations

# Kinds a segmenter mistakes for one another.
CONFUSIONS: dict[str, tuple[str, ...]] = {
    "chair": ("stool", "armchair"),
    "stool": ("chair",),
    "armchair": ("sofa", "chair"),
    "sofa": ("armchair",),
    "table": ("desk", "dining table", "coffee table"),
    "desk": ("table",),
    "dining table": ("table",),
    "coffee table": ("table",),
    "cabinet": ("dresser", "nightstand"),
    "dresser": ("cabinet",),
    "nightstand": ("cabinet",),
    "wardrobe": ("cabinet",),
    "bookshelf": ("cabinet",),
    "tv stand": ("cabinet",),
    "counter": ("cabinet",),
    "refrigerator": ("wardrobe",),
    "monitor": ("tv",),
    "tv": ("monitor",),
    "lamp": ("table lamp",),
    "table lamp": ("lamp",),
    "mug": ("bowl", "bottle"),
    "bowl": ("plate", "mug"),
    "plate": ("bowl",),
    "vase": ("bottle",),
    "bottle": ("vase",),
    "washing machine": ("dryer",),
    "dryer": ("washing machine",),
    "sink": ("bathtub",),
    "bathtub": ("sink",),
    "painting": ("mirror",),
    "mirror": ("painting", "window"),
    "book": ("laptop",),
    "laptop": ("book",),
}
