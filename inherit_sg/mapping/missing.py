"""Multi-session bookkeeping: an object from an earlier session whose place comes into
clear view without the object being seen again is marked ``missing`` (kept, not
deleted); seeing it again makes it active."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable

import numpy as np

from inherit_sg.model import Frame, ObjectNode, ObjectStatus

MIN_VIEWS = 2  # keyframes that must show the place before the object counts as missing
# metres: slack for depth noise; less than a wall is thick, so what hangs on its far
# side stays hidden
DEPTH_TOLERANCE = 0.1
MAX_RANGE = 6.0  # metres: farther places are not "in clear view"
MIN_INSIDE = 0.75  # share of the object's image that must lie inside the frame
MIN_SIDE = 0.04  # the object's image must be at least this share of the frame wide and high


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
        """Count keyframes that show the place of unseen earlier objects in clear view:
        the whole box in front of the camera, at least :data:`MIN_INSIDE` of its image
        inside the frame, at least :data:`MIN_SIDE` of the image wide and high, within
        :data:`MAX_RANGE`, and nothing standing in front of it (the median depth around
        its centre reaches at least the box's nearest corner, less
        :data:`DEPTH_TOLERANCE`: a wall right in front of a long counter hides it)."""
        todo = [o for oid, o in self.earlier.items() if oid not in self.seen]
        if not todo:
            return
        inv = np.linalg.inv(frame.pose.matrix)
        k = frame.intrinsics
        for node in todo:
            view = _clear_view(node, inv, k.fx, k.fy, k.cx, k.cy, k.width, k.height)
            if view is None:
                continue
            (u, v), nearest = view
            patch = frame.depth[
                max(0, v - 2) : min(k.height, v + 3), max(0, u - 2) : min(k.width, u + 3)
            ]
            valid = patch[patch > 0]
            if not len(valid):
                continue
            if float(np.median(valid)) >= nearest - DEPTH_TOLERANCE:
                self.views[node.id] += 1

    def merged(self, keep: str, drop: str) -> None:
        """Duplicate removal folded ``drop`` into ``keep``: an earlier object that was
        folded away cannot go missing, and being seen carries over to the one kept."""
        if drop in self.seen or drop in self.earlier:
            self.seen.add(keep)
        self.earlier.pop(drop, None)

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


def _clear_view(
    node: ObjectNode,
    world_to_camera: np.ndarray,
    fx: float,
    fy: float,
    cx: float,
    cy: float,
    width: int,
    height: int,
) -> tuple[tuple[int, int], float] | None:
    """The pixel of the object's centre and the depth of its box's nearest corner when the
    object is in clear view of the camera (see :meth:`MissingTracker.check_frame`), else
    None."""
    lo, hi = np.asarray(node.bbox.min), np.asarray(node.bbox.max)
    corners = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    points = np.vstack([np.asarray(node.position, dtype=float), corners])
    cam = points @ world_to_camera[:3, :3].T + world_to_camera[:3, 3]
    if np.any(cam[:, 2] <= 0.3) or cam[0, 2] > MAX_RANGE:
        return None
    u = fx * cam[:, 0] / cam[:, 2] + cx
    v = fy * cam[:, 1] / cam[:, 2] + cy
    box_w, box_h = u[1:].max() - u[1:].min(), v[1:].max() - v[1:].min()
    if box_w < MIN_SIDE * width or box_h < MIN_SIDE * height:
        return None
    inside_w = min(u[1:].max(), width) - max(u[1:].min(), 0.0)
    inside_h = min(v[1:].max(), height) - max(v[1:].min(), 0.0)
    if inside_w <= 0 or inside_h <= 0 or inside_w * inside_h < MIN_INSIDE * box_w * box_h:
        return None
    if not (0 <= u[0] < width and 0 <= v[0] < height):
        return None
    return (int(u[0]), int(v[0])), float(cam[1:, 2].min())
