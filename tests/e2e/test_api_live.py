"""Live mapping over REST: sessions, multipart frames and their validation, back-pressure
(429 and 503 with Retry-After) and queries that see a session's objects while it maps."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import cv2
import numpy as np
import pytest
from fastapi.testclient import TestClient

from inherit_sg.api.app import create_app
from inherit_sg.api.state import Registry, ServedMap
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.store import MapStore

NAME = "live"
BASE = f"/v1/maps/{NAME}"


@pytest.fixture(scope="module")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("live") / "walk"
    write_dataset(generate_house(3, 1, 4), out, width=160, height=120, workers=1, max_frames=30)
    return out


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("maps") / NAME
    MapStore.create(path).close()
    return path


@pytest.fixture(scope="module")
def client(map_dir: Path) -> Iterator[TestClient]:
    with TestClient(create_app(map_dir)) as c:
        yield c


def served(client: TestClient) -> ServedMap:
    registry: Registry = client.app.state.registry  # type: ignore[attr-defined]
    return registry.get(NAME)


def frame_parts(
    dataset: Path, index: int, *, intrinsics: bool = True
) -> tuple[dict[str, bytes], dict[str, str]]:
    """Multipart files and form fields of dataset frame ``index``."""
    line = (dataset / "poses.txt").read_text().splitlines()[index].split()
    base = dataset / "frames" / line[0]
    files = {
        "rgb": Path(f"{base}.rgb.png").read_bytes(),
        "depth": Path(f"{base}.depth.png").read_bytes(),
        "instances": Path(f"{base}.instances.png").read_bytes(),
    }
    data = {
        "pose": " ".join(line[1:]),
        "instance_labels": Path(f"{base}.instances.json").read_text(),
    }
    if intrinsics:
        data["intrinsics"] = (dataset / "intrinsics.json").read_text()
    return files, data


def start(client: TestClient, **body: Any) -> str:
    resp = client.post(f"{BASE}/sessions", json=body)
    assert resp.status_code == 201, resp.text
    assert resp.json()["map"] == NAME
    return str(resp.json()["session_id"])


def post(client: TestClient, sid: str, files: dict[str, bytes], data: dict[str, str]) -> Any:
    return client.post(f"{BASE}/sessions/{sid}/frames", files=files, data=data)


def wait_until(check: Callable[[], bool], timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while not check():
        assert time.monotonic() < deadline, "condition not reached in time"
        time.sleep(0.05)


def png(img: np.ndarray) -> bytes:
    ok, buf = cv2.imencode(".png", img)
    assert ok
    return buf.tobytes()


def test_session_lifecycle_conflict_and_unknown(client: TestClient, dataset: Path) -> None:
    frame = frame_parts(dataset, 0)
    sid = start(client, name="lifecycle")
    status = client.get(f"{BASE}/sessions/{sid}").json()
    assert status["state"] == "mapping" and status["name"] == "lifecycle"
    assert status["frames_received"] == 0 and status["map"] == NAME
    assert served(client).require().store.writable  # served writable while mapping
    second = client.post(f"{BASE}/sessions", json={})
    assert second.status_code == 409 and sid in second.json()["message"]
    for resp in (
        client.get(f"{BASE}/sessions/session:99"),
        client.post(f"{BASE}/sessions/session:99/finish"),
        post(client, "session:99", *frame),
        client.post("/v1/maps/nope/sessions", json={}),
    ):
        assert resp.status_code == 404, resp.text
    summary = client.post(f"{BASE}/sessions/{sid}/finish")
    assert summary.status_code == 200 and summary.json()["session_id"] == sid
    assert summary.json()["frames"] == 0
    assert client.post(f"{BASE}/sessions/{sid}/finish").json() == summary.json()
    assert client.get(f"{BASE}/sessions/{sid}").json()["state"] == "finished"
    late = post(client, sid, *frame)
    assert late.status_code == 409 and "finished" in late.json()["message"]
    assert not served(client).require().store.writable  # read-only again
    names = [s["name"] for s in client.get(BASE).json()["sessions"]]
    assert "lifecycle" in names
    dup = client.post(f"{BASE}/sessions", json={"name": "lifecycle"})
    assert dup.status_code == 409 and "lifecycle" in dup.json()["message"]
    assert client.post(f"{BASE}/sessions", json={"frame_queue": 0}).status_code == 400


def test_bad_frames_are_refused_and_change_nothing(client: TestClient, dataset: Path) -> None:
    sid = start(client)
    files, data = frame_parts(dataset, 0)
    rgb = cv2.imdecode(np.frombuffer(files["rgb"], np.uint8), cv2.IMREAD_COLOR)
    assert rgb is not None
    rot = "2 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1"
    cases: list[tuple[dict[str, bytes], dict[str, str], str]] = [
        ({**files, "rgb": b"not an image"}, data, "rgb"),
        ({**files, "rgb": b""}, data, "rgb"),
        ({**files, "rgb": png(cv2.resize(rgb, (80, 60)))}, data, "intrinsics say"),
        ({**files, "depth": png(np.zeros((120, 160), np.uint8))}, data, "uint16"),
        (files, {**data, "pose": "1 2 3"}, "16 numbers"),
        (files, {**data, "pose": " ".join(["nan"] * 16)}, "NaN"),
        (files, {**data, "pose": "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,NaN]]"}, "pose"),
        (files, {**data, "pose": rot}, "rotation"),
        (files, {**data, "intrinsics": "{not json"}, "intrinsics"),
        (files, {**data, "intrinsics": '{"width": 160}'}, "intrinsics"),
        (files, {k: v for k, v in data.items() if k != "intrinsics"}, "intrinsics"),
        ({k: v for k, v in files.items() if k != "instances"}, data, "instance"),
        (files, {**data, "timestamp": "-1"}, "timestamp"),
    ]
    for bad_files, bad_data, needle in cases:
        resp = post(client, sid, bad_files, bad_data)
        assert resp.status_code == 400, (needle, resp.text)
        assert needle.lower() in resp.json()["message"].lower(), resp.json()
    missing = client.post(f"{BASE}/sessions/{sid}/frames", data=data)  # no files at all
    assert missing.status_code == 400 and "rgb" in missing.json()["message"]
    assert client.get(f"{BASE}/sessions/{sid}").json()["frames_received"] == 0
    ok = post(client, sid, files, data)
    assert ok.status_code == 202 and ok.json()["frame"] == 0
    later, later_data = frame_parts(dataset, 1, intrinsics=False)
    assert post(client, sid, later, later_data).json()["frame"] == 1
    numbers = [float(v) for v in later_data["pose"].split()]
    as_rows = json.dumps([numbers[r * 4 : r * 4 + 4] for r in range(4)])
    with_commas = ", ".join(str(v) for v in numbers)
    for pose in (as_rows, with_commas):  # the other accepted pose spellings
        resp = post(client, sid, later, {**later_data, "pose": pose, "timestamp": "2.5"})
        assert resp.status_code == 202, resp.text
    other = {
        **later_data,
        "intrinsics": '{"width":160,"height":120,"fx":50,"fy":50,"cx":80,"cy":60}',
    }
    assert post(client, sid, later, other).status_code == 400
    summary = client.post(f"{BASE}/sessions/{sid}/finish").json()
    assert summary["frames"] == 4


def test_back_pressure_answers_429_then_503(client: TestClient, dataset: Path) -> None:
    sid = start(client, frame_queue=1)
    live = served(client).active(sid)
    codes = []
    with live.mapper.geometry.lock:  # the geometric stream is busy (as in a global update)
        for i in range(3):
            resp = post(client, sid, *frame_parts(dataset, i))
            codes.append(resp.status_code)
            if resp.status_code == 429:
                assert int(resp.headers["Retry-After"]) >= 1
                assert resp.json()["error"] == "too_many_frames"
        assert codes[0] == 202 and 429 in codes
        finisher = threading.Thread(target=served(client).finish_live, args=(sid,))
        finisher.start()
        wait_until(lambda: live.state == "finishing")
        closing = post(client, sid, *frame_parts(dataset, 3))
        assert closing.status_code == 503 and int(closing.headers["Retry-After"]) >= 1
    finisher.join(timeout=60)
    status = client.get(f"{BASE}/sessions/{sid}").json()
    assert status["state"] == "finished"
    assert status["frames_processed"] == codes.count(202) == status["summary"]["frames"]


def test_queries_see_objects_while_the_session_maps(
    client: TestClient, dataset: Path, map_dir: Path
) -> None:
    sid = start(client, name="walk", flush_every=3)
    n = len((dataset / "poses.txt").read_text().splitlines())
    for i in range(n):
        parts = frame_parts(dataset, i, intrinsics=i == 0)
        while (resp := post(client, sid, *parts)).status_code == 429:
            time.sleep(0.05)
        assert resp.status_code == 202, resp.text
    seen_query = (
        "MATCH (o:Object)-[:SEEN_IN]->(k:Keyframe) WHERE k.session_id = $sid "
        "RETURN DISTINCT o.id, o.label ORDER BY o.id"
    )

    def seen() -> list[list[str]]:
        body = {"query": seen_query, "params": {"sid": sid}}
        rows: list[list[str]] = client.post(f"{BASE}/cypher", json=body).json()["rows"]
        return rows

    wait_until(lambda: bool(seen()))
    assert client.get(f"{BASE}/sessions/{sid}").json()["state"] == "mapping"
    oid, label = next((r for r in seen() if r[1] != "door"), seen()[0])
    answer = client.post(f"{BASE}/query", json={"text": f"the {label}", "verify": False})
    assert answer.status_code == 200 and answer.json()["answer"]["label"] == label
    detail = client.get(f"{BASE}/objects/{oid}")
    assert detail.status_code == 200 and detail.json()["label"] == label
    summary = client.post(f"{BASE}/sessions/{sid}/finish").json()
    assert summary["frames"] == n and summary["objects"] > 0 and summary["keyframes"] > 0
    assert [Path(p) for p in summary["bev"]] == [map_dir / "bev" / "floor_0.png"]
    assert (map_dir / "bev" / "floor_0.png").stat().st_size > 0
    stats = client.get(BASE).json()
    walk = next(s for s in stats["sessions"] if s["name"] == "walk")
    assert walk["frames"] == n and walk["finished"] is not None
    assert len(seen()) >= 1 and stats["nodes"]["Object"] >= summary["objects"]


def post_frames(client: TestClient, dataset: Path, sid: str, count: int, masks: bool) -> None:
    """Post the first ``count`` frames of the walk, retrying on 429."""
    for i in range(count):
        files, data = frame_parts(dataset, i, intrinsics=i == 0)
        if not masks:
            files.pop("instances")
            data.pop("instance_labels")
        while (resp := post(client, sid, files, data)).status_code == 429:
            time.sleep(0.05)
        assert resp.status_code == 202, resp.text


def test_frames_without_masks_warn_and_mark_nothing_missing(
    client: TestClient, dataset: Path
) -> None:
    if client.get(f"{BASE}/objects").json()["total"] == 0:  # run alone: map objects first
        sid = start(client, name="with masks")
        post_frames(client, dataset, sid, 12, masks=True)
        client.post(f"{BASE}/sessions/{sid}/finish")
    assert client.get(f"{BASE}/objects").json()["total"] > 0
    sid = start(client, name="no masks")
    post_frames(client, dataset, sid, 12, masks=False)
    wait_until(lambda: client.get(f"{BASE}/sessions/{sid}").json()["frames_queued"] == 0)
    summary = client.post(f"{BASE}/sessions/{sid}/finish").json()
    status = client.get(f"{BASE}/sessions/{sid}").json()
    # the default segmenter looks at them with the classical one, and says so
    assert "keyframes came without instance masks" in status["warnings"][0]
    assert "stay unnamed" in status["warnings"][0]
    # unnamed detections are no evidence that the named objects are gone
    assert summary["missing"] == 0
    missing = client.post(
        f"{BASE}/cypher",
        json={"query": "MATCH (o:Object) WHERE o.status = 'missing' RETURN count(o)"},
    ).json()["rows"]
    assert missing == [[0]]


def test_one_unusable_frame_loses_nothing_else(client: TestClient, dataset: Path) -> None:
    sid = start(client, name="far pose")
    for i in range(3):
        assert post(client, sid, *frame_parts(dataset, i, intrinsics=i == 0)).status_code == 202
    files, data = frame_parts(dataset, 3, intrinsics=False)
    numbers = data["pose"].split()
    # a broken translation is refused at the door
    huge = [*numbers[:3], "1e308", *numbers[4:]]
    resp = post(client, sid, files, {**data, "pose": " ".join(huge)})
    assert resp.status_code == 400 and "implausible" in resp.json()["message"]
    # a pose 5 km from the walk passes the door, and the mapper leaves that frame out
    far = [*numbers[:3], str(float(numbers[3]) + 5000.0), *numbers[4:]]
    assert post(client, sid, files, {**data, "pose": " ".join(far)}).status_code == 202
    for i in range(3, 6):
        assert post(client, sid, *frame_parts(dataset, i, intrinsics=False)).status_code == 202
    wait_until(lambda: client.get(f"{BASE}/sessions/{sid}").json()["frames_queued"] == 0)
    status = client.get(f"{BASE}/sessions/{sid}").json()
    assert status["state"] == "mapping" and status["frames_rejected"] == 1
    assert any("left out" in w and "beyond 300 m" in w for w in status["warnings"]), status
    summary = client.post(f"{BASE}/sessions/{sid}/finish")
    assert summary.status_code == 200, summary.text
    assert summary.json()["frames"] == 6
