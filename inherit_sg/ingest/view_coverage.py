"""Where a walker must stop so that its look-arounds see the whole of a room.

A person filming a room for a scan does not stand only in its middle: a bed or a sofa
hides what stands behind it, and an L-shaped room has a corner that the middle does not
see. The plan view answers where to stand. A spot of the room counts as *seen* from a
stop when it lies within :data:`SIGHT_M` and the straight line to it crosses no wall and
no furniture footprint, except in the last :data:`OWN_M` before the spot (the footprint
the spot belongs to, or the thing right in front of it). Stops are then chosen greedily
from the reachable cells of the room: the first is the walker's usual roomy spot near the
middle; each further stop is the one that sees most of what is still unseen, while the
room is less than :data:`COVER_GOAL` seen, that stop adds at least :data:`MIN_GAIN` of
the room, and the room has fewer than :data:`MAX_STOPS` stops.

This only uses the occupancy of the plan (walls and furniture footprints), the same map
a robot's exploration planner holds; it never looks at what the objects are.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SIGHT_M = 4.0  # a spot farther than this is not seen well enough to count
OWN_M = 0.6  # blockers this close to the spot do not hide it
COVER_GOAL = 0.85  # share of the room seen before the walker moves on
MIN_GAIN = 0.1  # a further stop must see at least this share of the room anew
MAX_STOPS = 4  # stops per room at most
TARGET_STEP_M = 0.2  # spacing of the room spots whose sight is tested
STOP_STEP_M = 0.3  # spacing of the candidate stops


def _subsample(mask: np.ndarray, stride: int) -> np.ndarray:
    """Cells of ``mask`` on a lattice of ``stride`` cells, as (N, 2) rows and columns."""
    keep = np.zeros_like(mask)
    keep[::stride, ::stride] = True
    return np.argwhere(mask & keep)


def sight(
    blocked: np.ndarray,
    origin: tuple[int, int],
    targets: np.ndarray,
    res: float,
    sight_m: float = SIGHT_M,
) -> np.ndarray:
    """Which ``targets`` ((N, 2) cells) are seen from cell ``origin`` (see the module
    docstring): within ``sight_m``, and no blocked cell on the line before the last
    :data:`OWN_M`."""
    if len(targets) == 0:
        return np.zeros(0, dtype=bool)
    o = np.asarray(origin, dtype=float)
    delta = targets.astype(float) - o
    length = np.hypot(delta[:, 0], delta[:, 1]) * res
    near = length <= sight_m
    steps = max(int(np.ceil(sight_m / res)), 1)
    t = np.linspace(0.0, 1.0, steps + 1)[None, :]
    # Distance along the line left to the target at each sample; samples in the last
    # OWN_M (or past a target nearer than the sample spacing) are not tested.
    left = (1.0 - t) * length[:, None]
    pts = o[None, None, :] + t[:, :, None] * delta[:, None, :]
    rows = np.clip(np.rint(pts[..., 0]).astype(int), 0, blocked.shape[0] - 1)
    cols = np.clip(np.rint(pts[..., 1]).astype(int), 0, blocked.shape[1] - 1)
    hit = blocked[rows, cols] & (left > OWN_M)
    return near & ~hit.any(axis=1)


@dataclass(frozen=True)
class CoverageGoal:
    """When to stop adding stops: a spot counts as seen within ``sight_m``; stops are
    added while less than ``goal`` of the spots is seen, a further stop sees at least
    ``min_gain`` of them anew, and there are fewer than ``max_stops``."""

    sight_m: float = SIGHT_M
    goal: float = COVER_GOAL
    min_gain: float = MIN_GAIN
    max_stops: int = MAX_STOPS


def coverage_stops(
    room: np.ndarray,
    reach: np.ndarray,
    blocked: np.ndarray,
    res: float,
    first: tuple[int, int],
    spots: np.ndarray | None = None,
    aim: CoverageGoal = CoverageGoal(),
) -> list[tuple[int, int]]:
    """Stops (grid cells) from which look-arounds see ``room`` (a boolean mask), starting
    with ``first``; further stops are reachable cells of the room (see the module
    docstring). ``blocked`` marks what hides things (walls, furniture footprints);
    ``spots`` the cells to be seen (default: the room's unblocked cells)."""
    wanted = room & ~blocked if spots is None else spots
    targets = _subsample(wanted, max(round(TARGET_STEP_M / res), 1))
    if len(targets) == 0:
        return [first]
    candidates = _subsample(room & reach, max(round(STOP_STEP_M / res), 1))
    covered = sight(blocked, first, targets, res, aim.sight_m)
    stops = [first]
    if len(candidates) == 0:
        return stops
    seen = np.stack(
        [sight(blocked, (int(i), int(j)), targets, res, aim.sight_m) for i, j in candidates]
    )
    while covered.mean() < aim.goal and len(stops) < aim.max_stops:
        gain = (seen & ~covered).sum(axis=1)
        best = int(np.argmax(gain))
        if gain[best] < aim.min_gain * len(targets):
            break
        stops.append((int(candidates[best][0]), int(candidates[best][1])))
        covered |= seen[best]
    return stops
