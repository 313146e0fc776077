"""Bird's-eye-view picture of one floor drawn from the graph (room masks, room labels and
object dots) with numpy + OpenCV, and the exact world ↔ pixel transform of that picture.

Pixel column ``c`` covers world x in ``[origin_x + c*cell, origin_x + (c+1)*cell)``; pixel
row ``r`` covers world y in ``(origin_y - (r+1)*cell, origin_y - r*cell]``: north (+y) is
up, as on a map.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import cv2
import numpy as np

from inherit_sg.model import RoomMask

MARGIN_M = 0.5
ROOM_RADIUS_M = 1.0  # extent kept around a room that has no mask
BACKGROUND = (245, 245, 245)
OUTLINE = (90, 90, 90)
TEXT = (40, 40, 40)
OBJECT_DOT = (70, 70, 70)
# pastel fills (BGR), one per room in turn
PALETTE = (
    (230, 216, 173),
    (181, 228, 255),
    (193, 235, 193),
    (221, 200, 238),
    (180, 222, 250),
    (238, 230, 176),
    (203, 192, 255),
    (200, 230, 230),
)


@dataclass(frozen=True)
class BevTransform:
    """World (x, y) ↔ pixel mapping of a rendered BEV picture (see module docstring)."""

    origin_x: float
    origin_y: float
    cell: float
    width: int
    height: int

    def to_pixel(self, x: float, y: float) -> tuple[float, float]:
        """(column, row) of world point (x, y), fractional; pixel centres at +0.5."""
        return (x - self.origin_x) / self.cell, (self.origin_y - y) / self.cell

    def to_world(self, col: float, row: float) -> tuple[float, float]:
        """World (x, y) of a fractional pixel position."""
        return self.origin_x + col * self.cell, self.origin_y - row * self.cell

    def headers(self) -> dict[str, str]:
        """``X-BEV-*`` response headers that let a client place world points on the image."""
        return {
            "X-BEV-Origin": f"{self.origin_x:.6f},{self.origin_y:.6f}",
            "X-BEV-Cell": f"{self.cell:.6f}",
            "X-BEV-Size": f"{self.width},{self.height}",
            "X-BEV-Axes": "col=+x,row=-y",
        }


@dataclass(frozen=True)
class BevRoom:
    """What the picture needs of a room."""

    id: str
    label: str
    position: Sequence[float] | None
    mask: RoomMask | None


@dataclass(frozen=True)
class BevObject:
    """What the picture needs of an object."""

    id: str
    position: Sequence[float]


def _mask_extent(mask: RoomMask) -> tuple[float, float, float, float] | None:
    rows, cols = np.nonzero(mask.cells)
    if rows.size == 0:
        return None
    res = mask.resolution
    return (
        mask.origin_x + cols.min() * res,
        mask.origin_y + rows.min() * res,
        mask.origin_x + (cols.max() + 1) * res,
        mask.origin_y + (rows.max() + 1) * res,
    )


def fit_transform(
    rooms: Sequence[BevRoom],
    objects: Sequence[BevObject],
    *,
    px_per_m: float = 60.0,
    max_px: int = 1200,
) -> BevTransform:
    """The smallest picture frame holding every room and object, plus a margin."""
    boxes: list[tuple[float, float, float, float]] = []
    for room in rooms:
        box = _mask_extent(room.mask) if room.mask is not None else None
        if box is not None:
            boxes.append(box)
        elif room.position is not None:
            x, y = float(room.position[0]), float(room.position[1])
            r = ROOM_RADIUS_M
            boxes.append((x - r, y - r, x + r, y + r))
    for obj in objects:
        x, y = float(obj.position[0]), float(obj.position[1])
        boxes.append((x, y, x, y))
    if not boxes:
        boxes.append((-2.0, -2.0, 2.0, 2.0))
    arr = np.asarray(boxes, dtype=float)
    x0, y0 = arr[:, 0].min() - MARGIN_M, arr[:, 1].min() - MARGIN_M
    x1, y1 = arr[:, 2].max() + MARGIN_M, arr[:, 3].max() + MARGIN_M
    cell = max(1.0 / px_per_m, max(x1 - x0, y1 - y0) / max_px)
    width = max(1, int(np.ceil((x1 - x0) / cell)))
    height = max(1, int(np.ceil((y1 - y0) / cell)))
    return BevTransform(float(x0), float(y1), float(cell), width, height)


def rasterise(mask: RoomMask, tf: BevTransform) -> np.ndarray:
    """The room mask resampled onto the picture grid (bool H×W), by pixel centre."""
    cols = np.arange(tf.width) + 0.5
    rows = np.arange(tf.height) + 0.5
    xs = tf.origin_x + cols * tf.cell
    ys = tf.origin_y - rows * tf.cell
    mc = np.floor((xs - mask.origin_x) / mask.resolution).astype(int)
    mr = np.floor((ys - mask.origin_y) / mask.resolution).astype(int)
    h, w = mask.cells.shape
    ok_c = (mc >= 0) & (mc < w)
    ok_r = (mr >= 0) & (mr < h)
    sampled = mask.cells[np.ix_(np.clip(mr, 0, h - 1), np.clip(mc, 0, w - 1))]
    return np.asarray(sampled & ok_r[:, None] & ok_c[None, :], dtype=bool)


def _put_label(img: np.ndarray, text: str, centre: tuple[int, int]) -> None:
    font, scale, thick = cv2.FONT_HERSHEY_SIMPLEX, 0.45, 1
    (tw, th), _ = cv2.getTextSize(text, font, scale, thick)
    org = (int(centre[0] - tw / 2), int(centre[1] + th / 2))
    cv2.putText(img, text, org, font, scale, (255, 255, 255), thick + 2, cv2.LINE_AA)
    cv2.putText(img, text, org, font, scale, TEXT, thick, cv2.LINE_AA)


def render_bev(
    rooms: Sequence[BevRoom], objects: Sequence[BevObject], tf: BevTransform | None = None
) -> tuple[np.ndarray, BevTransform]:
    """The BEV picture (BGR uint8) and its transform."""
    tf = tf or fit_transform(rooms, objects)
    img = np.empty((tf.height, tf.width, 3), dtype=np.uint8)
    img[:] = BACKGROUND

    def px(x: float, y: float) -> tuple[int, int]:
        c, r = tf.to_pixel(x, y)
        return int(np.floor(c)), int(np.floor(r))

    for i, room in enumerate(rooms):
        if room.mask is None:
            continue
        cells = rasterise(room.mask, tf)
        img[cells] = PALETTE[i % len(PALETTE)]
        contours, _ = cv2.findContours(
            cells.astype(np.uint8), cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE
        )
        cv2.drawContours(img, contours, -1, OUTLINE, 2)
    for i, room in enumerate(rooms):
        if room.mask is None and room.position is not None:
            radius = max(2, int(ROOM_RADIUS_M / tf.cell))
            centre = px(float(room.position[0]), float(room.position[1]))
            cv2.circle(img, centre, radius, PALETTE[i % len(PALETTE)], -1)
            cv2.circle(img, centre, radius, OUTLINE, 2)
    for obj in objects:
        cv2.circle(img, px(float(obj.position[0]), float(obj.position[1])), 3, OBJECT_DOT, -1)
    for room in rooms:
        if room.position is not None and room.label:
            _put_label(img, room.label, px(float(room.position[0]), float(room.position[1])))
    return img, tf


def encode_png(img: np.ndarray) -> bytes:
    """PNG bytes of a BGR picture."""
    ok, buf = cv2.imencode(".png", img)
    if not ok:
        raise ValueError("PNG encoding failed")
    return bytes(buf.tobytes())
