"""The map commands as a user runs them: import, info, cypher, export/import round trip,
read-only refusal and the writer-lock message, through the real `inherit-sg` CLI."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.store import MapStore

CLI = [sys.executable, "-m", "inherit_sg.cli.main"]


def run(*args: str, check: bool = True) -> subprocess.CompletedProcess[str]:
    proc = subprocess.run([*CLI, *args], capture_output=True, text=True, timeout=300)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


@pytest.fixture
def apartment(real_data: Path, tmp_path: Path) -> Path:
    """The real Spark-DSG apartment imported through the CLI."""
    m = tmp_path / "apartment"
    src = real_data / "spark_dsg" / "apartment_dsg.json"
    run("import", "--format", "spark-dsg", str(src), "--map", str(m))
    return m


def test_spark_dsg_import_then_cypher_counts_seven_objects(apartment: Path) -> None:
    m = apartment
    out = json.loads(
        run("cypher", "--map", str(m), "MATCH (o:Object) RETURN count(o) AS n", "--json").stdout
    )
    assert out["columns"] == ["n"] and out["rows"] == [[7]]
    info = json.loads(run("info", "--map", str(m), "--json").stdout)
    assert (
        info["nodes"]["Object"] == 7 and info["nodes"]["Room"] == 1 and info["nodes"]["Floor"] == 1
    )
    assert info["edges"]["HAS_OBJECT"] == 7 and info["bytes"]["total"] > 0


def test_cypher_refuses_writes_and_reports_errors(apartment: Path, tmp_path: Path) -> None:
    m = apartment
    for query in (
        "MATCH (o:Object) SET o.label = 'x'",
        "CREATE (f:Floor {id: 'f9'})",
        "MATCH (o:Object) DETACH DELETE o",
    ):
        proc = run("cypher", "--map", str(m), query, check=False)
        assert proc.returncode == 2 and "error:" in proc.stderr
    # nothing was written
    out = json.loads(
        run(
            "cypher",
            "--map",
            str(m),
            "MATCH (o:Object) WHERE o.label = 'x' RETURN count(o)",
            "--json",
        ).stdout
    )
    assert out["rows"] == [[0]]
    bad = run("cypher", "--map", str(m), "MATCH (o:Nope) RETURN o", "--json", check=False)
    assert bad.returncode == 2 and json.loads(bad.stdout)["error"]
    missing = run("info", "--map", str(tmp_path / "no-such-map"), check=False)
    assert missing.returncode == 2 and "no-such-map" in missing.stderr


def test_export_import_round_trip_is_lossless(tmp_path: Path) -> None:
    from inherit_sg.ingest.synthetic.generate import generate_house

    scene = generate_house(5, 1, 4).scene
    (tmp_path / "scene.json").write_text(json.dumps(scene.to_dict()))
    a, b, dump = tmp_path / "a", tmp_path / "b", tmp_path / "a.json"
    run("import", "--format", "scene", str(tmp_path / "scene.json"), "--map", str(a))
    run("export", "--map", str(a), str(dump))
    run("import", str(dump), "--map", str(b))
    with MapStore.open(a) as sa, MapStore.open(b) as sb:
        ga, gb = sa.load_graph(), sb.load_graph()
    assert len(ga) == len(gb) > 0
    for node in ga.nodes():
        other = gb.get(node.id)
        for key, value in vars(node).items():
            if isinstance(value, np.ndarray):
                assert np.array_equal(value, getattr(other, key)), (node.id, key)
            else:
                assert value == getattr(other, key), (node.id, key)
    assert {e.key: e for e in ga.edges()} == {e.key: e for e in gb.edges()}
    again = run("import", str(dump), "--map", str(b), check=False)
    assert again.returncode == 2


def test_second_writer_gets_a_clear_lock_error(apartment: Path) -> None:
    m = apartment
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import sys, time; from inherit_sg.store import MapStore; "
            "s = MapStore.open(sys.argv[1], write=True); print('ready', flush=True); time.sleep(60)",
            str(m),
        ],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout is not None and holder.stdout.readline().strip() == "ready"
        code = "import sys; from inherit_sg.store import MapStore; MapStore.open(sys.argv[1], write=True)"
        proc = subprocess.run(
            [sys.executable, "-c", code, str(m)], capture_output=True, text=True, timeout=60
        )
        assert proc.returncode != 0
        assert str(m) in proc.stderr and f"pid {holder.pid}" in proc.stderr
    finally:
        holder.kill()
        holder.wait()


@pytest.mark.parametrize(
    "args",
    [["--help"], ["map", "build", "--help"], ["query", "--help"], ["sim", "generate", "--help"]],
)
def test_every_command_has_help(args: list[str]) -> None:
    proc = run(*args)
    assert "Usage" in proc.stdout and "--help" in proc.stdout


def test_cypher_timeout_option(tmp_path: Path) -> None:
    MapStore.create(tmp_path / "m").close()
    slow = (
        "UNWIND range(1, 3000) AS a UNWIND range(1, 3000) AS b UNWIND range(1, 3000) AS x "
        "WITH a, b, x WHERE (a * b + x) % 7 = 3 RETURN count(*)"
    )
    proc = run("cypher", "--map", str(tmp_path / "m"), slow, "--timeout", "0.2", check=False)
    assert proc.returncode != 0
    assert "time limit of 0.2 s" in proc.stderr + proc.stdout
