"""Multi-session bookkeeping: an object from an earlier session whose place comes into
clear view without the object being seen again is marked ``missing`` (kept, not
deleted); seeing it again makes it active."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable

import numpy as np

from inherit_sg.model import Frame, ObjectNode, ObjectStatus

MIN_VIEWS = 2  # keyframes that must show the place before the object counts as missing
DEPTH_TOLERANCE = 0.35  # metres: slack for depth noise when testing for occluders
MAX_RANGE = 6.0  # metres: farther places are not "in clear view"


class MissingTracker:
    """Counts, per earlier object, keyframes that showed its place."""

    def __init__(self, earlier: Iterable[ObjectNode]) -> None:
        self.earlier = {o.id: o for o in earlier}
        self.views: Counter[str] = Counter()
        self.seen: set[str] = set()

    def observed(self, object_ids: Iterable[str]) -> None:
        """Objects re-observed in this session."""
        self.seen.update(object_ids)

    def check_frame(self, frame: Frame) -> None:
        """Count keyframes whose view covers the place of unseen earlier objects."""
        todo = [o for oid, o in self.earlier.items() if oid not in self.seen]
        if not todo:
            return
        centres = np.array([o.position for o in todo], dtype=float)
        inv = np.linalg.inv(frame.pose.matrix)
        cam = centres @ inv[:3, :3].T + inv[:3, 3]
        k = frame.intrinsics
        z = cam[:, 2]
        ok = z > 0.3
        u = np.where(ok, k.fx * cam[:, 0] / np.where(ok, z, 1) + k.cx, -1)
        v = np.where(ok, k.fy * cam[:, 1] / np.where(ok, z, 1) + k.cy, -1)
        margin = 0.1
        inside = ok & (u >= margin * k.width) & (u < (1 - margin) * k.width)
        inside &= (v >= margin * k.height) & (v < (1 - margin) * k.height)
        for i in np.nonzero(inside)[0]:
            d = float(frame.depth[int(v[i]), int(u[i])])
            # nothing stands in front of the place (the object, or what is behind it, is seen)
            if (
                d > 0
                and z[i] <= MAX_RANGE
                and d >= z[i] - DEPTH_TOLERANCE - 0.5 * max(todo[i].bbox.size)
            ):
                self.views[todo[i].id] += 1

    def finish(self) -> list[str]:
        """Mark unseen-but-viewed earlier objects missing; returns their ids."""
        missing = []
        for oid, node in self.earlier.items():
            if oid in self.seen:
                node.status = ObjectStatus.ACTIVE
            elif self.views[oid] >= MIN_VIEWS and node.status is not ObjectStatus.REMOVED:
                node.status = ObjectStatus.MISSING
                missing.append(oid)
        return missing
