"""Working-set state of one object node: the persisted :class:`ObjectNode` plus what
only mapping needs (fused points, label votes, per-keyframe view quality)."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from inherit_sg.model import ObjectNode


@dataclass
class TrackedObject:
    """An object node with its fused observation state."""

    node: ObjectNode
    points: np.ndarray  # (N, 3) voxel-downsampled world points fused from all views
    label_votes: Counter[str] = field(default_factory=Counter)
    best_offset: float = 1e9  # centre offset of the best keyframe so far (lower is better)
    floor_id: str | None = None
    dirty: bool = True  # changed since the last flush

    @property
    def id(self) -> str:
        """Node id."""
        return self.node.id

    @property
    def label(self) -> str:
        """Majority label over all observations (ties: first seen)."""
        return self.label_votes.most_common(1)[0][0] if self.label_votes else self.node.label
