"""REST service benchmark: query throughput and latency under concurrent clients.

A generated house is imported as an oracle map and served by a real ``inherit-sg serve``
process on a free loopback port. For each concurrency level (``--clients``) that many
client threads, each with its own HTTP connection, send requests from the house's query
set (verification off) for ``--seconds``; queries/s and p50 / p99 latency are reported.
Every query is sent once beforehand, so the numbers are for cached phrase embeddings.

Two phases: ``idle`` (only queries), then ``mapping``: a live session on the same map is
fed the house's rendered frames (``POST /v1/maps/{map}/sessions`` … ``/frames``, at most
``--fps``, honouring 429 Retry-After) while the same query load runs; the session is
finished at the end. The mapping phase is skipped with a note when the server has no live
session routes.

A third phase serves the same map from several processes (``serve --workers N``,
read-only; ``--workers 2`` by default) and measures the idle load again.

Run: ``python bench/service.py [--seed 201] [--clients 1,4,16] [--seconds 5] [--fps 5]
[--frames 60] [--workers 2] [--out bench/results/service.json]``
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import httpx
import numpy as np

from inherit_sg.benchmark.machine import machine_reference
from inherit_sg.facade import import_into_new_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.ingest.synthetic.queries import generate_queries

ROOT = Path(__file__).resolve().parents[1]
NAME = "house"
READY_TIMEOUT_S = 180.0


def free_port() -> int:
    """A TCP port on loopback that nothing listens on right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def start_server(map_dir: Path, port: int, log: Path, workers: int = 1) -> subprocess.Popen[bytes]:
    """``inherit-sg serve`` (``--workers``) in a child process; returns once ``/readyz``
    answers 200."""
    cmd = [
        sys.executable,
        "-c",
        "from inherit_sg.cli.main import main; main()",
        "serve",
        "--map",
        str(map_dir),
        "--host",
        "127.0.0.1",
        "--port",
        str(port),
        "--workers",
        str(workers),
    ]
    with log.open("wb") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, cwd=ROOT)
    deadline = time.monotonic() + READY_TIMEOUT_S
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"server exited with {proc.returncode}; see {log}")
        try:
            if httpx.get(f"http://127.0.0.1:{port}/readyz", timeout=2).status_code == 200:
                return proc
        except httpx.TransportError:
            pass
        time.sleep(0.3)
    proc.terminate()
    raise RuntimeError(f"server not ready after {READY_TIMEOUT_S:.0f} s; see {log}")


def query_load(base: str, texts: list[str], clients: int, seconds: float) -> dict[str, Any]:
    """``clients`` threads sending queries for ``seconds``; throughput and latency."""
    url = f"{base}/v1/maps/{NAME}/query"
    latencies: list[list[float]] = [[] for _ in range(clients)]
    errors = [0] * clients
    start = threading.Barrier(clients + 1)

    def worker(i: int) -> None:
        with httpx.Client(timeout=60) as client:
            client.post(url, json={"text": texts[i % len(texts)], "verify": False})  # warm-up
            start.wait()
            n = i
            while time.perf_counter() < stop_at:
                t0 = time.perf_counter()
                resp = client.post(url, json={"text": texts[n % len(texts)], "verify": False})
                latencies[i].append(time.perf_counter() - t0)
                errors[i] += resp.status_code != 200
                n += clients

    stop_at = float("inf")  # set once every client is warm
    threads = [threading.Thread(target=worker, args=(i,)) for i in range(clients)]
    for t in threads:
        t.start()
    start.wait()
    began = time.perf_counter()
    stop_at = began + seconds
    for t in threads:
        t.join()
    elapsed = time.perf_counter() - began
    lat = np.asarray([x for per in latencies for x in per]) * 1000.0
    return {
        "clients": clients,
        "requests": int(lat.size),
        "errors": int(sum(errors)),
        "seconds": round(elapsed, 2),
        "qps": round(lat.size / elapsed, 2),
        "p50_ms": round(float(np.percentile(lat, 50)), 1) if lat.size else None,
        "p99_ms": round(float(np.percentile(lat, 99)), 1) if lat.size else None,
        "mean_ms": round(float(lat.mean()), 1) if lat.size else None,
    }


