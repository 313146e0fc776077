"""The wheel installs one top-level package, ``inherit_sg`` (with its data): beside the
PyPI package ``schema`` in a fresh virtual environment, both import (issue: generic
top-level names such as ``schema``, ``api`` and ``ingest`` broke other packages)."""

from __future__ import annotations

import subprocess
import sys
import venv
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q",
         "-w", str(out), str(ROOT)],
        check=True,
    )  # fmt: skip
    return next(out.glob("inherit_sg-*.whl"))


def test_the_wheel_holds_only_the_inherit_sg_package(wheel: Path) -> None:
    names = zipfile.ZipFile(wheel).namelist()
    tops = {n.split("/")[0] for n in names}
    assert {t for t in tops if not t.endswith(".dist-info")} == {"inherit_sg"}
    for data in (
        "inherit_sg/schema/0001_init.cypher",
        "inherit_sg/api/static/index.html",
        "inherit_sg/vocab/data/objects.toml",
    ):
        assert data in names, data


def test_it_installs_beside_the_pypi_schema_package(wheel: Path, tmp_path: Path) -> None:
    env = tmp_path / "venv"
    venv.create(env, with_pip=True)
    python = env / "bin" / "python"
    pip = [str(python), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    subprocess.run([*pip, "schema"], check=True)
    subprocess.run([*pip, "--no-deps", str(wheel)], check=True)
    code = (
        "import schema, inherit_sg, inherit_sg.schema, importlib.util as u; "
        "assert hasattr(schema, 'Schema'), schema.__file__; "
        "assert u.find_spec('api') is None and u.find_spec('ingest') is None; "
        "print(inherit_sg.__version__)"
    )
    out = subprocess.run([str(python), "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip()
