"""Retrieval on generated houses from seeds nobody looked at: the honest figure.

A benchmark house that a developer has read the misses of is no longer fresh. This
script draws houses from seeds given on the command line (pick new ones for every
measurement you report), renders each at 640×480 with the default walk, maps it with
``inherit-sg map build`` and answers a category-balanced cut of its requests with
``inherit-sg bench --map … --no-ablations``, clean and noisy. Each run's JSON goes to
``bench/results/fresh_seeds/house-<seed>-<noise>.json``; the summary (per house and the
request-weighted mean per noise level) to ``bench/results/fresh_seeds.json``, which
``bench/run_all.py`` puts on docs/benchmarks.md.

    python bench/fresh_seeds.py --seeds 941,942,943 [--noise clean,noisy] [--work DIR]
    python bench/fresh_seeds.py --report-only     # re-summarise the JSON files
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
RUNS = ROOT / "bench" / "results" / "fresh_seeds"
SUMMARY = ROOT / "bench" / "results" / "fresh_seeds.json"
WIDTH, HEIGHT = 640, 480
GROUPS = ("A-C", "D", "E", "F")


def _cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "inherit_sg.cli.main", *args], check=True, cwd=ROOT)


def run_house(seed: int, noise: str, work: Path, max_queries: int) -> Path:
    """Generate (kept when already in ``work``), map and bench one house; its JSON path."""
    dataset = work / f"house-{seed}-{noise}"
    if not (dataset / "scene.json").is_file():
        _cli("sim", "generate", "--seed", str(seed), "--floors", "2", "--noise", noise,
             "--width", str(WIDTH), "--height", str(HEIGHT), "--out", str(dataset), "--force")  # fmt: skip
    map_dir = work / f"map-{seed}-{noise}"
    if not (map_dir / "graph.kuzu").exists():
        _cli("map", "build", str(dataset), "--map", str(map_dir))
    out = RUNS / f"house-{seed}-{noise}.json"
    _cli("bench", "--dataset", str(dataset), "--map", str(map_dir), "--out", str(out),
         "--max-queries", str(max_queries), "--no-ablations", "--quiet")  # fmt: skip
    return out


def _row(path: Path) -> dict[str, Any]:
    doc = json.loads(path.read_text(encoding="utf-8"))
    ours = doc["accuracy"]["ours"]
    objects = doc["mapping"]["quality"]["objects"]
    rooms = doc["mapping"]["quality"].get("rooms") or {}
    return {
        "house": path.stem,
        "requests": ours["overall"]["n"],
        "within_1m": ours["overall"]["within_1m"],
        "groups": {g: ours[g]["within_1m"] for g in GROUPS if g in ours},
        "object_precision": objects["precision"],
        "object_recall": objects["recall"],
        "room_precision": rooms.get("precision"),
        "room_recall": rooms.get("recall"),
        "frames": doc["mapping"].get("frames"),
        "build_s": doc["mapping"].get("build_s"),
    }


def summarise(paths: list[Path]) -> dict[str, Any]:
    """Per-house rows and, per noise level, the request-weighted mean within 1 m."""
    rows = [_row(p) for p in sorted(paths)]
    means: dict[str, float] = {}
    for noise in sorted({r["house"].rsplit("-", 1)[1] for r in rows}):
        mine = [r for r in rows if r["house"].endswith(f"-{noise}")]
        n = sum(r["requests"] for r in mine)
        means[noise] = sum(r["within_1m"] * r["requests"] for r in mine) / n if n else 0.0
    return {"houses": rows, "mean_within_1m": means}


def main() -> None:
    """Run the houses (unless --report-only) and write the summary."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="", help="comma-separated house seeds")
    ap.add_argument(
        "--noise",
        default="clean,noisy",
        help="comma-separated noise levels (clean, noisy; default: both)",
    )
    ap.add_argument("--max-queries", type=int, default=400)
    ap.add_argument("--work", type=Path, help="keep (and reuse) datasets and maps here")
    ap.add_argument("--report-only", action="store_true")
    args = ap.parse_args()
    RUNS.mkdir(parents=True, exist_ok=True)
    if not args.report_only:
        seeds = [int(s) for s in args.seeds.split(",") if s.strip()]
        if not seeds:
            sys.exit("give --seeds (new ones: a seed whose misses you have read is not fresh)")
        noises = [n.strip() for n in args.noise.split(",") if n.strip()]
        with tempfile.TemporaryDirectory(prefix="isg-fresh-") as tmp:
            work = args.work or Path(tmp)
            work.mkdir(parents=True, exist_ok=True)
            for noise in noises:
                for seed in seeds:
                    print(f"== house {seed} {noise}", flush=True)
                    run_house(seed, noise, work, args.max_queries)
    summary = summarise(list(RUNS.glob("house-*.json")))
    SUMMARY.write_text(json.dumps(summary, indent=1) + "\n", encoding="utf-8")
    for row in summary["houses"]:
        groups = " ".join(f"{g} {v:.1f}" for g, v in row["groups"].items())
        print(f"{row['house']}: {row['within_1m']:.1f} % within 1 m ({groups})")
    for noise, mean in summary["mean_within_1m"].items():
        print(f"mean {noise}: {mean:.1f} %")
    print(f"written {SUMMARY}")


if __name__ == "__main__":
    main()
