"""The README's main job: ``inherit-sg demo`` end to end as a user runs it (a real
process), at a small resolution, then serving the map it built with ``--serve``."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import httpx

from tests.local_http import free_port


def _wait_ready(base: str, proc: subprocess.Popen[str], timeout_s: float) -> None:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        assert proc.poll() is None, "demo exited before serving"
        try:
            if httpx.get(f"{base}/readyz", timeout=1.0).status_code == 200:
                return
        except httpx.TransportError:
            pass
        time.sleep(0.5)
    raise AssertionError(f"demo did not start serving within {timeout_s} s")


def test_demo_builds_answers_and_serves(tmp_path: Path) -> None:
    out = tmp_path / "demo"
    port = free_port()
    cmd = [
        sys.executable,
        "-m",
        "inherit_sg.cli.main",
        "demo",
        "--out",
        str(out),
        "--width",
        "160",
        "--height",
        "120",
        "--json",
        "--serve",
        "--port",
        str(port),
    ]
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=dict(os.environ)
    )
    base = f"http://127.0.0.1:{port}"
    try:
        _wait_ready(base, proc, timeout_s=300)
        stats = httpx.get(f"{base}/v1/maps/map", timeout=10).json()
        assert stats["nodes"]["Floor"] == 2 and stats["nodes"]["Object"] > 20
        answer = httpx.post(f"{base}/v1/maps/map/query", json={"text": "a bed"}, timeout=30).json()
        assert answer["answer"]["label"] == "bed"
    finally:
        proc.send_signal(signal.SIGINT)
        stdout, _ = proc.communicate(timeout=30)
    summary = json.loads(stdout)
    assert summary["map"]["floors"] == 2
    assert len(summary["answers"]) >= 8
    # at 160×120 perception is coarse; most showcase answers must still be right
    assert summary["correct"] >= len(summary["answers"]) // 2
    for png in summary["map"]["bev"]:
        assert Path(png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
