"""The build-many manifest: good lines become map jobs, bad ones name their line and
what is wrong; a missing Ray names the install command."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from inherit_sg.errors import InputError
from inherit_sg.scale import require_ray
from inherit_sg.scale.manifest import ManifestError, SessionJob, read_manifest


@pytest.fixture
def data(tmp_path: Path) -> Path:
    for name in ("a", "b", "c"):
        (tmp_path / name).mkdir()
    return tmp_path


def _manifest(root: Path, *lines: str) -> Path:
    path = root / "manifest.jsonl"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_lines_become_jobs(data: Path) -> None:
    path = _manifest(
        data,
        "# fleet of Monday",
        '{"dataset": "a"}',
        "",
        '{"dataset": "b", "format": "isg", "map": "house-b", "session": "mon", "max_frames": 9}',
        '{"map": "c2", "format": "isg", "sessions": [{"dataset": "c"}, '
        '{"dataset": "a", "format": "auto", "session": "tue"}]}',
    )
    jobs = read_manifest(path)
    assert [j.name for j in jobs] == ["a", "house-b", "c2"]
    assert [j.line for j in jobs] == [2, 4, 5]
    assert jobs[0].sessions == (SessionJob(str(data / "a")),)
    assert jobs[1].sessions == (SessionJob(str(data / "b"), "isg", "mon", 9),)
    assert jobs[2].sessions == (
        SessionJob(str(data / "c"), "isg"),
        SessionJob(str(data / "a"), "auto", "tue"),
    )


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ("{not json", "line 2: not valid JSON"),
        ("[1, 2]", "line 2: expected a JSON object, got list"),
        ('{"map": "x"}', "line 2: 'dataset' must be a non-empty path string"),
        ('{"dataset": "nowhere"}', "line 2: dataset"),
        ('{"dataset": "b", "format": "obj"}', "line 2: format 'obj' is not one of"),
        ('{"dataset": "b", "colour": 1}', "line 2: unknown field(s) colour"),
        ('{"dataset": "b", "max_frames": 0}', "line 2: 'max_frames' must be a positive"),
        ('{"dataset": "b", "map": "../up"}', "line 2: map name '../up' must be"),
        ('{"dataset": "a"}', "line 2: map 'a' is already built by line 1"),
        ('{"sessions": []}', "line 2: 'sessions' must be a non-empty list"),
        ('{"sessions": [{"dataset": "b"}, 3]}', "line 2, session 2: expected a JSON object"),
        ('{"dataset": "b", "sessions": [{"dataset": "c"}]}', "line 2: give either"),
    ],
)
def test_bad_lines_are_named(data: Path, line: str, message: str) -> None:
    with pytest.raises(ManifestError, match="^" + re.escape(message)):
        read_manifest(_manifest(data, '{"dataset": "a"}', line))


def test_empty_or_missing_manifest(data: Path) -> None:
    with pytest.raises(ManifestError, match="lists no maps"):
        read_manifest(_manifest(data, "# nothing", ""))
    with pytest.raises(ManifestError, match="cannot read manifest"):
        read_manifest(data / "absent.jsonl")


def test_missing_ray_names_the_install_command(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray now raises ImportError
    with pytest.raises(InputError, match=r"pip install 'inherit-sg\[ray\]'"):
        require_ray()
