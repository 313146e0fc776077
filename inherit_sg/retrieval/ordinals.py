"""Ordinals and "the middle one": order a superlative's tier by position and pick one.

The tier is ordered as the viewer sees it: by the lateral coordinate from the ``left``
(or the ``right``), by depth from the ``front`` (nearest first) or the ``back``; an
ordinal without a direction counts outwards — from the landmark when the superlative
has one ("the second chair from the door"), else from the viewer ("the second door").
``middle`` orders left to right (front to back when the direction says so).

The chosen candidate scores 1 and the others ``falloff / (1 + |rank - k|)``, so ties
between equally good candidates are broken by position. Of an even tier's two central
candidates, the one nearer the viewer scores 1 and the other ``runner_up``. An ordinal
beyond the tier takes its last candidate (best effort, with a note).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from inherit_sg.retrieval.constraints import Superlative
from inherit_sg.retrieval.viewer import View

_SUFFIX = {1: "st", 2: "nd", 3: "rd"}


def nth(k: int) -> str:
    """``1st``, ``2nd``, ``3rd``, ``4th`` … (``last`` for -1, ``2nd from last`` …)."""
    if k < 0:
        return "last" if k == -1 else f"{nth(-k)} from last"
    if k % 100 in (11, 12, 13):
        return f"{k}th"
    return f"{k}{_SUFFIX.get(k % 10, 'th')}"


@dataclass
class Placed:
    """Similarities and reasons per tier member (input order), and a note or None."""

    sims: list[float] = field(default_factory=list)
    whys: list[str] = field(default_factory=list)
    note: str | None = None


def _order(
    con: Superlative, xy: np.ndarray, view: View, landmark_dist: np.ndarray | None
) -> tuple[np.ndarray, str, np.ndarray]:
    """Sort keys (ascending = counted first), what they measure, and the values shown."""
    direction = con.direction
    if con.measure == "middle" and direction not in ("front", "back"):
        direction = "left"
    if direction in ("left", "right"):
        lat = view.lateral(xy)
        return (lat if direction == "left" else -lat), "lateral", lat
    if direction in ("front", "back"):
        dep = view.depth(xy)
        return (dep if direction == "front" else -dep), "depth", dep
    if landmark_dist is not None:
        return landmark_dist, "distance to the landmark", landmark_dist
    dist = view.distance(xy)
    return dist, "distance from the viewer", dist


def place(
    con: Superlative,
    ids: list[str],
    xy: np.ndarray,
    view: View,
    *,
    landmark_dist: np.ndarray | None = None,
    falloff: float = 0.5,
    runner_up: float = 0.9,
) -> Placed:
    """Similarities of the tier members ``ids`` (positions ``xy``, (n, 2)) to the
    ordinal / middle superlative ``con`` seen from ``view``."""
    n = len(ids)
    keys, what, shown = _order(con, xy, view, landmark_dist)
    order = sorted(range(n), key=lambda i: (float(keys[i]), ids[i]))
    rank = {i: r for r, i in enumerate(order)}
    out = Placed()
    side = f" from the {con.direction}" if con.direction else ""
    if con.measure == "middle":
        centre = [(n - 1) // 2] if n % 2 else [n // 2 - 1, n // 2]
        dist = view.distance(xy)
        firsts = sorted(centre, key=lambda r: (float(dist[order[r]]), r))
        values = {firsts[0]: 1.0, **({firsts[1]: runner_up} if len(firsts) > 1 else {})}
        label = "the middle one"
    else:
        k = con.ordinal or 1
        want = k - 1 if k > 0 else n + k
        if not 0 <= want < n:
            out.note = (
                f"{con.id}: only {n} candidate(s) in the tier for the {nth(k)}{side}; "
                f"taking the {'last' if k > 0 else 'first'}"
            )
            want = n - 1 if k > 0 else 0
        values = {want: 1.0}
        centre = [want]
        label = f"the {nth(k)}{side}"
    for i in range(n):
        r = rank[i]
        gap = min(abs(r - c) for c in centre)
        sim = values.get(r, falloff / (1.0 + gap))
        out.sims.append(float(sim))
        out.whys.append(f"#{r + 1} of {n} by {what} ({float(shown[i]):+.2f} m); wanted {label}")
    return out
