"""A TF tree gathered from a bag's ``/tf`` and ``/tf_static`` messages, with lookups of
``T_parent_child`` at a time through the chain of frames between them."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from inherit_sg.ingest.readers.tum import pose_at


@dataclass
class _Edge:
    """The transform from ``parent`` to one child frame: fixed, or samples over time."""

    parent: str
    static: np.ndarray | None = None
    times: list[float] = field(default_factory=list)
    mats: list[np.ndarray] = field(default_factory=list)

    def at(self, t: float, max_dt: float) -> np.ndarray | None:
        if self.static is not None:
            return self.static
        return pose_at(t, self.times, self.mats, max_dt)


class TfTree:
    """Transforms by child frame (every frame has at most one parent, as in ROS)."""

    def __init__(self) -> None:
        self._edges: dict[str, _Edge] = {}

    def add(self, parent: str, child: str, t: float, matrix: np.ndarray, static: bool) -> None:
        """Record ``T_parent_child`` at time ``t`` (seconds); a static transform holds at
        every time. A dynamic sample replaces an earlier static one for the same child."""
        edge = self._edges.get(child)
        if edge is None or edge.parent != parent:
            edge = self._edges[child] = _Edge(parent)
        if static:
            if not edge.times:
                edge.static = matrix
            return
        edge.static = None
        edge.times.append(t)
        edge.mats.append(matrix)

    def finish(self) -> None:
        """Sort each dynamic edge's samples by time (call after the last :meth:`add`)."""
        for edge in self._edges.values():
            order = np.argsort(edge.times, kind="stable")
            edge.times = [edge.times[i] for i in order]
            edge.mats = [edge.mats[i] for i in order]

    @property
    def frames(self) -> list[str]:
        """Every frame named in the tree, sorted."""
        return sorted({*self._edges, *(e.parent for e in self._edges.values())})

    def chain(self, frame: str) -> list[str]:
        """``frame`` and its ancestors up to its tree's root."""
        out = [frame]
        while out[-1] in self._edges and len(out) <= len(self._edges):
            out.append(self._edges[out[-1]].parent)
        return out

    def root(self, frame: str) -> str:
        """The root of ``frame``'s tree."""
        return self.chain(frame)[-1]

    def connected(self, parent: str, child: str) -> bool:
        """Whether both frames hang in one tree."""
        return self.root(parent) == self.root(child)

    def is_dynamic(self, parent: str, child: str) -> bool:
        """Whether any transform between the two frames changes over time."""
        ancestors = set(self.chain(parent)) & set(self.chain(child))
        edges = [f for f in (*self.chain(parent), *self.chain(child)) if f not in ancestors]
        return any(self._edges[f].static is None for f in edges)

    def _from_root(self, frame: str, t: float, max_dt: float) -> np.ndarray | None:
        out = np.eye(4)
        for child in self.chain(frame)[:-1]:
            step = self._edges[child].at(t, max_dt)
            if step is None:
                return None
            out = step @ out
        return out

    def lookup(self, parent: str, child: str, t: float, max_dt: float) -> np.ndarray | None:
        """``T_parent_child`` at ``t``: dynamic transforms are interpolated between samples
        within ``max_dt`` (else the nearest within ``max_dt``); None when one is missing."""
        root_child = self._from_root(child, t, max_dt)
        root_parent = self._from_root(parent, t, max_dt)
        if root_child is None or root_parent is None:
            return None
        return np.linalg.inv(root_parent) @ root_child
