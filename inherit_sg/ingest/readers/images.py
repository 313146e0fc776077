"""Image and file helpers shared by the readers: colour and depth decoding with errors
that name the file, header-only size probes, and numbered-file discovery."""

from __future__ import annotations

import re
from pathlib import Path

import cv2
import numpy as np
from PIL import Image, UnidentifiedImageError

from inherit_sg.errors import DatasetError, FrameError

_TRAILING_NUMBER = re.compile(r"(\d+)$")


def read_rgb(path: Path) -> np.ndarray:
    """Load a colour image as (H, W, 3) uint8 RGB; FrameError names a missing or bad file."""
    if not path.is_file():
        raise FrameError(f"missing colour image {path}")
    img = cv2.imread(str(path), cv2.IMREAD_COLOR)
    if img is None:
        raise FrameError(f"cannot decode colour image {path}")
    return cv2.cvtColor(img, cv2.COLOR_BGR2RGB)


def read_depth(path: Path, units_per_metre: float) -> np.ndarray:
    """Load a 16-bit depth PNG as (H, W) float32 metres (0 stays 0 = no reading)."""
    if not path.is_file():
        raise FrameError(f"missing depth image {path}")
    raw = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if raw is None:
        raise FrameError(f"cannot decode depth image {path}")
    if raw.ndim != 2 or raw.dtype != np.uint16:
        raise FrameError(
            f"{path}: depth must be a single-channel 16-bit image, "
            f"got dtype {raw.dtype} with shape {raw.shape}"
        )
    return raw.astype(np.float32) / np.float32(units_per_metre)


def image_size(path: Path) -> tuple[int, int]:
    """(width, height) of an image from its header; DatasetError if unreadable."""
    try:
        with Image.open(path) as img:
            return int(img.width), int(img.height)
    except (OSError, UnidentifiedImageError) as exc:
        raise DatasetError(f"cannot read image size of {path}: {exc}") from None


def trailing_number(stem: str) -> int | None:
    """The number a file stem ends with (``frame000012`` -> 12), or None."""
    match = _TRAILING_NUMBER.search(stem)
    return int(match.group(1)) if match else None


def numbered_files(folder: Path, prefix: str, suffixes: tuple[str, ...]) -> dict[int, Path]:
    """Files ``<prefix><number><suffix>`` in ``folder`` keyed by number. When one number has
    several suffixes the earlier suffix in ``suffixes`` wins."""
    out: dict[int, Path] = {}
    if not folder.is_dir():
        return out
    rank = {s: i for i, s in enumerate(suffixes)}
    for path in folder.iterdir():
        suffix = path.suffix.lower()
        if suffix not in rank or not path.stem.startswith(prefix):
            continue
        digits = path.stem[len(prefix) :]
        if not digits.isdigit():
            continue
        number = int(digits)
        current = out.get(number)
        if current is None or rank[suffix] < rank[current.suffix.lower()]:
            out[number] = path
    return out
