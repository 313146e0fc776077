"""Bad input to the CLI, as a careless or hostile user gives it: every case ends with a
clear error that names what is wrong, no traceback, and nothing left behind."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest

from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset

CLI = [sys.executable, "-m", "inherit_sg.cli.main"]


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*CLI, *args], capture_output=True, text=True, timeout=300)


def refused(proc: subprocess.CompletedProcess[str], needle: str) -> None:
    """A non-zero exit whose message names the problem, without a traceback."""
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0, out
    assert "Traceback" not in out, out
    assert needle.lower() in out.lower(), out


@pytest.fixture(scope="module")
def walk(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("hostile") / "walk"
    write_dataset(generate_house(3, 1, 4), out, width=160, height=120, workers=1, max_frames=3)
    return out


def variant(walk: Path, tmp_path: Path, name: str) -> Path:
    out = tmp_path / name
    shutil.copytree(walk, out)
    return out


def test_intrinsics_that_are_not_numbers(walk: Path, tmp_path: Path) -> None:
    data = variant(walk, tmp_path, "fx")
    intr = json.loads((data / "intrinsics.json").read_text())
    (data / "intrinsics.json").write_text(json.dumps({**intr, "fx": "abc"}))
    refused(run("map", "build", str(data), "--map", str(tmp_path / "m")), "must be numbers")
    assert not (tmp_path / "m").exists()


def test_an_8_bit_depth_image_is_not_read_as_metres(walk: Path, tmp_path: Path) -> None:
    data = variant(walk, tmp_path, "d8")
    for path in (data / "frames").glob("*.depth.png"):
        depth = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
        cv2.imwrite(str(path), (depth // 256).astype(np.uint8))
    refused(run("map", "build", str(data), "--map", str(tmp_path / "m")), "uint16")
    assert not (tmp_path / "m").exists(), "a map was made from frames that cannot be read"


def test_an_empty_walk_and_no_frames(walk: Path, tmp_path: Path) -> None:
    data = variant(walk, tmp_path, "empty")
    (data / "poses.txt").write_text("")
    refused(run("map", "build", str(data), "--map", str(tmp_path / "m")), "no frames")
    assert not (tmp_path / "m").exists()
    for n in ("0", "-1"):
        args = ("map", "build", str(walk), "--map", str(tmp_path / "m"), "--max-frames", n)
        refused(run(*args), "--max-frames")
    assert not (tmp_path / "m").exists()


def test_a_pose_far_from_the_origin(walk: Path, tmp_path: Path) -> None:
    data = variant(walk, tmp_path, "far")
    lines = (data / "poses.txt").read_text().splitlines()
    fields = lines[1].split()
    fields[4] = "1e308"  # the x translation
    lines[1] = " ".join(fields)
    (data / "poses.txt").write_text("\n".join(lines) + "\n")
    refused(run("map", "build", str(data), "--map", str(tmp_path / "m")), "implausible")


def test_a_refused_build_leaves_no_lock(walk: Path, tmp_path: Path) -> None:
    folder = tmp_path / "notes"
    folder.mkdir()
    (folder / "todo.txt").write_text("buy milk")
    refused(run("map", "build", str(walk), "--map", str(folder)), "not empty")
    assert sorted(p.name for p in folder.iterdir()) == ["todo.txt"]


def test_a_file_is_no_map(tmp_path: Path) -> None:
    note = tmp_path / "a-file.txt"
    note.write_text("hello")
    refused(run("info", "--map", str(note)), "is a file")
    refused(run("cypher", "--map", str(note), "RETURN 1"), "is a file")
    refused(run("query", "--map", str(note), "the bed"), "is a file")


def test_bad_numbers_for_cypher(walk: Path, tmp_path: Path) -> None:
    m = tmp_path / "m"
    assert run("map", "build", str(walk), "--map", str(m)).returncode == 0
    refused(run("cypher", "--map", str(m), "RETURN 1", "--max-rows", "-1"), "--max-rows")
    refused(run("cypher", "--map", str(m), "RETURN 1", "--timeout", "0"), "--timeout")
    refused(run("cypher", "--map", str(m), "MATCH (o:Object) SET o.label = 'x'"), "read-only")
    refused(run("cypher", "--map", str(m), "RETURN 1; RETURN 2"), "one Cypher statement")
    refused(run("cypher", "--map", str(m), "RETURN $x", "--param", "x"), "NAME=VALUE")


def test_a_truncated_search_index_is_derived_data(walk: Path, tmp_path: Path) -> None:
    m = tmp_path / "m"
    assert run("map", "build", str(walk), "--map", str(m)).returncode == 0
    index = m / "index.kuzu"
    with open(index, "r+b") as fh:
        fh.truncate(index.stat().st_size // 2)
    for args in (
        ("info", "--map", str(m)),
        ("cypher", "--map", str(m), "MATCH (o:Object) RETURN count(o)"),
        ("query", "--map", str(m), "the bed", "--no-verify"),
    ):
        proc = run(*args)
        out = proc.stdout + proc.stderr
        assert proc.returncode == 0 and "Traceback" not in out, out
    assert "index.kuzu is damaged" in run("info", "--map", str(m)).stderr
    # opening the map for writing rebuilds it
    assert run("map", "build", str(walk), "--map", str(m), "--session", "again").returncode == 0
    assert "damaged" not in run("info", "--map", str(m)).stderr


def test_a_deleted_keyframe_file_is_named_with_its_way_out(walk: Path, tmp_path: Path) -> None:
    m = tmp_path / "m"
    assert run("map", "build", str(walk), "--map", str(m)).returncode == 0
    found = run("cypher", "--map", str(m), "MATCH (o:Object) RETURN o.label LIMIT 1", "--json")
    label = json.loads(found.stdout)["rows"][0][0]
    data = next((m / "lance" / "keyframes.lance" / "data").glob("*.lance"))
    data.unlink()
    proc = run("query", "--map", str(m), f"the {label}")
    refused(proc, "keyframe table")
    assert "export" in proc.stdout + proc.stderr
    # the way out it names: the graph without pictures, into a new map that answers
    out = tmp_path / "m.json"
    assert run("export", "--map", str(m), "--no-images", str(out)).returncode == 0
    assert run("import", str(out), "--map", str(tmp_path / "new")).returncode == 0
    again = run("query", "--map", str(tmp_path / "new"), f"the {label}", "--json")
    assert again.returncode == 0, again.stderr
    assert json.loads(again.stdout)["answer"] is not None


def test_map_json_dimensions_that_do_not_fit_the_vectors(walk: Path, tmp_path: Path) -> None:
    m = tmp_path / "m"
    assert run("map", "build", str(walk), "--map", str(m)).returncode == 0
    info = json.loads((m / "map.json").read_text())
    (m / "map.json").write_text(json.dumps({**info, "visual_dim": 128}))
    refused(run("query", "--map", str(m), "the door"), "set visual_dim to 256")


def test_garbled_database_files(walk: Path, tmp_path: Path) -> None:
    import os

    m = tmp_path / "m"
    assert run("map", "build", str(walk), "--map", str(m)).returncode == 0
    garbled = tmp_path / "g"
    shutil.copytree(m, garbled)

    def garble(path: Path) -> None:  # keep the header, scramble the pages after it
        size = path.stat().st_size
        with open(path, "r+b") as fh:
            fh.seek(4096)
            fh.write(os.urandom(size - 8192))

    # the derived search index: the map answers without it, and a writable open rebuilds it
    garble(m / "index.kuzu")
    proc = run("info", "--map", str(m))
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert "index.kuzu is damaged" in proc.stderr
    # the scene graph: a clear error with the way back
    garble(garbled / "graph.kuzu")
    refused(run("info", "--map", str(garbled)), "inherit-sg import")
