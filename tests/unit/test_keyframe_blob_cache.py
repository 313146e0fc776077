"""The in-memory cache of keyframe JPEGs and features (verification reads the same best
views again and again)."""

from __future__ import annotations

import numpy as np

from inherit_sg.store.keyframes import BlobCache


def _blob(n: int) -> tuple[bytes, np.ndarray]:
    return bytes(n), np.zeros(4, dtype=np.float32)  # n + 16 bytes


def test_least_recently_used_pairs_leave_first_within_the_byte_budget() -> None:
    cache = BlobCache(max_bytes=3 * 116)
    for kf in ("a", "b", "c"):
        cache.put(kf, _blob(100))
    assert cache.get("a") is not None  # "a" is now the most recently used
    cache.put("d", _blob(100))
    assert cache.get("b") is None
    assert [k for k in "acd" if cache.get(k) is not None] == ["a", "c", "d"]


def test_a_replaced_pair_counts_once_and_oversized_pairs_are_not_kept() -> None:
    cache = BlobCache(max_bytes=300)
    cache.put("a", _blob(100))
    cache.put("a", _blob(150))
    cache.put("b", _blob(100))
    got = cache.get("a")
    assert got is not None and len(got[0] or b"") == 150
    assert cache.get("b") is not None
    cache.put("huge", _blob(1000))
    assert cache.get("huge") is None and cache.get("a") is not None


def test_clear_forgets_everything() -> None:
    cache = BlobCache()
    cache.put("a", _blob(10))
    cache.clear()
    assert cache.get("a") is None
