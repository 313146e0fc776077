"""``inherit-sg serve --ray``: a root folder of two maps served by a Ray Serve deployment
of two replicas on a local Ray cluster; both replicas answer, and their answers equal
MapService.query on the same maps."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from inherit_sg.facade import MapService
from tests.e2e.oracle_maps import oracle_map
from tests.local_http import free_port

pytest.importorskip("ray.serve")
from inherit_sg.scale.serve import REPLICA_HEADER

REQUESTS = ("the bed", "a chair", "something to sit on")


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, Path]]:
    root = tmp_path_factory.mktemp("serve_ray")
    oracle_map(root, "house", seed=4, rooms=5)
    oracle_map(root, "flat", seed=6, rooms=4)
    maps = root / "maps"
    port = free_port()
    log_path = root / "serve.log"
    log = log_path.open("wb")
    proc = subprocess.Popen(
        [
            *(sys.executable, "-m", "inherit_sg.cli.main", "serve", "--map", str(maps)),
            *("--port", str(port), "--ray", "--replicas", "2"),
        ],
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 240
        while True:
            assert proc.poll() is None, log_path.read_text()
            try:
                if httpx.get(f"{base}/readyz", timeout=2).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            assert time.monotonic() < deadline, log_path.read_text()
            time.sleep(0.5)
        yield base, maps
    finally:
        proc.send_signal(signal.SIGTERM)  # shuts Serve and the local Ray cluster down
        try:
            proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=30)
        log.close()
    assert "2 Ray Serve replicas" in log_path.read_text()


def _comparable(result: dict) -> dict:
    return {
        "answer": result["answer"],
        "candidates": [(c["id"], round(c["score"], 6)) for c in result["candidates"]],
        "constraints": result["constraints"],
    }


def test_two_replicas_answer_like_the_facade(served: tuple[str, Path]) -> None:
    base, maps = served
    replicas: set[str] = set()
    answers: dict[tuple[str, str], dict] = {}
    with httpx.Client(timeout=60) as http:
        for i in range(40):
            name = ("house", "flat")[i % 2]
            text = REQUESTS[i % len(REQUESTS)]
            r = http.post(f"{base}/v1/maps/{name}/query", json={"text": text, "verify": False})
            assert r.status_code == 200, r.text
            replicas.add(r.headers[REPLICA_HEADER])
            got = _comparable(r.json())
            assert answers.setdefault((name, text), got) == got  # every replica agrees
            if len(replicas) == 2 and len(answers) == 2 * len(REQUESTS):
                break
    assert len(replicas) == 2, replicas
    for (name, text), got in answers.items():
        with MapService.open(maps / name) as service:
            want = service.query(text, verify=False).to_dict()
        assert got == _comparable(want), (name, text)
    assert answers[("house", "the bed")]["answer"]["label"] == "bed"


def test_replicas_refuse_what_needs_one_process(served: tuple[str, Path]) -> None:
    base, _ = served
    with httpx.Client(timeout=60) as http:
        session = http.post(f"{base}/v1/maps/house/sessions", json={"name": "walk"})
        assert session.status_code == 409, session.text
        listing = http.get(f"{base}/v1/maps/flat/objects", params={"limit": 5})
        assert listing.status_code == 200 and listing.json()["objects"]
