"""Large SKIP values are refused before Kuzu sees them (they crash Kuzu 0.11.3)."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.errors import CypherError
from inherit_sg.store import MapStore
from inherit_sg.store.skip_guard import MAX_SKIP, check_skip


@pytest.mark.parametrize(
    ("query", "params"),
    [
        ("MATCH (o:Object) RETURN o.id ORDER BY o.id SKIP 20000 LIMIT 5", None),
        ("MATCH (o:Object) RETURN o.id ORDER BY o.id skip $off LIMIT 5", {"off": 60_000}),
    ],
)
def test_large_skip_is_refused(query: str, params: dict | None) -> None:
    with pytest.raises(CypherError, match="page on the sort key"):
        check_skip(query, params)


@pytest.mark.parametrize(
    ("query", "params"),
    [
        (f"MATCH (o:Object) RETURN o.id ORDER BY o.id SKIP {MAX_SKIP} LIMIT 5", None),
        ("MATCH (o:Object) RETURN o.id SKIP $off", {"off": 3}),
        ("MATCH (o:Object) WHERE o.label = 'SKIP 99999' RETURN o.id", None),
        ("MATCH (o:Object) RETURN o.skip", None),
    ],
)
def test_small_or_quoted_skip_passes(query: str, params: dict | None) -> None:
    check_skip(query, params)


def test_store_refuses_before_running(tmp_path: Path) -> None:
    MapStore.create(tmp_path / "m").close()
    with MapStore.open(tmp_path / "m") as store:
        with pytest.raises(CypherError, match="above 10000"):
            store.cypher("MATCH (o:Object) RETURN o.id ORDER BY o.id SKIP 50000 LIMIT 1")
        assert store.cypher("MATCH (o:Object) RETURN count(o)").rows == [[0]]
