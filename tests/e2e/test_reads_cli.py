"""``inherit-sg ls`` and ``inherit-sg show`` end to end on a real map (Kuzu + LanceDB) of
the small scene: the same reads REST serves, through MapService."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from inherit_sg.cli.main import app
from inherit_sg.facade import MapService
from tests.unit.retrieval_fixtures import write_small_map

runner = CliRunner()


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_small_map(tmp_path_factory.mktemp("reads") / "map")


def run(*args: str) -> tuple[int, str]:
    result = runner.invoke(app, list(args))
    return result.exit_code, result.output


def test_ls_every_layer_as_json_matches_the_service(map_dir: Path) -> None:
    with MapService.open(map_dir) as service:
        expected = {
            "floors": service.floors().model_dump(mode="json"),
            "rooms": service.rooms().model_dump(mode="json"),
            "areas": service.areas().model_dump(mode="json"),
            "objects": service.objects().model_dump(mode="json"),
        }
    for layer, want in expected.items():
        code, out = run("ls", layer, "--map", str(map_dir), "--json")
        assert code == 0, out
        assert json.loads(out) == want
    assert expected["floors"]["total"] == 2
    assert {r["label"] for r in expected["rooms"]["rooms"]} >= {"kitchen", "living room"}


def test_ls_filters_and_pages(map_dir: Path) -> None:
    code, out = run("ls", "objects", "--map", str(map_dir), "--label", "MUG", "--json")
    assert code == 0, out
    mugs = json.loads(out)
    assert mugs["total"] == 3 and {o["label"] for o in mugs["objects"]} == {"mug"}
    code, out = run(
        "ls", "objects", "-m", str(map_dir), "--room", "room:kitchen", "--limit", "2", "--json"
    )
    page = json.loads(out)
    assert code == 0 and len(page["objects"]) == 2 and page["total"] > 2
    assert all(o["room_id"] == "room:kitchen" for o in page["objects"])
    code, out = run("ls", "rooms", "-m", str(map_dir), "--floor", "floor:1")
    assert code == 0 and "bathroom" in out and "kitchen" not in out and "of 2" in out
    code, out = run("ls", "objects", "-m", str(map_dir), "--limit", "5")
    assert code == 0 and "(more: --offset 5)" in out


def test_show_an_object(map_dir: Path) -> None:
    code, out = run("show", "obj:m3", "--map", str(map_dir), "--json")
    assert code == 0, out
    detail = json.loads(out)
    assert detail["label"] == "mug" and detail["room_id"] == "room:living"
    assert [h["layer"] for h in detail["hierarchy"]] == ["area", "room", "floor"]
    assert any(r["other_id"] == "obj:ct1" for r in detail["relations"])
    code, out = run("show", "obj:m3", "--map", str(map_dir))
    assert code == 0 and "obj:m3  mug" in out and "room room:living (living room)" in out


def test_bad_reads_give_clear_errors(map_dir: Path, tmp_path: Path) -> None:
    code, out = run("show", "obj:nope", "--map", str(map_dir))
    assert code == 2 and "no object with id 'obj:nope'" in out
    code, out = run("ls", "floors", "--map", str(map_dir), "--room", "room:kitchen")
    assert code == 2 and "--room filters areas and objects" in out
    code, out = run("ls", "tables", "--map", str(map_dir))
    assert code == 2 and "tables" in out
    code, out = run("ls", "rooms", "--map", str(tmp_path / "missing"))
    assert code == 2 and "missing" in out


def test_query_results_are_typed_and_say_the_same_as_the_json(map_dir: Path) -> None:
    with MapService.open(map_dir) as service:
        result = service.query("the mug on the coffee table", verify=False)
    typed = result.model()
    assert typed.answer is not None and typed.answer.id == "obj:m3" and typed.answer.floor == 0
    assert typed.candidates[0].scores["c1"].kind == "label"
    relation = typed.constraints.constraints[1]
    assert relation.kind == "relation" and relation.model_extra["predicate"] == "on"
    assert typed.model_dump(mode="json", exclude_unset=True) == json.loads(result.to_json())
