"""Bird's-eye-view picture of one floor (paper §III-C, the soft trigger's input).

Unknown space is grey, free space white, obstacles dark; every room is tinted with its
own colour and labelled at its most interior point; doors are orange squares, the
trajectory a blue line ending in a red dot, and past map-update points are magenta
rings that fade with age. North (+y) is up.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import cv2
import numpy as np
from PIL import Image
from scipy import ndimage as ndi

_PALETTE = np.array(
    [
        (230, 25, 75),
        (60, 180, 75),
        (255, 225, 25),
        (0, 130, 200),
        (245, 130, 48),
        (145, 30, 180),
        (70, 240, 240),
        (240, 50, 230),
        (210, 245, 60),
        (250, 190, 212),
        (0, 128, 128),
        (220, 190, 255),
        (170, 110, 40),
        (128, 0, 0),
        (170, 255, 195),
        (128, 128, 0),
        (0, 0, 128),
        (255, 215, 180),
    ],
    dtype=np.float32,
)
UNKNOWN = (190, 190, 190)
FREE = (255, 255, 255)
OCCUPIED = (35, 35, 35)


def room_colour(room: int) -> tuple[int, int, int]:
    """Stable colour of a room number."""
    c = _PALETTE[(room - 1) % len(_PALETTE)]
    return (int(c[0]), int(c[1]), int(c[2]))


@dataclass
class BevScene:
    """What to draw, in the grid's cell frame (``origin`` = world x, y of cell (0, 0))."""

    free: np.ndarray
    occupied: np.ndarray
    rooms: np.ndarray  # int room numbers, 0 = none
    origin: tuple[float, float]
    resolution: float
    labels: Mapping[int, str] = field(default_factory=dict)
    doors: Sequence[tuple[float, float]] = ()
    trajectory: Sequence[tuple[float, float]] = ()
    update_points: Sequence[tuple[float, float, float]] = ()  # x, y, time of the update
    now: float = 0.0
    fade_s: float = 120.0


def _px(scene: BevScene, x: float, y: float, scale: int) -> tuple[int, int]:
    h = scene.free.shape[0]
    col = (x - scene.origin[0]) / scene.resolution
    row = (y - scene.origin[1]) / scene.resolution
    return round(col * scale), round((h - row) * scale)


def render_bev(scene: BevScene, scale: int = 3) -> np.ndarray:
    """RGB uint8 picture of the floor, ``scale`` pixels per cell."""
    base = np.empty((*scene.free.shape, 3), dtype=np.float32)
    base[:] = UNKNOWN
    base[scene.free] = FREE
    tint = scene.rooms > 0
    colours = _PALETTE[(scene.rooms[tint] - 1) % len(_PALETTE)]
    base[tint] = 0.45 * base[tint] + 0.55 * colours
    base[scene.occupied] = OCCUPIED
    img = np.ascontiguousarray(np.flipud(base).astype(np.uint8))
    img = np.ascontiguousarray(np.repeat(np.repeat(img, scale, axis=0), scale, axis=1))
    for x, y, t in scene.update_points:
        alpha = math.exp(-max(0.0, scene.now - t) / scene.fade_s)
        colour = tuple(int(255 - alpha * (255 - v)) for v in (200, 0, 200))
        cv2.circle(img, _px(scene, x, y, scale), 4 * scale, colour, max(1, scale // 2))
    if len(scene.trajectory) > 1:
        pts = np.array([_px(scene, x, y, scale) for x, y in scene.trajectory], dtype=np.int32)
        cv2.polylines(img, [pts.reshape(-1, 1, 2)], False, (30, 90, 220), max(1, scale // 2))
    if scene.trajectory:
        cv2.circle(img, _px(scene, *scene.trajectory[-1], scale), 2 * scale, (220, 20, 20), -1)
    half = max(2, scale * 2)
    for x, y in scene.doors:
        px, py = _px(scene, x, y, scale)
        cv2.rectangle(img, (px - half, py - half), (px + half, py + half), (255, 140, 0), -1)
    for room, text in scene.labels.items():
        mask = scene.rooms == room
        if not mask.any():
            continue
        depth = ndi.distance_transform_edt(mask)
        r, c = np.unravel_index(int(np.argmax(depth)), mask.shape)
        x = scene.origin[0] + (c + 0.5) * scene.resolution
        y = scene.origin[1] + (r + 0.5) * scene.resolution
        _label(img, text, _px(scene, x, y, scale))
    return img


def _label(img: np.ndarray, text: str, at: tuple[int, int]) -> None:
    font, size = cv2.FONT_HERSHEY_SIMPLEX, 0.45
    (tw, th), _ = cv2.getTextSize(text, font, size, 1)
    org = (at[0] - tw // 2, at[1] + th // 2)
    cv2.putText(img, text, org, font, size, (255, 255, 255), 3, cv2.LINE_AA)
    cv2.putText(img, text, org, font, size, (0, 0, 0), 1, cv2.LINE_AA)


def write_png(image: np.ndarray, path: str | Path) -> Path:
    """Write an RGB picture as PNG (creating folders); returns the path."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(image).save(out, format="PNG")
    return out


def save_bev(scene: BevScene, path: str | Path, scale: int = 3) -> Path:
    """Render and write a PNG; returns the path."""
    return write_png(render_bev(scene, scale), path)
