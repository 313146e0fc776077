"""A real recording without instance masks, mapped with the defaults: the Replica office0
frames give objects (the classical segmenter, chosen by the ``auto`` default) and the log
says why they are unnamed and how to name them."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.facade import MapService, build_map


def test_office0_maps_to_objects_with_the_defaults(
    real_data: Path, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    with caplog.at_level("WARNING"):
        summary = build_map(real_data / "replica_office0", tmp_path / "office0")
    assert summary["frames"] == 4 and summary["objects"] >= 3, summary
    assert "without instance masks" in caplog.text and "perception.segmenter" in caplog.text
    with MapService.open(tmp_path / "office0") as service:
        rows = service.cypher("MATCH (o:Object) RETURN o.label, o.description").rows
    assert len(rows) == summary["objects"]
    assert all(label == "object" for label, _ in rows)
    # unnamed, but told apart by how they look: shape and colour lead the description
    shapes = ("a flat ", "a tall ", "a long ", "a box-like ")
    assert all(text.startswith(shapes) for _, text in rows), rows
