"""Rerun logging (``--rerun``) on a small generated house, read back with rerun-sdk's own
.rrd reader: a build logs the camera, images, the graph after each update and the BEV; a
query logs the map, its candidates, its answer and the trace."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from inherit_sg.cli.main import app
from inherit_sg.facade import MapService
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset

pytest.importorskip("rerun")
from rerun.chunk import RrdReader

runner = CliRunner()


def _chunks(path: Path) -> dict[str, list]:
    """Chunks of an .rrd file by entity path, in the order they were written."""
    out: dict[str, list] = {}
    for chunk in RrdReader(str(path)).store().stream().to_chunks():
        out.setdefault(chunk.entity_path, []).append(chunk)
    return out


def _last(chunks: list, column: str) -> list:
    """The last row's values of a component column across ``chunks``."""
    rows = [v for c in chunks for v in c.to_record_batch().column(column).to_pylist()]
    return rows[-1] or []


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    root = tmp_path_factory.mktemp("rerun")
    write_dataset(generate_house(3, 1, 4), root / "house", width=128, height=96, workers=2)
    rrd = root / "logs" / "build.rrd"
    res = runner.invoke(
        app,
        [
            "map",
            "build",
            str(root / "house"),
            "--map",
            str(root / "map"),
            "--rerun",
            str(rrd),
            "--rerun-images",
            "3",
        ],
    )
    assert res.exit_code == 0, res.output
    assert f"Rerun recording: {rrd}" in res.output
    return root / "map", rrd


def test_build_logs_camera_images_graph_and_bev(built: tuple[Path, Path]) -> None:
    map_dir, rrd = built
    chunks = _chunks(rrd)
    for path in ("/world/camera", "/world/camera/image", "/world/camera/image/rgb",
                 "/world/camera/image/depth", "/world/rooms", "/world/objects",
                 "/world/relations", "/world/doors", "/bev/floor_0"):  # fmt: skip
        assert path in chunks, f"{path} not logged: {sorted(chunks)}"
    frames = sum(c.num_rows for c in chunks["/world/camera"])
    rgb = sum(c.num_rows for c in chunks["/world/camera/image/rgb"])
    assert frames > 10 and rgb == -(-frames // 3)  # every third frame's images
    # the graph logged last is the map that was stored
    with MapService.open(map_dir) as service:
        scene = service.scene3d()
    labels = _last(chunks["/world/objects"], "Boxes3D:labels")
    assert sorted(labels) == sorted(o.label for o in scene.objects)
    centres = np.array(_last(chunks["/world/objects"], "Boxes3D:centers"))
    expected = np.array([(np.add(o.bbox_min, o.bbox_max) / 2) for o in scene.objects])
    assert np.allclose(np.sort(centres, axis=0), np.sort(expected, axis=0), atol=1e-4)
    rooms = _last(chunks["/world/rooms"], "LineStrips3D:labels")
    assert set(rooms) == {r.label for r in scene.rooms}
    # the camera's last logged position is the last frame's
    last = (map_dir.parent / "house" / "poses.txt").read_text().split("\n")[-2].split()[1:]
    matrix = np.array(last, dtype=float).reshape(4, 4)
    (position,) = _last(chunks["/world/camera"], "Transform3D:translation")
    assert np.allclose(position, matrix[:3, 3], atol=1e-5)


def test_query_logs_answer_candidates_and_trace(built: tuple[Path, Path], tmp_path: Path) -> None:
    map_dir, _ = built
    rrd = tmp_path / "query.rrd"
    res = runner.invoke(
        app, ["query", "-m", str(map_dir), "a window", "--json", "--rerun", str(rrd)]
    )
    assert res.exit_code == 0, res.output
    import json

    result = json.loads(res.output)
    chunks = _chunks(rrd)
    answer = _last(chunks["/world/query/answer"], "Boxes3D:labels")
    assert answer == [f"{result['answer']['label']} ({result['answer']['id']})"]
    others = _last(chunks["/world/query/candidates"], "Boxes3D:labels")
    expected = [c for c in result["candidates"] if c["id"] != result["answer"]["id"]]
    assert len(others) == len(expected) > 0
    (trace,) = _last(chunks["/query/trace"], "TextDocument:text")
    assert trace.startswith("**a window**") and result["trace"][0] in trace


def test_bad_targets_and_batch_are_refused(built: tuple[Path, Path], tmp_path: Path) -> None:
    map_dir, _ = built
    res = runner.invoke(
        app, ["query", "-m", str(map_dir), "a sofa", "--rerun", str(tmp_path / "x.txt")]
    )
    assert res.exit_code != 0 and ".rrd file or a rerun+http:// URL" in res.output
    batch = tmp_path / "in.jsonl"
    batch.write_text('{"text": "a sofa"}\n')
    res = runner.invoke(
        app,
        [
            "query",
            "-m",
            str(map_dir),
            "--batch",
            str(batch),
            "--out",
            str(tmp_path / "o.jsonl"),
            "--rerun",
            str(tmp_path / "b.rrd"),
        ],
    )
    assert res.exit_code != 0 and "--rerun logs one request" in res.output


def test_nothing_imports_rerun_unless_asked(built: tuple[Path, Path]) -> None:
    import subprocess

    code = (
        "import sys\n"
        "from inherit_sg.facade import MapService\n"
        f"with MapService.open({str(built[0])!r}) as s:\n"
        "    s.query('a sofa', verify=False)\n"
        "print('rerun' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "False"
