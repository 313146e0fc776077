"""The Python API from a plain script (no ``if __name__ == "__main__"`` guard), as the
README shows it: reads that run in the map's Cypher worker process must not run the
script a second time in that child, nor fail to start it."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.unit.retrieval_fixtures import write_small_map

SCRIPT = """
from pathlib import Path
runs = Path({runs!r})
runs.write_text(runs.read_text() + "run\\n" if runs.exists() else "run\\n")
from inherit_sg import MapService
with MapService.open({map!r}) as svc:
    print(svc.rooms().total, svc.cypher("MATCH (o:Object) RETURN count(o)").rows[0][0])
"""


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_small_map(tmp_path_factory.mktemp("plain") / "map")


def test_a_script_without_a_main_guard_runs_once_and_reads_the_map(
    map_dir: Path, tmp_path: Path
) -> None:
    runs = tmp_path / "runs.txt"
    script = tmp_path / "plain.py"
    script.write_text(SCRIPT.format(runs=str(runs), map=str(map_dir)), encoding="utf-8")
    out = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path, timeout=300
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["4", "29"]
    assert runs.read_text().splitlines() == ["run"]  # the worker did not run the script
