"""Global room-ID grid with hysteresis voting (paper §III-B).

Each re-segmentation proposes labels with arbitrary numbers. They are first matched to
the persistent room ids by overlap (one-to-one, largest overlaps first; unmatched
segments get fresh ids). Then every cell votes: a cell already owned by a room switches
to a different proposal only after ``hysteresis`` consecutive segmentations agree on it,
so room borders do not flicker while the map grows.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from inherit_sg.geometry.records import IdCounter

_MIN_SHARE = 0.3  # overlap / smaller area needed to inherit an id


class RoomIdGrid:
    """Persistent room ids (0 = none) aligned with one floor's occupancy grid.

    ``new_id`` hands out fresh ids; share one between floors so ids stay unique.
    """

    def __init__(self, hysteresis: int, new_id: Callable[[], int] | None = None) -> None:
        self.hysteresis = hysteresis
        self._new_id = new_id or IdCounter(1)
        self.ids = np.zeros((0, 0), dtype=np.int32)
        self._candidate = np.zeros((0, 0), dtype=np.int32)
        self._votes = np.zeros((0, 0), dtype=np.uint8)

    def align(self, shape: tuple[int, int], offset_rows: int, offset_cols: int) -> None:
        """Pad the layers after the occupancy grid grew by ``offset`` rows/cols at the
        origin side and now has ``shape``."""
        h, w = self.ids.shape
        below, left = offset_rows, offset_cols
        above, right = shape[0] - h - below, shape[1] - w - left
        pad = ((below, above), (left, right))
        self.ids = np.pad(self.ids, pad)
        self._candidate = np.pad(self._candidate, pad)
        self._votes = np.pad(self._votes, pad)

    def match(self, labels: np.ndarray) -> np.ndarray:
        """Map segmentation labels (1..n) to persistent ids; returns the id image."""
        return self.match_table(labels)[labels]

    def match_table(self, labels: np.ndarray) -> np.ndarray:
        """Persistent id of every segmentation label (index 0 maps to 0).

        Segments inherit the id of the room they overlap most, then, failing that, the
        id of a pending change they overlap (so a new room keeps its id while its cells
        collect votes), else a fresh id.
        """
        n = int(labels.max()) if labels.size else 0
        lut = np.zeros(n + 1, dtype=np.int32)
        if n == 0:
            return lut
        taken: set[int] = set()
        _assign(labels, self.ids, lut, taken)
        _assign(labels, np.where(self._votes > 0, self._candidate, 0), lut, taken)
        for seg in range(1, n + 1):
            if not lut[seg]:
                lut[seg] = self._new_id()
        return lut

    def vote(self, proposal: np.ndarray) -> None:
        """One round of hysteresis voting with a proposal id image (0 = no room)."""
        ids, cand, votes = self.ids, self._candidate, self._votes
        same = proposal == ids
        fresh = (ids == 0) & (proposal > 0)
        ids[fresh] = proposal[fresh]
        agree = ~same & ~fresh & (proposal == cand)
        votes[agree] = np.minimum(votes[agree].astype(np.int32) + 1, 255).astype(np.uint8)
        new = ~same & ~fresh & ~agree
        cand[new] = proposal[new]
        votes[new] = 1
        votes[same | fresh] = 0
        cand[same | fresh] = 0
        flip = votes >= self.hysteresis
        ids[flip] = cand[flip]
        votes[flip] = 0
        cand[flip] = 0

    def update(self, labels: np.ndarray) -> np.ndarray:
        """Match a new segmentation, vote, and return the current id image."""
        self.vote(self.match(labels))
        return self.ids

    def room_ids(self) -> list[int]:
        """Ids that own at least one cell."""
        return [int(i) for i in np.unique(self.ids) if i > 0]


def _assign(labels: np.ndarray, ref: np.ndarray, lut: np.ndarray, taken: set[int]) -> None:
    """Give unassigned segments the id of ``ref`` they overlap most (one-to-one)."""
    n = len(lut) - 1
    both = (labels > 0) & (ref > 0)
    if not both.any():
        return
    m = int(ref.max()) + 1
    pair = np.bincount(
        labels[both].astype(np.int64) * m + ref[both], minlength=(n + 1) * m
    ).reshape(n + 1, m)
    seg_size = np.bincount(labels.reshape(-1), minlength=n + 1)
    id_size = np.bincount(ref.reshape(-1), minlength=m)
    for flat in np.argsort(-pair, axis=None):
        seg, rid = divmod(int(flat), m)
        ov = pair[seg, rid]
        if ov == 0:
            break
        if seg == 0 or rid == 0 or lut[seg] or rid in taken:
            continue
        if ov >= _MIN_SHARE * min(seg_size[seg], id_size[rid]):
            lut[seg] = rid
            taken.add(rid)
