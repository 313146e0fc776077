"""A real uvicorn server on loopback: a generated house is mapped live over HTTP (frames
posted one by one with httpx), the session finished, and "a bed" is found within 1 m of
the true bed; a session left open is finished when the server shuts down."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import numpy as np
import pytest
import uvicorn

from inherit_sg.api.app import create_app
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.store import MapStore
from tests.local_http import uvicorn_on_loopback

NAME = "house"
SEED, ROOMS = 4, 5  # a one-floor house with a bedroom


@pytest.fixture(scope="module")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("uvicorn") / "walk"
    write_dataset(generate_house(SEED, 1, ROOMS), out, width=160, height=120, workers=1)
    return out


Served = tuple[str, Path, uvicorn.Server, threading.Thread]


@pytest.fixture
def server(tmp_path: Path) -> Iterator[Served]:
    """An empty map served by uvicorn in a thread: (base URL, map dir, server, thread)."""
    map_dir = tmp_path / NAME
    MapStore.create(map_dir).close()
    with uvicorn_on_loopback(create_app(map_dir)) as (base, srv, thread):
        yield f"{base}/v1/maps/{NAME}", map_dir, srv, thread


def post_frame(http: httpx.Client, url: str, dataset: Path, index: int) -> httpx.Response:
    """Post dataset frame ``index`` (retrying while the server answers 429)."""
    line = (dataset / "poses.txt").read_text().splitlines()[index].split()
    base = dataset / "frames" / line[0]
    files = {
        "rgb": ("rgb.png", Path(f"{base}.rgb.png").read_bytes(), "image/png"),
        "depth": ("depth.png", Path(f"{base}.depth.png").read_bytes(), "image/png"),
        "instances": ("inst.png", Path(f"{base}.instances.png").read_bytes(), "image/png"),
    }
    data = {
        "pose": " ".join(line[1:]),
        "instance_labels": Path(f"{base}.instances.json").read_text(),
        "timestamp": str(index / 10),
    }
    if index == 0:
        data["intrinsics"] = (dataset / "intrinsics.json").read_text()
    while True:
        resp = http.post(url, files=files, data=data)
        if resp.status_code != 429:
            return resp
        assert int(resp.headers["Retry-After"]) >= 1
        time.sleep(0.1)


def test_live_mapping_over_http_finds_the_bed(server: Served, dataset: Path) -> None:
    base, map_dir, srv, thread = server
    n = len((dataset / "poses.txt").read_text().splitlines())
    with httpx.Client(timeout=120) as http:
        created = http.post(f"{base}/sessions", json={"name": "http walk", "frame_queue": 16})
        assert created.status_code == 201, created.text
        sid = created.json()["session_id"]
        for i in range(n):
            resp = post_frame(http, f"{base}/sessions/{sid}/frames", dataset, i)
            assert resp.status_code == 202 and resp.json()["frame"] == i, resp.text
            if i % 8 == 7:  # pace like a polite client: let the semantic stream keep up
                while http.get(f"{base}/sessions/{sid}").json()["keyframes_pending"] > 24:
                    time.sleep(0.05)
        summary = http.post(f"{base}/sessions/{sid}/finish")
        assert summary.status_code == 200, summary.text
        assert summary.json()["frames"] == n and summary.json()["rooms"] >= 3
        answer = http.post(f"{base}/query", json={"text": "a bed"}).json()["answer"]
        # a second session is left open: shutting the server down must finish it
        second = http.post(f"{base}/sessions", json={"name": "left open"}).json()["session_id"]
        for i in range(3):
            assert post_frame(http, f"{base}/sessions/{second}/frames", dataset, i).is_success
    truth = Scene.load(dataset)
    beds = [np.asarray(o.centroid) for o in truth.objects if o.label == "bed"]
    assert answer is not None and answer["label"] == "bed"
    assert min(np.linalg.norm(b - np.asarray(answer["position"])) for b in beds) < 1.0
    assert (map_dir / "bev" / "floor_0.png").is_file()
    srv.should_exit = True  # the lifespan shutdown finishes the open session
    thread.join(timeout=120)
    assert not thread.is_alive()
    with MapStore.open(map_dir) as store:
        sessions = {s.name: s for s in store.sessions()}
    assert sessions["http walk"].frames == n
    assert sessions["left open"].finished is not None and sessions["left open"].frames == 3
