"""``inherit-sg bench --ray``: one Ray task per dataset on a local cluster; each writes the
same results JSON as ``inherit-sg bench`` on that dataset alone."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from inherit_sg.cli.main import app
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset

pytest.importorskip("ray")

runner = CliRunner()
SEEDS = (3, 4)
FRAMES = 40
QUICK = ["--no-ablations", "--max-queries", "12", "--quiet"]


@pytest.fixture(scope="module")
def walks(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    root = tmp_path_factory.mktemp("bench_walks")
    out = []
    for seed in SEEDS:
        path = root / f"walk{seed}"
        write_dataset(generate_house(seed, 1, 4), path, width=128, height=96, workers=1,
                      max_frames=FRAMES, close_looks=False)  # fmt: skip
        out.append(path)
    return out


def _keys(doc: dict, depth: int = 2) -> set[str]:
    """Key paths of ``doc`` down to ``depth`` levels (the report's shape)."""
    keys = set()
    for k, v in doc.items():
        keys.add(k)
        if depth > 1 and isinstance(v, dict):
            keys |= {f"{k}.{sub}" for sub in _keys(v, depth - 1)}
    return keys


def test_bench_on_ray_writes_what_bench_writes_alone(walks: list[Path], tmp_path: Path) -> None:
    alone = tmp_path / "alone.json"
    res = runner.invoke(app, ["bench", "-d", str(walks[0]), "--out", str(alone), *QUICK])
    assert res.exit_code == 0, res.output
    args = ["bench", "-d", str(walks[0]), "-d", str(walks[1]), "--out", str(tmp_path / "ray")]
    res = runner.invoke(app, [*args, "--ray", *QUICK])
    assert res.exit_code == 0, res.output
    assert f"results written to {tmp_path / 'ray'}/" in res.output
    docs = {p.stem: json.loads(p.read_text()) for p in (tmp_path / "ray").glob("*.json")}
    assert sorted(docs) == ["walk3", "walk4"]  # nothing partial left beside them
    reference = json.loads(alone.read_text())
    ours = docs["walk3"]
    assert _keys(ours) == _keys(reference)
    assert ours["accuracy"]["ours"]["overall"]["n"] == reference["accuracy"]["ours"]["overall"]["n"]
    # the same objects are mapped (rooms, and the relations counted within them, may
    # differ: the global update's timing is free)
    got = ours["mapping"]["quality"]["objects"]
    want = reference["mapping"]["quality"]["objects"]
    same = {k for k in want if not k.startswith("relation")}
    assert same and {k: got[k] for k in same} == {k: want[k] for k in same}
    assert docs["walk4"]["accuracy"]["ours"]["overall"]["n"] > 0


def test_bench_several_without_ray_and_bad_arguments(walks: list[Path], tmp_path: Path) -> None:
    out = tmp_path / "seq"
    res = runner.invoke(
        app, ["bench", "-d", str(walks[0]), "-d", str(walks[1]), "--out", str(out), *QUICK]
    )
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in out.iterdir()) == ["walk3.json", "walk4.json"]
    res = runner.invoke(
        app, ["bench", "-d", str(walks[0]), "-d", str(walks[1]), "--out", str(tmp_path / "x.json")]
    )
    assert res.exit_code != 0 and "give a folder" in res.output
    res = runner.invoke(app, ["bench", "-d", str(walks[0]), "-d", str(walks[0]), "--out", str(out)])
    assert res.exit_code != 0 and "share the folder name" in res.output
    res = runner.invoke(
        app,
        ["bench", "-d", str(walks[0]), "-d", str(walks[1]), "--map", str(out), "--out", str(out)],
    )
    assert res.exit_code != 0 and "--map names the map of one dataset" in res.output