def warm_up(base: str, texts: list[str]) -> None:
    """Send every query once so phrase embeddings are cached before timing."""
    with httpx.Client(timeout=120) as client:
        for text in texts:
            client.post(f"{base}/v1/maps/{NAME}/query", json={"text": text, "verify": False})


def frame_parts(dataset: Path) -> list[tuple[dict[str, tuple[str, bytes, str]], dict[str, str]]]:
    """Multipart files and form fields of every frame of an isg folder, in walk order."""
    intrinsics = (dataset / "intrinsics.json").read_text(encoding="utf-8")
    shared_labels = dataset / "instances.json"
    out = []
    for i, line in enumerate((dataset / "poses.txt").read_text().splitlines()):
        fid, *pose = line.split()
        frames = dataset / "frames"
        rgb = next(frames.glob(f"{fid}.rgb.*"))
        files = {
            "rgb": (rgb.name, rgb.read_bytes(), "image/png"),
            "depth": ("depth.png", (frames / f"{fid}.depth.png").read_bytes(), "image/png"),
        }
        form = {"pose": " ".join(pose)}
        if i == 0:
            form["intrinsics"] = intrinsics
        inst = frames / f"{fid}.instances.png"
        if inst.is_file():
            files["instances"] = ("instances.png", inst.read_bytes(), "image/png")
            labels = frames / f"{fid}.instances.json"
            source = labels if labels.is_file() else shared_labels
            if source.is_file():
                form["instance_labels"] = source.read_text(encoding="utf-8")
        out.append((files, form))
    return out


class FramePoster(threading.Thread):
    """Posts frames to a live session at most ``fps`` per second until stopped; frames
    after the first loop around the walk without intrinsics."""

    def __init__(self, base: str, sid: str, frames: list[Any], fps: float) -> None:
        super().__init__(daemon=True)
        self.url = f"{base}/v1/maps/{NAME}/sessions/{sid}/frames"
        self.frames, self.period = frames, 1.0 / fps
        self.stop = threading.Event()
        self.counts = {"accepted": 0, "throttled": 0, "rejected": 0}

    def run(self) -> None:
        with httpx.Client(timeout=60) as client:
            i = 0
            while not self.stop.is_set():
                t0 = time.perf_counter()
                files, form = self.frames[i % len(self.frames)]
                if i >= len(self.frames):
                    form = {k: v for k, v in form.items() if k != "intrinsics"}
                resp = client.post(self.url, files=files, data=form)
                if resp.status_code in (429, 503):
                    self.counts["throttled"] += 1
                    self.stop.wait(float(resp.headers.get("Retry-After", "1")))
                    continue
                self.counts["accepted" if resp.status_code == 202 else "rejected"] += 1
                i += 1
                self.stop.wait(max(0.0, self.period - (time.perf_counter() - t0)))


def mapping_phase(
    base: str, texts: list[str], args: argparse.Namespace, frames: list[Any]
) -> dict[str, Any]:
    """The query load while a live session maps the house's frames."""
    created = httpx.post(f"{base}/v1/maps/{NAME}/sessions", json={"name": "bench"}, timeout=60)
    if created.status_code in (404, 405):
        return {"skipped": f"no live session routes (POST sessions answered {created.status_code})"}
    created.raise_for_status()
    sid = created.json()["session_id"]
    poster = FramePoster(base, sid, frames, args.fps)
    poster.start()
    began = time.perf_counter()
    time.sleep(1.0)  # the session is under way before the clients start
    levels = [query_load(base, texts, n, args.seconds) for n in args.clients]
    poster.stop.set()
    poster.join()
    posted_s = time.perf_counter() - began
    finished = httpx.post(f"{base}/v1/maps/{NAME}/sessions/{sid}/finish", timeout=600)
    return {
        "levels": levels,
        "frames": poster.counts,
        "frames_per_s": round(poster.counts["accepted"] / posted_s, 2),
        "finish_status": finished.status_code,
    }


