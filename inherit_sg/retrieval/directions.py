"""Viewer-relative relations: ``left_of``, ``right_of``, ``in_front_of`` and ``behind``
decided from box centres as a :class:`~inherit_sg.retrieval.viewer.View` sees them.

For a candidate t and a landmark L (both objects, on one floor, in the same room when
both rooms are known, footprints at most ``DIRECTION_RANGE`` apart), the centres'
difference ``d = c_t - c_L`` is split into the lateral part ``d·r`` and the depth part
``d·f``. The wanted axis (lateral for left / right, depth for front / behind; "in front
of" = between the viewer and L = smaller depth) must point the right way; the score
grows with how far it exceeds the boxes' half-extents along that axis (1 once the boxes
no longer overlap along it). When the difference along the other axis is larger than
along the wanted one (a chair mostly behind the table is not "left of" it), the score
falls off linearly, reaching 0 at ``OFF_AXIS`` metres of excess. The relation's
similarity is the best ``quality(L) × score`` over the landmark candidates.

``facing`` keeps the ``near`` approximation of :mod:`~inherit_sg.retrieval.graph_checks`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from inherit_sg.retrieval.graph_checks import Landmarks
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.retrieval.viewer import View

VIEW_PREDICATES = frozenset({"left_of", "right_of", "in_front_of", "behind"})
# Footprints farther apart than this (m) are not in a viewer-relative relation.
DIRECTION_RANGE = 2.5
# Excess of the other axis over the wanted one (m) at which the score reaches 0.
OFF_AXIS = 1.5
# Half-extent sums below this (m) are treated as this (thin boxes, points).
MIN_EXTENT = 0.05
_WORDS = {
    "left_of": "left of",
    "right_of": "right of",
    "in_front_of": "in front of",
    "behind": "behind",
}


def half_extents(size: np.ndarray, axis: tuple[float, float]) -> np.ndarray:
    """Half-extents of axis-aligned boxes of horizontal ``size`` (n, ≥2) along a unit
    horizontal ``axis``."""
    return 0.5 * (abs(axis[0]) * size[:, 0] + abs(axis[1]) * size[:, 1])


def directional_all(
    snap: MapSnapshot,
    view: View,
    nodes: Sequence[str],
    predicate: str,
    landmarks: Landmarks,
) -> dict[str, tuple[float, str]]:
    """``predicate(node, landmark)`` for every object in ``nodes`` (only those where it
    holds): the best ``quality × score`` with its evidence in words."""
    objs = [n for n in nodes if n in snap.obj_index]
    if not objs or predicate not in VIEW_PREDICATES:
        return {}
    rows = np.array([snap.obj_index[n] for n in objs], dtype=int)
    lo, hi = snap.lo[rows], snap.hi[rows]
    centre = snap.centre[rows, :2]
    size = hi - lo
    right, fwd = view.right, view.forward
    lateral_axis = predicate in ("left_of", "right_of")
    main_axis, other_axis = (right, fwd) if lateral_axis else (fwd, right)
    sign = 1.0 if predicate in ("right_of", "behind") else -1.0
    ext_main_t = half_extents(size, main_axis)
    ext_other_t = half_extents(size, other_axis)
    rooms = [snap.room_of.get(n) for n in objs]
    out: dict[str, tuple[float, str]] = {}
    for lid, quality in landmarks:
        j = snap.obj_index.get(lid)
        if j is None or quality <= 0.0:
            continue
        lsize = (snap.hi[j] - snap.lo[j]).reshape(1, 3)
        ext_main = np.maximum(ext_main_t + half_extents(lsize, main_axis)[0], MIN_EXTENT)
        ext_other = ext_other_t + half_extents(lsize, other_axis)[0]
        d = centre - snap.centre[j, :2]
        main = sign * (d @ np.asarray(main_axis))
        other = np.abs(d @ np.asarray(other_axis))
        dx = np.maximum(0.0, np.maximum(lo[:, 0] - snap.hi[j, 0], snap.lo[j, 0] - hi[:, 0]))
        dy = np.maximum(0.0, np.maximum(lo[:, 1] - snap.hi[j, 1], snap.lo[j, 1] - hi[:, 1]))
        lroom = snap.room_of.get(lid)
        same_room = np.array([r is None or lroom is None or r == lroom for r in rooms])
        near = (np.hypot(dx, dy) <= DIRECTION_RANGE) & (snap.level[rows] == snap.level[j])
        clear = np.clip(main / ext_main, 0.0, 1.0)
        excess = np.maximum(0.0, other - ext_other) - np.maximum(0.0, main - ext_main)
        factor = np.clip(1.0 - np.maximum(0.0, excess) / OFF_AXIS, 0.0, 1.0)
        score = np.where(near & same_room & (main > 0.0), clear * factor, 0.0) * quality
        for i in np.flatnonzero(score > 0.0):
            node = objs[i]
            if node == lid or score[i] <= out.get(node, (0.0, ""))[0]:
                continue
            why = (
                f"{node} is {main[i]:.2f} m {_WORDS[predicate]} {lid} "
                f"(clear {clear[i]:.2f}, on-axis {factor[i]:.2f}; {view.source} view)"
            )
            out[node] = (float(score[i]), why)
    return out
