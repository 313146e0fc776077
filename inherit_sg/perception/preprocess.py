"""Image preprocessing for the model adapters, done by hand with numpy and OpenCV
(no torchvision here): crop, resize, rescale to [0, 1], normalise, NCHW batches.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from inherit_sg.perception.base import mask_bbox

IMAGENET_MEAN = (0.485, 0.456, 0.406)
IMAGENET_STD = (0.229, 0.224, 0.225)
HALF_MEAN = (0.5, 0.5, 0.5)
HALF_STD = (0.5, 0.5, 0.5)


def resize(image: np.ndarray, height: int, width: int) -> np.ndarray:
    """Resize an (H, W[, C]) array: area averaging when shrinking, bilinear otherwise."""
    if image.shape[:2] == (height, width):
        return image
    shrink = height < image.shape[0] and width < image.shape[1]
    interp = cv2.INTER_AREA if shrink else cv2.INTER_LINEAR
    return cv2.resize(image, (width, height), interpolation=interp)


def round_to_multiple(value: float, multiple: int) -> int:
    """Nearest positive multiple of ``multiple``."""
    return max(multiple, round(value / multiple) * multiple)


def normalise(
    rgb: np.ndarray, mean: Sequence[float] = IMAGENET_MEAN, std: Sequence[float] = IMAGENET_STD
) -> np.ndarray:
    """(H, W, 3) uint8 → (3, H, W) float32, rescaled to [0, 1] then standardised."""
    x = rgb.astype(np.float32) * np.float32(1.0 / 255.0)
    y = (x - np.asarray(mean, dtype=np.float32)) / np.asarray(std, dtype=np.float32)
    return np.ascontiguousarray(y.transpose(2, 0, 1), dtype=np.float32)


def to_batch(
    images: Sequence[np.ndarray],
    height: int,
    width: int,
    mean: Sequence[float] = IMAGENET_MEAN,
    std: Sequence[float] = IMAGENET_STD,
) -> np.ndarray:
    """Resize and normalise images into one (N, 3, height, width) float32 array."""
    out = np.empty((len(images), 3, height, width), dtype=np.float32)
    for i, img in enumerate(images):
        out[i] = normalise(resize(img, height, width), mean, std)
    return out


def square_box(
    box: tuple[int, int, int, int], shape: tuple[int, int], margin: float = 0.1
) -> tuple[int, int, int, int]:
    """Square crop window ``(x0, y0, x1, y1)`` (exclusive end) around an inclusive box,
    grown by ``margin`` of its side and shifted/clipped to stay inside ``shape``."""
    h, w = shape
    x0, y0, x1, y1 = box
    side = max(x1 - x0 + 1, y1 - y0 + 1)
    side = min(max(h, w), int(np.ceil(side * (1.0 + 2.0 * margin))))
    cx, cy = (x0 + x1 + 1) / 2.0, (y0 + y1 + 1) / 2.0
    sx0 = int(np.clip(round(cx - side / 2.0), 0, max(0, w - side)))
    sy0 = int(np.clip(round(cy - side / 2.0), 0, max(0, h - side)))
    return sx0, sy0, min(w, sx0 + side), min(h, sy0 + side)


def masked_crop(
    rgb: np.ndarray,
    mask: np.ndarray,
    size: int,
    fill: Sequence[float] = IMAGENET_MEAN,
    margin: float = 0.1,
) -> tuple[np.ndarray, np.ndarray]:
    """Square ``size``×``size`` crop around ``mask``: pixels outside the mask are set to
    ``fill`` (so they normalise to ~0). Returns (crop uint8, mask coverage float32 in
    [0, 1] at the crop's resolution). An empty mask gives the whole image."""
    box = mask_bbox(mask) or (0, 0, rgb.shape[1] - 1, rgb.shape[0] - 1)
    x0, y0, x1, y1 = square_box(box, mask.shape, margin)
    crop = rgb[y0:y1, x0:x1]
    m = mask[y0:y1, x0:x1].astype(np.float32)
    fill_px = np.asarray(fill, dtype=np.float32) * 255.0
    blended = crop.astype(np.float32) * m[..., None] + fill_px * (1.0 - m[..., None])
    crop_out = resize(np.clip(blended + 0.5, 0, 255).astype(np.uint8), size, size)
    return crop_out, resize(m, size, size)


def patch_weights(coverage: np.ndarray, patch: int) -> np.ndarray:
    """Mean mask coverage per ``patch``×``patch`` cell of an (H, W) map, row-major
    flattened: the weights of mask-pooling patch tokens."""
    h, w = coverage.shape
    gh, gw = h // patch, w // patch
    cells = coverage[: gh * patch, : gw * patch].reshape(gh, patch, gw, patch)
    return cells.mean(axis=(1, 3)).reshape(-1).astype(np.float32)
