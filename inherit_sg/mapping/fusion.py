"""Fusing an observation into an object node.

Points from every view are merged into one voxel set per node, so the box and centre
come from all views together (a sofa seen end by end converges to its true extent);
the visual feature follows a weighted moving average, as in the paper; the keyframe
kept as the node's best view is the one whose mask sits closest to the image centre.
"""

from __future__ import annotations

import numpy as np

from inherit_sg.mapping.backproject import Observation, robust_box, voxel_downsample
from inherit_sg.mapping.tracked import TrackedObject

MAX_POINTS = 3000
MAX_KEYFRAMES = 24
VOXEL = 0.03


def _cap(points: np.ndarray, limit: int) -> np.ndarray:
    if len(points) <= limit:
        return points
    idx = np.linspace(0, len(points) - 1, limit).astype(int)
    return points[idx]


def refresh_geometry(obj: TrackedObject) -> None:
    """Recompute box and centre of ``obj`` from its fused points."""
    box = robust_box(obj.points, 1.0, 99.0)
    obj.node.bbox = box
    obj.node.position = tuple(float(v) for v in box.center)  # type: ignore[assignment]


def fuse(obj: TrackedObject, obs: Observation) -> None:
    """Merge ``obs`` into ``obj`` in place."""
    node = obj.node
    obj.points = _cap(voxel_downsample(np.vstack([obj.points, obs.points]), VOXEL), MAX_POINTS)
    refresh_geometry(obj)
    n = node.observation_count
    if obs.visual_feature is not None:
        if node.visual_feature is None:
            node.visual_feature = obs.visual_feature.astype(np.float32)
        else:
            mixed = (n * node.visual_feature + obs.visual_feature) / (n + 1)
            node.visual_feature = (mixed / (np.linalg.norm(mixed) or 1.0)).astype(np.float32)
    node.observation_count = n + 1
    node.last_seen = max(node.last_seen, obs.timestamp)
    node.first_seen = min(node.first_seen, obs.timestamp)
    obj.label_votes[obs.label] += 1
    node.label = obj.label
    if obs.keyframe_id and obs.keyframe_id not in node.keyframe_ids:
        node.keyframe_ids.append(obs.keyframe_id)
        if len(node.keyframe_ids) > MAX_KEYFRAMES:
            # keep the best view and the most recent ones
            keep = {node.best_keyframe} if node.best_keyframe else set()
            node.keyframe_ids = [k for k in node.keyframe_ids if k in keep] + [
                k for k in node.keyframe_ids[-(MAX_KEYFRAMES - 1) :] if k not in keep
            ]
    if obs.centre_offset < obj.best_offset and obs.keyframe_id:
        obj.best_offset = obs.centre_offset
        node.best_keyframe = obs.keyframe_id
    obj.dirty = True


def merge_tracked(keep: TrackedObject, drop: TrackedObject) -> None:
    """Fold ``drop`` into ``keep`` (duplicate removal)."""
    keep.points = _cap(voxel_downsample(np.vstack([keep.points, drop.points]), VOXEL), MAX_POINTS)
    refresh_geometry(keep)
    a, b = keep.node, drop.node
    if a.visual_feature is not None and b.visual_feature is not None:
        mixed = a.observation_count * a.visual_feature + b.observation_count * b.visual_feature
        a.visual_feature = (mixed / (np.linalg.norm(mixed) or 1.0)).astype(np.float32)
    elif a.visual_feature is None:
        a.visual_feature = b.visual_feature
    a.observation_count += b.observation_count
    a.first_seen = min(a.first_seen, b.first_seen)
    a.last_seen = max(a.last_seen, b.last_seen)
    keep.label_votes.update(drop.label_votes)
    a.label = keep.label
    a.keyframe_ids.extend(k for k in b.keyframe_ids if k not in a.keyframe_ids)
    if drop.best_offset < keep.best_offset:
        keep.best_offset, a.best_keyframe = drop.best_offset, b.best_keyframe
    keep.dirty = True
