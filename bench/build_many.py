"""Speed-up of ``map build-many`` (Ray, one task per map) over a sequential loop.

    python bench/build_many.py [--houses 4] [--width 160 --height 120] \
        [--out bench/results/build_many.json]

Generates N one-floor houses (4 rooms, walk without close looks), then builds them
(1) one after another with ``build_map`` in this process (the models load once: the
fastest sequential loop), (2) one after another as ``inherit-sg map build`` processes
(what a shell loop does), and (3) with ``inherit-sg map build-many`` on a local Ray
cluster sized to this machine (Ray's start-up and each worker's model loading
included). Wall times, speed-ups and the machine's load average go to the JSON file;
the maps of (1) and (3) are compared with :func:`inherit_sg.scale.compare.same_objects`.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.scale.cluster import local_cpus
from inherit_sg.scale.compare import map_signature, same_objects

CLI = [sys.executable, "-m", "inherit_sg.cli.main"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--houses", type=int, default=4)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--out", type=Path, default=Path("bench/results/build_many.json"))
    args = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="build_many_"))
    try:
        seeds = list(range(3, 3 + args.houses))
        lines, frames = [], {}
        for seed in seeds:
            ds = work / f"walk{seed}"
            summary = write_dataset(
                generate_house(seed, 1, 4),
                ds,
                width=args.width,
                height=args.height,
                workers=1,
                close_looks=False,
            )
            frames[f"house{seed}"] = summary.frames
            lines.append(json.dumps({"dataset": str(ds), "map": f"house{seed}"}))
        manifest = work / "manifest.jsonl"
        manifest.write_text("\n".join(lines) + "\n", encoding="utf-8")

        t = time.perf_counter()
        for seed in seeds:
            build_map(work / f"walk{seed}", work / "loop" / f"house{seed}")
        loop_s = time.perf_counter() - t

        t = time.perf_counter()
        for seed in seeds:
            subprocess.run(
                [
                    *CLI,
                    "map",
                    "build",
                    str(work / f"walk{seed}"),
                    "--map",
                    str(work / "cli" / f"house{seed}"),
                    "--json",
                ],
                check=True,
                capture_output=True,
            )
        cli_s = time.perf_counter() - t

        load_before = os.getloadavg()
        t = time.perf_counter()
        res = subprocess.run(
            [*CLI, "map", "build-many", str(manifest), "--out", str(work / "ray"), "--json"],
            check=True,
            capture_output=True,
            text=True,
        )
        ray_s = time.perf_counter() - t
        report = json.loads(res.stdout[res.stdout.index("{") :])
        same = {
            name: same_objects(
                map_signature(work / "ray" / name), map_signature(work / "loop" / name)
            )
            for name in frames
        }
        doc = {
            "houses": len(seeds),
            "frames": frames,
            "size": [args.width, args.height],
            "cpus": local_cpus(),
            "load_average_before_build_many": [round(x, 2) for x in load_before],
            "sequential_in_process_s": round(loop_s, 1),
            "sequential_cli_processes_s": round(cli_s, 1),
            "build_many_s": round(ray_s, 1),
            "build_many_task_s": {m["map"]: m["seconds"] for m in report["maps"]},
            "speedup_vs_in_process_loop": round(loop_s / ray_s, 2),
            "speedup_vs_cli_loop": round(cli_s / ray_s, 2),
            "same_objects_as_loop": same,
        }
    finally:
        shutil.rmtree(work, ignore_errors=True)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    print(json.dumps(doc, indent=1))


if __name__ == "__main__":
    main()
