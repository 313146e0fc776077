"""A real recording without instance masks, mapped with the defaults: the Replica office0
frames give objects (the classical segmenter, chosen by the ``auto`` default) and the log
says why they are unnamed and how to name them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from inherit_sg.cli.main import app
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
    shapes = ("a flat ", "a tall ", "a round ", "a long ", "a box-like ")
    assert all(text.startswith(shapes) for _, text in rows), rows


def test_a_200_frame_render_of_the_office0_scan_maps_to_20_objects(
    real_data: Path, tmp_path: Path
) -> None:
    """The real scanned mesh rendered along its recorded trajectory, as a user would with
    ``sim render-mesh``, then mapped with the defaults."""
    office = real_data / "replica_office0"
    dataset = tmp_path / "render"
    result = CliRunner().invoke(
        app,
        [
            "sim", "render-mesh", str(office / "office0_mesh.ply"),
            "--trajectory", str(office / "traj.txt"),
            "--camera", str(office / "cam_params.json"),
            "--out", str(dataset), "--frames", "200", "--json",
        ],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["frames"] == 200
    assert not any(dataset.glob("frames/*.instances.png"))  # like a real recording
    summary = build_map(dataset, tmp_path / "map")
    assert summary["frames"] == 200 and summary["rooms"] == 1
    assert summary["objects"] >= 20, summary
