"""Perception noise: what a real segmenter and depth sensor would get wrong.

A rendered frame's instance image and labels are degraded with a seeded generator.
Rates of the ``noisy`` level (``clean`` leaves everything unchanged):

| effect           | noisy rate                  | what happens                                       |
|------------------|-----------------------------|----------------------------------------------------|
| dropped mask     | 10 % of instances           | its pixels become 0 (not segmented)                |
| split mask       | 5 % of instances            | cut in two ids across its longer image axis        |
| merged masks     | 5 % of instances            | it and a touching instance share one id and the    |
|                  |                             | label of the larger                                |
| label synonym    | 15 % of masks               | another word for the same kind ("couch" for sofa)  |
| label confusion  | 5 % of masks                | a similar-looking kind ("stool" for chair)         |
| depth noise      | every pixel                 | Gaussian, σ = 1 cm · (depth / 1 m)²                |
| depth dropout    | 0.5 % of pixels             | depth 0 (no reading)                               |
| pose drift       | every frame                 | random walk of the written pose: 3 mm and 0.05° of |
|                  |                             | yaw per frame (rendering uses the true pose)       |

Independently of the level, :func:`renumber` gives every frame's instances fresh ids
(a seeded random permutation of 1..n), so ids never link observations across frames.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from inherit_sg.ingest.synthetic.confusions import CONFUSIONS
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS
from inherit_sg.model import Pose


@dataclass(frozen=True)
class NoiseConfig:
    """Rates and magnitudes of every effect (see the module table)."""

    drop: float = 0.0
    split: float = 0.0
    merge: float = 0.0
    synonym: float = 0.0
    confusion: float = 0.0
    depth_sigma_1m: float = 0.0  # metres of noise at 1 m, growing with depth²
    depth_dropout: float = 0.0
    drift_m: float = 0.0  # per-frame random walk of the written position
    drift_yaw_deg: float = 0.0


LEVELS: dict[str, NoiseConfig] = {
    "clean": NoiseConfig(),
    "noisy": NoiseConfig(
        drop=0.10,
        split=0.05,
        merge=0.05,
        synonym=0.15,
        confusion=0.05,
        depth_sigma_1m=0.01,
        depth_dropout=0.005,
        drift_m=0.003,
        drift_yaw_deg=0.05,
    ),
}


def noise_config(level: str) -> NoiseConfig:
    """The configuration of a named level (``clean`` or ``noisy``)."""
    try:
        return LEVELS[level]
    except KeyError:
        raise ValueError(f"unknown noise level {level!r}; choose one of {sorted(LEVELS)}") from None


def _split(sub: np.ndarray, k: int, new_id: int) -> bool:
    """Cut instance ``k`` of the image window ``sub`` in two across its longer axis."""
    rows, cols = np.nonzero(sub == k)
    if len(rows) < 2:
        return False
    half = cols > np.median(cols) if np.ptp(cols) >= np.ptp(rows) else rows > np.median(rows)
    if not half.any() or half.all():
        return False
    sub[rows[half], cols[half]] = new_id
    return True


def _grow(window: tuple[slice, ...], by: int, shape: tuple[int, ...]) -> tuple[slice, slice]:
    return (
        slice(max(window[0].start - by, 0), min(window[0].stop + by, shape[0])),
        slice(max(window[1].start - by, 0), min(window[1].stop + by, shape[1])),
    )


def _union(a: tuple[slice, ...], b: tuple[slice, ...]) -> tuple[slice, slice]:
    return (
        slice(min(a[0].start, b[0].start), max(a[0].stop, b[0].stop)),
        slice(min(a[1].start, b[1].start), max(a[1].stop, b[1].stop)),
    )


def _neighbour(
    ids: np.ndarray, k: int, window: tuple[slice, ...], rng: np.random.Generator
) -> int | None:
    """A random other instance touching ``k`` (within 2 pixels)."""
    area = ids[_grow(window, 3, ids.shape)]
    mask = area == k
    ring = ndimage.binary_dilation(mask, iterations=2) & ~mask
    around = np.unique(area[ring])
    around = around[(around != 0) & (around != k)]
    return int(rng.choice(around)) if len(around) else None


def relabel(label: str, config: NoiseConfig, rng: np.random.Generator) -> str:
    """Maybe swap a label for a synonym or a confusable kind."""
    u = rng.random()
    if u < config.synonym:
        kind = OBJECT_KINDS.get(label)
        words = [w for w in (kind.synonyms if kind else ()) if w != label]
        return str(rng.choice(words)) if words else label
    if u < config.synonym + config.confusion and CONFUSIONS.get(label):
        return str(rng.choice(CONFUSIONS[label]))
    return label


def degrade_instances(
    instances: np.ndarray, labels: dict[int, str], config: NoiseConfig, rng: np.random.Generator
) -> tuple[np.ndarray, dict[int, str]]:
    """Drop, split and merge masks and perturb labels; returns a new image and labels.

    ``labels`` must name every id present in ``instances``.
    """
    ids = instances.astype(np.int32)
    present = [int(k) for k in np.flatnonzero(np.bincount(ids.ravel())) if k != 0]
    out_labels = {k: labels[k] for k in present}
    if config.drop + config.split + config.merge > 0:
        windows = dict(enumerate(ndimage.find_objects(ids), start=1))
        next_id = max(present, default=0) + 1
        for k in present:
            u = rng.random()
            if k not in out_labels:
                continue  # merged into a neighbour already
            window = windows[k]
            assert window is not None
            sub = ids[window]
            if u < config.drop:
                sub[sub == k] = 0
                del out_labels[k]
            elif u < config.drop + config.split:
                if _split(sub, k, next_id):
                    out_labels[next_id] = out_labels[k]
                    next_id += 1
            elif u < config.drop + config.split + config.merge:
                other = _neighbour(ids, k, window, rng)
                if other is None or windows.get(other) is None:
                    continue
                both = _union(window, windows[other])
                sizes = {j: int((ids[both] == j).sum()) for j in (k, other)}
                keep, gone = (k, other) if sizes[k] >= sizes[other] else (other, k)
                area = ids[both]
                area[area == gone] = keep
                windows[keep] = both
                out_labels.pop(gone, None)
    for k in list(out_labels):
        out_labels[k] = relabel(out_labels[k], config, rng)
    return ids, out_labels


def degrade_depth(depth: np.ndarray, config: NoiseConfig, rng: np.random.Generator) -> np.ndarray:
    """Depth-dependent Gaussian noise and random dropouts (0 stays 0)."""
    if config.depth_sigma_1m <= 0 and config.depth_dropout <= 0:
        return depth
    valid = depth > 0
    noisy = depth + rng.normal(0.0, 1.0, depth.shape).astype(np.float32) * (
        np.float32(config.depth_sigma_1m) * depth * depth
    )
    noisy[rng.random(depth.shape) < config.depth_dropout] = 0.0
    return np.where(valid, np.clip(noisy, 0.0, None), 0.0).astype(np.float32)


def renumber(
    instances: np.ndarray, labels: dict[int, str], rng: np.random.Generator
) -> tuple[np.ndarray, dict[int, str]]:
    """Give the instances present fresh ids 1..n in random order (uint16 image)."""
    flat = instances.ravel()
    present = np.flatnonzero(np.bincount(flat))
    present = present[present != 0]
    fresh = rng.permutation(len(present)) + 1
    lut = np.zeros(int(flat.max(initial=0)) + 1, dtype=np.uint16)
    lut[present] = fresh
    out = lut[instances]
    return out, {int(f): labels[int(k)] for k, f in zip(present, fresh, strict=True)}


class PoseDrift:
    """A random walk added to the written poses (odometry drift)."""

    def __init__(self, config: NoiseConfig, rng: np.random.Generator) -> None:
        self.config = config
        self.rng = rng
        self.offset = np.zeros(3)
        self.yaw = 0.0

    def apply(self, pose: Pose) -> Pose:
        """The drifted version of the next pose in the sequence."""
        c = self.config
        if c.drift_m <= 0 and c.drift_yaw_deg <= 0:
            return pose
        self.offset += self.rng.normal(0.0, c.drift_m, 3) * np.array([1.0, 1.0, 0.3])
        self.yaw += math.radians(float(self.rng.normal(0.0, c.drift_yaw_deg)))
        cy, sy = math.cos(self.yaw), math.sin(self.yaw)
        turn = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
        m = pose.matrix
        m[:3, :3] = turn @ m[:3, :3]
        m[:3, 3] = m[:3, 3] + self.offset
        return Pose.from_matrix(m)
