"""A built map records its vocabulary and label space in map.json; a later session with
another vocabulary records the new one with a warning; maps made before these fields
existed still open, and ``inherit-sg info`` shows them."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.store import MapStore, mapdir
from inherit_sg.vocab import vocabulary_info

FRAMES = 40


@pytest.fixture(scope="module")
def house_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("vocab-house") / "h"
    write_dataset(generate_house(4, 1, 4), out, width=160, height=120, workers=1)
    return out


@pytest.fixture(scope="module")
def built(house_dir: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    map_dir = tmp_path_factory.mktemp("vocab-maps") / "m"
    build_map(house_dir, map_dir, max_frames=FRAMES)
    return map_dir


def _card(map_dir: Path) -> dict[str, Any]:
    return json.loads((map_dir / "map.json").read_text(encoding="utf-8"))


def test_built_map_records_vocabulary_and_label_space(built: Path) -> None:
    card = _card(built)
    assert card["vocabulary"] == vocabulary_info()
    assert {"rooms", "areas", "colours"} <= set(card["vocabulary"]["versions"])
    with MapStore.open(built) as store:
        labels = {o.label for o in store.load_graph().objects()}
        assert store.info.label_space == card["label_space"]
    assert labels and card["label_space"] == sorted(labels)


def test_later_session_with_other_vocabulary_warns_and_records_it(
    built: Path,
    house_dir: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    work = tmp_path / "m"
    shutil.copytree(built, work)
    old = _card(work)
    old_digest = old["vocabulary"]["digest"]
    card = _card(work)
    card["label_space"] = [*card["label_space"], "zeppelin"]  # a label from earlier words
    (work / "map.json").write_text(json.dumps(card), encoding="utf-8")
    other: dict[str, Any] = {
        "versions": {**old["vocabulary"]["versions"], "rooms": 99},
        "digest": "0123abcd0123abcd",
    }
    monkeypatch.setattr(mapdir, "vocabulary_info", lambda: other)
    with caplog.at_level(logging.WARNING, logger="inherit_sg.store.mapdir"):
        build_map(house_dir, work, session_name="again", max_frames=10)
    warned = [r.getMessage() for r in caplog.records if r.name == "inherit_sg.store.mapdir"]
    assert any(old_digest in m and other["digest"] in m for m in warned), warned
    after = _card(work)
    assert after["vocabulary"] == other
    assert "zeppelin" in after["label_space"]  # the union keeps what was there
    assert set(old["label_space"]) <= set(after["label_space"])
    assert after["label_space"] == sorted(after["label_space"])
    with MapStore.open(work) as store:  # still usable
        assert [s.name for s in store.sessions()] == ["session-1", "again"]


def _without_fields(built: Path, work: Path) -> Path:
    """A copy of ``built`` whose map.json predates the vocabulary fields."""
    shutil.copytree(built, work)
    card = _card(work)
    del card["vocabulary"], card["label_space"]
    (work / "map.json").write_text(json.dumps(card), encoding="utf-8")
    return work


def test_old_map_json_without_the_fields_still_opens(built: Path, tmp_path: Path) -> None:
    work = _without_fields(built, tmp_path / "old")
    with MapStore.open(work) as store:
        assert store.info.vocabulary == {} and store.info.label_space == []
    with MapStore.open(work, write=True) as store:  # a writable open keeps them absent
        assert store.info.vocabulary == {}
    assert "vocabulary" not in _card(work) or _card(work)["vocabulary"] == {}


def test_info_shows_vocabulary_and_label_space(built: Path, tmp_path: Path) -> None:
    from inherit_sg.cli.main import app

    runner = CliRunner()
    shown = runner.invoke(app, ["info", "--map", str(built)])
    assert shown.exit_code == 0, shown.output
    digest = _card(built)["vocabulary"]["digest"]
    versions = _card(built)["vocabulary"]["versions"]
    assert f"vocabulary: {digest} (lexicon v{versions['lexicon']}, " in shown.output
    assert f"rooms v{versions['rooms']}" in shown.output
    assert "label space: " in shown.output and "labels:" in shown.output
    as_json = json.loads(runner.invoke(app, ["info", "--map", str(built), "--json"]).output)
    assert as_json["label_space"] == _card(built)["label_space"]
    assert as_json["vocabulary"]["digest"] == digest

    old = runner.invoke(app, ["info", "--map", str(_without_fields(built, tmp_path / "old"))])
    assert old.exit_code == 0, old.output
    assert "vocabulary: not recorded" in old.output and "label space: none recorded" in old.output
