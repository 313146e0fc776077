"""Classical class-agnostic segmenter for unlabelled RGB-D data.

1. drop structural planes (floor, walls, ceiling) found by RANSAC-lite on the depth;
2. cut the rest along depth discontinuities and along chromatic edges (changes of Lab
   a/b, which shading and lightness patterns do not cause);
3. connected components of what is left, opened to break thin bridges, filtered by
   size, become masks labelled "object"; the score is how well a component stands out
   in depth from its surroundings.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from inherit_sg.model import Frame
from inherit_sg.perception.base import Detection, make_detection
from inherit_sg.perception.planes import backproject, structural_planes

_KERNEL = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (3, 3))


def depth_edges(depth: np.ndarray, rel: float = 0.03, abs_m: float = 0.02) -> np.ndarray:
    """Pixels whose depth jumps against a 4-neighbour by more than ``abs_m + rel·z``."""
    edges = np.zeros(depth.shape, dtype=bool)
    for dy, dx in ((0, 1), (1, 0)):
        a = depth[: depth.shape[0] - dy, : depth.shape[1] - dx]
        b = depth[dy:, dx:]
        jump = np.abs(a - b) > abs_m + rel * np.minimum(a, b)
        jump |= (a > 0) != (b > 0)
        edges[: depth.shape[0] - dy, : depth.shape[1] - dx] |= jump
        edges[dy:, dx:] |= jump
    return edges


def chroma_edges(rgb: np.ndarray, threshold: float = 12.0) -> np.ndarray:
    """Pixels where the Lab a/b channels change sharply (object colour boundaries)."""
    lab = cv2.cvtColor(cv2.GaussianBlur(rgb, (3, 3), 0), cv2.COLOR_RGB2LAB).astype(np.float32)
    mag = np.zeros(rgb.shape[:2], dtype=np.float32)
    for c in (1, 2):
        gx = cv2.Sobel(lab[..., c], cv2.CV_32F, 1, 0, ksize=3)
        gy = cv2.Sobel(lab[..., c], cv2.CV_32F, 0, 1, ksize=3)
        mag += gx * gx + gy * gy
    return np.sqrt(mag) / 4.0 > threshold


class ClassicalSegmenter:
    """Depth + colour segmentation with structural-plane rejection (label "object")."""

    def __init__(
        self,
        min_pixels: int = 50,
        min_fraction: float = 0.0005,
        max_fraction: float = 0.5,
        use_colour: bool = True,
        seed: int = 0,
    ) -> None:
        self.name = "classical"
        self._min_pixels = min_pixels
        self._min_fraction = min_fraction
        self._max_fraction = max_fraction
        self._use_colour = use_colour
        self._seed = seed

    def segment(self, frame: Frame, prompts: Sequence[str] | None = None) -> list[Detection]:
        """Class-agnostic masks, largest first. Prompts other than generic words
        ("object", "thing", "item") cannot be honoured and give no detections."""
        if prompts and not {p.strip().lower() for p in prompts} & {"object", "thing", "item"}:
            return []
        depth = frame.depth
        valid = depth > 0
        points = backproject(depth, frame.intrinsics)
        structure = structural_planes(points, valid, seed=self._seed)
        cut = depth_edges(depth)
        if self._use_colour:
            cut |= chroma_edges(frame.rgb)
        free = (valid & ~structure & ~cut).astype(np.uint8)
        free = cv2.morphologyEx(free, cv2.MORPH_OPEN, _KERNEL)
        n, labels, stats, _ = cv2.connectedComponentsWithStats(free, connectivity=4)
        lo = max(self._min_pixels, int(self._min_fraction * depth.size))
        hi = self._max_fraction * depth.size
        boundary = structure | cut
        h, w = depth.shape
        out: list[Detection] = []
        for i in range(1, n):
            x, y, bw, bh, area = (int(v) for v in stats[i])
            if area < lo or area > hi:
                continue
            # work in the component's window grown by the ring width
            win = (
                slice(max(0, y - 3), min(h, y + bh + 3)),
                slice(max(0, x - 3), min(w, x + bw + 3)),
            )
            local = labels[win] == i
            mask = np.zeros((h, w), dtype=bool)
            mask[win] = local
            score = self._standout(local, depth[win], boundary[win])
            det = make_detection(mask, "object", score)
            if det is not None:
                out.append(det)
        out.sort(key=lambda d: d.area, reverse=True)
        return out

    @staticmethod
    def _standout(mask: np.ndarray, depth: np.ndarray, boundary: np.ndarray) -> float:
        """Share of the ring around the mask that is farther away, a cut or structure."""
        ring = cv2.dilate(mask.view(np.uint8), _KERNEL, iterations=2).astype(bool) & ~mask
        if not ring.any():
            return 0.0
        z = float(np.median(depth[mask]))
        behind = (depth[ring] > z + 0.03) | boundary[ring] | (depth[ring] == 0)
        return float(np.clip(0.2 + 0.8 * behind.mean(), 0.0, 1.0))