def print_table(results: dict[str, Any]) -> None:
    """Queries/s and latency per phase and concurrency."""
    print(
        f"{'phase':8} {'clients':>7} {'req':>6} {'err':>4} {'q/s':>8} {'p50 ms':>8} {'p99 ms':>8}"
    )
    for phase in ("idle", "mapping"):
        data = results[phase]
        if "skipped" in data:
            print(f"{phase:8} skipped: {data['skipped']}")
            continue
        for r in data["levels"]:
            print(
                f"{phase:8} {r['clients']:>7} {r['requests']:>6} {r['errors']:>4} "
                f"{r['qps']:>8.2f} {r['p50_ms']!s:>8} {r['p99_ms']!s:>8}"
            )
    for count, data in results.get("workers", {}).items():
        for r in data["levels"]:
            print(
                f"{count + ' proc':8} {r['clients']:>7} {r['requests']:>6} {r['errors']:>4} "
                f"{r['qps']:>8.2f} {r['p50_ms']!s:>8} {r['p99_ms']!s:>8}"
            )
    if "frames" in results["mapping"]:
        m = results["mapping"]
        print(f"frames while mapping: {m['frames']} ({m['frames_per_s']} accepted/s)")


def main() -> None:
    """Build the map, run both phases, write and print the results."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=201)
    parser.add_argument("--clients", default="1,4,16")
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--fps", type=float, default=5.0, help="live frames per second (max)")
    parser.add_argument("--frames", type=int, default=60, help="frames rendered for the walk")
    parser.add_argument(
        "--workers",
        default="2",
        help="server process counts to measure besides one (idle phase only: several "
        "processes serve read-only); empty for none",
    )
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "service.json")
    args = parser.parse_args()
    args.clients = [int(c) for c in args.clients.split(",")]
    args.workers = [int(w) for w in args.workers.split(",") if w.strip() and int(w) > 1]

    with tempfile.TemporaryDirectory(prefix="bench-service-") as tmp:
        work = Path(tmp)
        house = generate_house(args.seed, 1)
        (work / "scene.json").write_text(json.dumps(house.scene.to_dict()))
        map_dir = work / NAME
        import_into_new_map(work / "scene.json", map_dir, fmt="scene")
        texts = [q.text for q in generate_queries(house.scene, args.seed)]
        write_dataset(house, work / "walk", width=320, height=240, max_frames=args.frames)
        frames = frame_parts(work / "walk")
        port = free_port()
        server = start_server(map_dir, port, work / "server.log")
        base = f"http://127.0.0.1:{port}"
        try:
            warm_up(base, texts)
            results: dict[str, Any] = {
                "seed": args.seed,
                "queries": len(texts),
                "seconds_per_level": args.seconds,
                "verify": False,
                "cpus": os.cpu_count(),
                "load_avg_at_start": [round(x, 2) for x in os.getloadavg()],
                "machine_reference": machine_reference(),
                "idle": {
                    "levels": [query_load(base, texts, n, args.seconds) for n in args.clients]
                },
            }
            results["mapping"] = mapping_phase(base, texts, args, frames)
            results["load_avg_at_end"] = [round(x, 2) for x in os.getloadavg()]
        finally:
            server.terminate()
            server.wait(timeout=30)
        results["workers"] = {}
        for count in args.workers:
            port = free_port()
            server = start_server(map_dir, port, work / f"server-{count}.log", count)
            base = f"http://127.0.0.1:{port}"
            try:
                for _ in range(count):  # each process keeps its own phrase cache
                    warm_up(base, texts)
                levels = [query_load(base, texts, n, args.seconds) for n in args.clients]
                results["workers"][str(count)] = {"levels": levels}
            finally:
                server.terminate()
                server.wait(timeout=30)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"service": results}, indent=2) + "\n", encoding="utf-8")
    print_table(results)
    print(f"→ {args.out}")


if __name__ == "__main__":
    main()
