"""Floor tracking from the camera height, with hysteresis (paper §III-B, L0).

The camera stays at a near-constant height above the floor it walks on. A sustained
change of at least ``floor_min_height`` that has settled (the last frames agree within
``floor_settle_tol``) is a vertical transition: the tracker re-enters the floor at that
height or creates a new one. Floor levels are the rank of the floor heights (0 = lowest)
and are re-ordered whenever a floor below the known ones appears.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import numpy as np

from inherit_sg.config import GeometryConfig
from inherit_sg.model import NodeId

_MAX_ESTIMATES = 256


@dataclass
class FloorState:
    """What the tracker knows about one floor."""

    id: NodeId
    camera_z: float  # typical camera height on this floor (world z)
    level: int = 0
    estimates: deque[float] = field(default_factory=lambda: deque(maxlen=_MAX_ESTIMATES))
    fallback_eye: float = 1.4

    @property
    def floor_z(self) -> float:
        """Floor surface height: median of per-frame estimates, else from the eye height."""
        if self.estimates:
            return float(np.median(np.fromiter(self.estimates, dtype=np.float64)))
        return self.camera_z - self.fallback_eye


@dataclass(frozen=True)
class FloorTransition:
    """A completed vertical transition between two floors."""

    from_id: NodeId
    to_id: NodeId
    created: bool
    reordered: bool
    start: tuple[float, float, float]  # last settled camera position on the old floor
    end: tuple[float, float, float]  # first settled camera position on the new floor


def estimate_floor_z(z: np.ndarray, camera_z: float, bin_size: float = 0.05) -> float | None:
    """Height of the lowest well-supported horizontal surface below the camera, if any."""
    cand = z[(z > camera_z - 2.5) & (z < camera_z - 0.3)]
    if cand.size < 50:
        return None
    lo = camera_z - 2.5
    bins = ((cand - lo) / bin_size).astype(np.int64)
    counts = np.bincount(bins)
    if counts.max() < 30:  # points spread over heights (a frame that looks up): no surface
        return None
    need = max(30, int(0.25 * counts.max()))
    first = int(np.flatnonzero(counts >= need)[0])
    near = cand[np.abs(cand - (lo + (first + 0.5) * bin_size)) <= bin_size]
    return float(np.median(near))


class FloorTracker:
    """Assigns every frame to a floor and detects floor transitions."""

    def __init__(self, cfg: GeometryConfig, first_id: int = 0) -> None:
        self.cfg = cfg
        self.first_id = first_id
        self.floors: dict[str, FloorState] = {}
        self.current: FloorState | None = None
        self.settled = False
        self._recent: deque[float] = deque(maxlen=cfg.floor_stable_frames)
        self._steady = 0
        self._last_settled: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def ordered(self) -> list[FloorState]:
        """Floors from the lowest up."""
        return sorted(self.floors.values(), key=lambda f: f.level)

    def _new_floor(self, camera_z: float) -> tuple[FloorState, bool]:
        fid = NodeId(f"floor:{self.first_id + len(self.floors)}")
        state = FloorState(fid, camera_z, fallback_eye=self.cfg.default_eye_height)
        self.floors[fid] = state
        before = {f.id: f.level for f in self.floors.values()}
        for level, f in enumerate(sorted(self.floors.values(), key=lambda s: s.camera_z)):
            f.level = level
        reordered = any(self.floors[k].level != v for k, v in before.items() if k != fid)
        return state, reordered

    def update(
        self, position: tuple[float, float, float], floor_estimate: float | None
    ) -> FloorTransition | None:
        """Feed one camera position (and the floor height seen in the frame, if any)."""
        z = position[2]
        if self.current is None:
            self.current, _ = self._new_floor(z)
        cur = self.current
        self._recent.append(z)
        steady = (
            len(self._recent) == self._recent.maxlen
            and max(self._recent) - min(self._recent) <= self.cfg.floor_settle_tol
        )
        self._steady = self._steady + 1 if steady else 0
        dz = z - cur.camera_z
        if abs(dz) <= self.cfg.floor_settle_tol:
            self.settled = True
            cur.camera_z += 0.05 * dz
            self._last_settled = position
            if floor_estimate is not None and self._plausible(cur, z, floor_estimate):
                cur.estimates.append(floor_estimate)
            return None
        self.settled = False
        if not steady:
            return None
        if abs(dz) >= self.cfg.floor_min_height:
            return self._switch(position)
        if self._steady >= 3 * self.cfg.floor_stable_frames:
            # A small lasting height change on the same floor (ramp, new camera mount).
            cur.camera_z = float(np.median(np.fromiter(self._recent, dtype=np.float64)))
        return None

    @staticmethod
    def _plausible(floor: FloorState, z: float, estimate: float) -> bool:
        """Reject floor estimates far from the usual eye height (a table top, a step)."""
        if len(floor.estimates) < 5:
            return True
        return abs((z - estimate) - (floor.camera_z - floor.floor_z)) < 0.5

    def _switch(self, position: tuple[float, float, float]) -> FloorTransition:
        assert self.current is not None
        z = position[2]
        old = self.current
        tol = self.cfg.floor_min_height / 2.0
        match = min(self.floors.values(), key=lambda f: abs(f.camera_z - z))
        created, reordered = False, False
        if abs(match.camera_z - z) > tol:
            match, reordered = self._new_floor(z)
            created = True
        self.current = match
        self.settled = True
        start, self._last_settled = self._last_settled, position
        return FloorTransition(old.id, match.id, created, reordered, start, position)
