"""A real recording without instance masks, mapped with the defaults: the Replica office0
frames give objects (the classical segmenter, chosen by the ``auto`` default) and the log
says why they are unnamed and how to name them."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.facade import MapService, build_map

REPO_ROOT = Path(__file__).resolve().parents[2]
OFFICE0 = REPO_ROOT / ".." / "shared" / "data" / "real" / "replica_office0"

pytestmark = pytest.mark.skipif(
    not (OFFICE0 / "traj.txt").is_file(), reason="shared real data absent"
)


def test_office0_maps_to_objects_with_the_defaults(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    with caplog.at_level("WARNING"):
        summary = build_map(OFFICE0, tmp_path / "office0")
    assert summary["frames"] == 4 and summary["objects"] >= 3, summary
    assert "without instance masks" in caplog.text and "perception.segmenter" in caplog.text
    with MapService.open(tmp_path / "office0") as service:
        rows = service.cypher("MATCH (o:Object) RETURN o.label, o.description").rows
    assert len(rows) == summary["objects"]
    assert all(label == "object" for label, _ in rows)
    # unnamed, but told apart by how they look: shape and colour lead the description
    shapes = ("a flat ", "a tall ", "a long ", "a box-like ")
    assert all(text.startswith(shapes) for _, text in rows), rows
