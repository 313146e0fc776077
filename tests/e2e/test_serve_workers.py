"""``inherit-sg serve --workers 2``: two real server processes behind one port answer
queries on the same map read-only, and refuse what needs one process (a live session,
a conversation) with a clear error instead of a wrong answer."""

from __future__ import annotations

import subprocess
import sys
import time
from collections.abc import Iterator

import httpx
import pytest

from tests.e2e.oracle_maps import oracle_map
from tests.local_http import free_port

NAME = "house"


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    root = tmp_path_factory.mktemp("workers")
    map_dir = oracle_map(root, NAME, seed=4, rooms=5)  # a one-floor house with a bedroom
    port = free_port()
    log = (root / "serve.log").open("wb")
    proc = subprocess.Popen(
        [
            *(sys.executable, "-m", "inherit_sg.cli.main", "serve", "--map", str(map_dir)),
            *("--port", str(port), "--workers", "2"),
        ],
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 120
        while True:
            assert proc.poll() is None, (root / "serve.log").read_text()
            try:
                if httpx.get(f"{base}/readyz", timeout=2).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            assert time.monotonic() < deadline, (root / "serve.log").read_text()
            time.sleep(0.3)
        yield f"{base}/v1/maps/{NAME}"
    finally:
        proc.terminate()
        proc.wait(timeout=30)
        log.close()
    text = (root / "serve.log").read_text()
    assert text.count("Application startup complete") == 2  # two processes served


def test_two_processes_answer_queries(served: str) -> None:
    with httpx.Client(timeout=60) as http:
        answers = [
            http.post(f"{served}/query", json={"text": "the bed", "verify": False})
            for _ in range(12)
        ]
    assert all(r.status_code == 200 for r in answers), answers[0].text
    labels = {r.json()["answer"]["label"] for r in answers}
    assert labels == {"bed"}


def test_what_needs_one_process_is_refused_clearly(served: str) -> None:
    with httpx.Client(timeout=60) as http:
        session = http.post(f"{served}/sessions", json={"name": "walk"})
        assert session.status_code == 409
        assert "--workers 1" in session.json()["message"]
        conv = http.post(f"{served}/query", json={"text": "the bed", "conversation_id": "c1"})
        assert conv.status_code == 400
        assert "--workers 1" in conv.json()["message"]
        # the map is still served after both refusals
        ok = http.post(f"{served}/query", json={"text": "the bed", "verify": False})
        assert ok.status_code == 200
