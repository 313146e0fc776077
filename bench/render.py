"""Synthetic world speed: house generation, walk planning, rendering and dataset writing.

Renders poses of a generated two-floor house's walk at 640×480 and 320×240 in this
process (frames/s from the median and the best frame time), then writes a short
dataset with the default worker count. Prints one line per number and writes them to
``bench/results/render.json`` (or ``--json PATH``).

    python bench/render.py [--seed 7] [--frames 40] [--json PATH]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import tempfile
import time
from pathlib import Path

from inherit_sg.ingest.synthetic.generate import (
    House,
    generate_house,
    make_intrinsics,
    write_dataset,
)
from inherit_sg.ingest.synthetic.render import Renderer
from inherit_sg.model import Pose

RESULTS = Path(__file__).resolve().parent / "results" / "render.json"


def _render_rate(
    house: House, poses: list[Pose], width: int, height: int, shadows: bool
) -> dict[str, float]:
    renderer = Renderer(house.world, house.plan, make_intrinsics(width, height), shadows=shadows)
    renderer.render(poses[0])
    times = []
    for pose in poses:
        t0 = time.perf_counter()
        renderer.render(pose)
        times.append(time.perf_counter() - t0)
    return {
        "fps_median": round(1.0 / statistics.median(times), 2),
        "fps_best": round(1.0 / min(times), 2),
    }


def main() -> None:
    """Run the benchmark and print/write the numbers."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--frames", type=int, default=40, help="poses rendered per size")
    parser.add_argument("--json", type=Path, default=RESULTS)
    args = parser.parse_args()

    t0 = time.perf_counter()
    house = generate_house(args.seed, 2)
    gen_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    traj = house.trajectory()
    walk_s = time.perf_counter() - t0
    step = max(1, len(traj) // args.frames)
    poses = traj.poses[::step][: args.frames]
    results: dict[str, object] = {
        "house": {
            "seed": args.seed,
            "floors": 2,
            "rooms": len(house.scene.rooms),
            "objects": len(house.scene.objects),
            "triangles": len(house.world.faces),
            "walk_frames": len(traj),
        },
        "generate_house_s": round(gen_s, 3),
        "plan_walk_s": round(walk_s, 3),
        "cpu_count": os.cpu_count(),
    }
    for width, height in ((640, 480), (320, 240)):
        for shadows in (False, True):
            key = f"render_{width}x{height}" + ("_shadows" if shadows else "")
            results[key] = _render_rate(house, poses, width, height, shadows)
    with tempfile.TemporaryDirectory() as tmp:
        summary = write_dataset(house, tmp, width=640, height=480, max_frames=args.frames)
    results["write_dataset_640x480_fps"] = round(summary.frames / summary.seconds, 2)

    for key, value in results.items():
        print(f"{key}: {value}")
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(json.dumps(results, indent=2) + "\n")
    print(f"written to {args.json}")


if __name__ == "__main__":
    main()
