"""``inherit-sg query`` end to end on a real map of the small scene: one request (text
and JSON), the plan, batches with bad lines, conversation files and bad input."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from inherit_sg.cli import query_cmd
from tests.unit.retrieval_fixtures import write_small_map

runner = CliRunner()


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_small_map(tmp_path_factory.mktemp("cli") / "map")


def run(*args: str) -> tuple[int, str]:
    result = runner.invoke(query_cmd.app, list(args))
    return result.exit_code, result.output


def test_query_json(map_dir: Path) -> None:
    code, out = run("--map", str(map_dir), "the mug on the coffee table", "--json", "--top-k", "2")
    assert code == 0, out
    data = json.loads(out)
    assert data["answer"]["id"] == "obj:m3" and data["answer"]["label"] == "mug"
    assert data["answer"]["room"] == "living room" and data["answer"]["floor"] == 0
    assert len(data["candidates"]) == 2
    assert data["constraints"]["target"]["labels"] == ["mug"]
    assert set(data["timings_ms"]) == {"parse", "retrieve", "verify", "total"}


def test_query_text_with_plan(map_dir: Path) -> None:
    code, out = run("--map", str(map_dir), "a lamp upstairs", "--explain", "--no-verify")
    assert code == 0, out
    assert "plan for: 'a lamp upstairs'" in out and "H_floor" in out
    assert "answer: obj:l3 lamp" in out and "candidates" in out
    assert "total" in out and "ms" in out


def test_batch(map_dir: Path, tmp_path: Path) -> None:
    src = tmp_path / "in.jsonl"
    lines = [
        {"id": "q1", "text": "the sofa"},
        {"id": "q2", "text": "   "},
        {"id": "q3", "text": "the refrigerator", "category": "A", "target_ids": ["f1"]},
    ]
    src.write_text("\n".join(json.dumps(x) for x in lines) + "\nnot json\n")
    dst = tmp_path / "out.jsonl"
    code, out = run("--map", str(map_dir), "--batch", str(src), "--out", str(dst), "--json")
    assert code == 0, out
    assert json.loads(out) == {"requests": 4, "answered": 2, "no_answer": 0, "errors": 2}
    rows = [json.loads(x) for x in dst.read_text().splitlines()]
    assert [r["id"] for r in rows] == ["q1", "q2", "q3", "4"]
    assert rows[0]["answer"]["id"] == "obj:s1" and rows[2]["answer"]["id"] == "obj:f1"
    assert rows[1]["error"]["error"] == "bad_query"
    assert "invalid JSON" in rows[3]["error"]["message"]


def test_conversation_file(map_dir: Path, tmp_path: Path) -> None:
    conv = tmp_path / "conv.json"
    code, out = run(
        "--map", str(map_dir), "the mug on the coffee table", "--json", "--conversation", str(conv)
    )
    assert code == 0 and json.loads(out)["answer"]["id"] == "obj:m3"
    code, out = run("--map", str(map_dir), "the other one", "--json", "--conversation", str(conv))
    assert code == 0, out
    data = json.loads(out)
    assert data["answer"]["id"] in {"obj:m1", "obj:m2"}
    assert len(json.loads(conv.read_text())["turns"]) == 2


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["   "], "empty"),
        (["x" * 5001], "long"),
        ([], "either a request TEXT or --batch"),
        (["--batch", "in.jsonl"], "--batch needs --out"),
    ],
)
def test_bad_input_is_a_clear_error(map_dir: Path, args: list[str], message: str) -> None:
    code, out = run("--map", str(map_dir), *args)
    assert code == 2
    assert message in out


def test_missing_map_is_an_error(tmp_path: Path) -> None:
    code, out = run("--map", str(tmp_path / "nope"), "the sofa", "--json")
    assert code == 2
    assert json.loads(out)["error"] == "map_not_found"


def test_query_with_an_image(map_dir: Path, tmp_path: Path) -> None:
    import cv2
    import numpy as np

    picture = tmp_path / "mug.png"
    cv2.imwrite(str(picture), np.full((64, 64, 3), (40, 40, 190), np.uint8))
    code, out = run("--map", str(map_dir), "a mug", "--image", str(picture), "--json")
    assert code == 0, out
    data = json.loads(out)
    assert data["answer"]["label"] == "mug"
    assert data["candidates"][0]["scores"]["image"]["kind"] == "visual"
    code, out = run("--map", str(map_dir), "a mug", "--image", str(tmp_path / "none.png"))
    assert code == 2 and "not found or not an image" in out


def test_query_with_the_robots_pose(map_dir: Path) -> None:
    code, out = run("--map", str(map_dir), "the sofa", "--json", "--viewer=7.5,-1,0,90")
    assert code == 0, out
    trace = json.loads(out)["trace"]
    assert "robot pose given: (7.50, -1.00, 0.00), heading 90°" in trace


@pytest.mark.parametrize("value", ["1,2", "a,b,c,d", "1,2,3,inf"])
def test_bad_viewer_is_a_clear_error(map_dir: Path, value: str) -> None:
    code, out = run("--map", str(map_dir), "the sofa", f"--viewer={value}")
    assert code == 2
    assert "viewer" in out and "error" in out


def test_batch_lines_may_carry_a_viewer(map_dir: Path, tmp_path: Path) -> None:
    src = tmp_path / "in.jsonl"
    lines = [
        {"id": "own", "text": "the sofa", "viewer": {"position": [1, 2, 0], "yaw_deg": 180}},
        {"id": "bad", "text": "the sofa", "viewer": {"position": [1, 2]}},
        {"id": "default", "text": "the sofa"},
    ]
    src.write_text("\n".join(json.dumps(x) for x in lines) + "\n")
    dst = tmp_path / "out.jsonl"
    args = ["--map", str(map_dir), "--batch", str(src), "--out", str(dst), "--json"]
    code, out = run(*args, "--viewer=0,0,0,45")
    assert code == 0, out
    assert json.loads(out) == {"requests": 3, "answered": 2, "no_answer": 0, "errors": 1}
    rows = {r["id"]: r for r in map(json.loads, dst.read_text().splitlines())}
    assert "robot pose given: (1.00, 2.00, 0.00), heading 180°" in rows["own"]["trace"]
    assert "viewer must be an object" in rows["bad"]["error"]["message"]
    assert "robot pose given: (0.00, 0.00, 0.00), heading 45°" in rows["default"]["trace"]
