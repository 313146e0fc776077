"""The object layer of the working set: integrates keyframe observations into tracked
object nodes (association + fusion), allocates ids, and removes duplicates."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np

from inherit_sg.mapping.association import AssociationParams, Match, associate
from inherit_sg.mapping.backproject import Observation
from inherit_sg.mapping.fusion import fuse, merge_tracked
from inherit_sg.mapping.tracked import TrackedObject
from inherit_sg.model import BBox3D, Layer, ObjectNode, ObjectStatus, make_id

LabelSimilarity = Callable[[str, str], float]


@dataclass
class IntegrationResult:
    """What one keyframe did to the object layer."""

    matched: list[Match] = field(default_factory=list)
    created: list[str] = field(default_factory=list)


class ObjectMap:
    """Tracked objects by id, with association, fusion and duplicate removal."""

    def __init__(
        self,
        label_similarity: LabelSimilarity,
        params: AssociationParams | None = None,
        next_index: int = 0,
    ) -> None:
        self.objects: dict[str, TrackedObject] = {}
        self.params = params or AssociationParams()
        self._label_similarity = label_similarity
        self._next = next_index
        self.removed: list[str] = []

    def __len__(self) -> int:
        return len(self.objects)

    def new_id(self) -> str:
        """Allocate a fresh object id."""
        self._next += 1
        return make_id(Layer.OBJECT, self._next)

    def adopt(self, node: ObjectNode, floor_id: str | None = None) -> TrackedObject:
        """Bring an existing (stored) node into the working set, e.g. for a new session."""
        lo, hi = np.asarray(node.bbox.min), np.asarray(node.bbox.max)
        grid = np.stack(np.meshgrid(*[np.linspace(lo[i], hi[i], 3) for i in range(3)]), -1).reshape(
            -1, 3
        )
        obj = TrackedObject(
            node=node,
            points=grid,
            label_votes=Counter({node.label: max(1, node.observation_count)}),
            floor_id=floor_id or node.floor_id,
            dirty=False,
        )
        self.objects[node.id] = obj
        index = node.id.partition(":")[2]
        if index.isdigit():
            self._next = max(self._next, int(index))
        return obj

    def candidates(self, floor_id: str | None) -> list[TrackedObject]:
        """Active objects that an observation on ``floor_id`` may match."""
        return [
            o
            for o in self.objects.values()
            if o.node.status is not ObjectStatus.REMOVED
            and (floor_id is None or o.floor_id in (None, floor_id))
        ]

    def integrate(
        self, observations: Sequence[Observation], floor_id: str | None
    ) -> IntegrationResult:
        """Associate a keyframe's observations and fuse or create nodes."""
        result = IntegrationResult()
        matches = associate(
            observations, self.candidates(floor_id), self.params, self._label_similarity
        )
        matched_obs = {m.observation for m in matches}
        for m in matches:
            obj = self.objects[m.node_id]
            fuse(obj, observations[m.observation])
            if obj.node.status is ObjectStatus.MISSING:
                obj.node.status = ObjectStatus.ACTIVE
        result.matched = matches
        for i, obs in enumerate(observations):
            if i in matched_obs:
                continue
            node = ObjectNode(
                id=self.new_id(),
                label=obs.label,
                position=tuple(float(v) for v in obs.centroid),  # type: ignore[arg-type]
                bbox=obs.bbox,
                visual_feature=obs.visual_feature,
                keyframe_ids=[obs.keyframe_id] if obs.keyframe_id else [],
                best_keyframe=obs.keyframe_id or None,
                observation_count=1,
                first_seen=obs.timestamp,
                last_seen=obs.timestamp,
                floor_id=floor_id,
            )
            obj = TrackedObject(
                node=node,
                points=obs.points,
                label_votes=Counter({obs.label: 1}),
                best_offset=obs.centre_offset,
                floor_id=floor_id,
            )
            self.objects[node.id] = obj
            result.created.append(node.id)
        return result

    def remove_duplicates(
        self, min_overlap: float = 0.5, min_iou: float = 0.25
    ) -> list[tuple[str, str]]:
        """Merge same-label nodes whose boxes overlap strongly (split masks, drift), or
        that are overlapping pieces of one long object (see :func:`pieces_of_one`).
        Returns (kept, dropped) pairs; dropped ids are listed in ``self.removed``."""
        merged: list[tuple[str, str]] = []
        by_label: dict[tuple[str, str | None], list[TrackedObject]] = {}
        for obj in self.objects.values():
            by_label.setdefault((obj.label, obj.floor_id), []).append(obj)
        for group in by_label.values():
            group.sort(key=lambda o: -o.node.observation_count)
            alive = list(group)
            i = 0
            while i < len(alive):
                keep = alive[i]
                j = i + 1
                while j < len(alive):
                    other = alive[j]
                    inter = keep.node.bbox.intersection_volume(other.node.bbox)
                    smaller = max(min(keep.node.bbox.volume, other.node.bbox.volume), 1e-6)
                    if (
                        inter / smaller >= min_overlap
                        or keep.node.bbox.iou(other.node.bbox) >= min_iou
                        or pieces_of_one(keep.node.bbox, other.node.bbox)
                    ):
                        merge_tracked(keep, other)
                        del self.objects[other.id]
                        self.removed.append(other.id)
                        merged.append((keep.id, other.id))
                        alive.pop(j)
                    else:
                        j += 1
                i += 1
        return merged

    def nodes(self) -> Iterable[ObjectNode]:
        """Current object nodes."""
        return (o.node for o in self.objects.values())


def pieces_of_one(a: BBox3D, b: BBox3D, same_extent: float = 0.75, min_shared: float = 0.3) -> bool:
    """Whether two boxes look like overlapping pieces of one long object: a staircase, a
    counter or a bed seen a part at a time. They match in two axes (1-D overlap over union
    at least ``same_extent``) and overlap along the third by at least ``min_shared`` of the
    shorter piece. Neighbours standing side by side (chairs at a table, pillows on a sofa)
    touch at most, so they do not qualify."""
    shared = np.clip(np.minimum(a.max, b.max) - np.maximum(a.min, b.min), 0.0, None)
    union = np.maximum(a.max, b.max) - np.minimum(a.min, b.min)
    shorter = np.maximum(np.minimum(a.size, b.size), 1e-6)
    matched = shared / np.maximum(union, 1e-6) >= same_extent
    if int(matched.sum()) < 2:
        return False
    return bool(np.all(matched | (shared / shorter >= min_shared)))
