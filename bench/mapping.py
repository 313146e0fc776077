"""Mapping benchmark: build a map of a generated two-floor house (clean and noisy
perception) and report speed, memory and quality against the ground truth.

    python bench/mapping.py [--seed 7] [--width 320 --height 240] [--out bench/results/mapping.json]

Numbers: frames/s of the geometric stream, keyframes/s of the semantic stream, whole
build time, peak RSS, object precision/recall (0.5 m, compatible label), duplicate rate,
room and floor assignment accuracy, relation precision.
"""

from __future__ import annotations

import argparse
import json
import resource
import shutil
import tempfile
import time
from pathlib import Path

from inherit_sg.benchmark.metrics.mapping import evaluate_objects, room_correspondence
from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.ingest.synthetic.ground_truth_files import seen_objects
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.model import EdgeKind, FloorNode, RoomNode
from inherit_sg.store import MapStore


def run(seed: int, noise: str, width: int, height: int, work: Path) -> dict[str, object]:
    """Generate, build and evaluate one house."""
    data, map_dir = work / f"house-{noise}", work / f"map-{noise}"
    write_dataset(generate_house(seed, 2), data, noise=noise, width=width, height=height)
    t0 = time.perf_counter()
    summary = build_map(data, map_dir)
    seconds = time.perf_counter() - t0
    scene = Scene.load(data)
    with MapStore.open(map_dir) as store:
        graph = store.load_graph()
        size = store.stats().to_dict()
    levels = {n.id: n.level for n in graph.nodes() if isinstance(n, FloorNode)}
    rooms = [n for n in graph.nodes() if isinstance(n, RoomNode)]
    quality = evaluate_objects(
        list(graph.objects()),
        scene,
        visible=seen_objects(data),
        room_map=room_correspondence(rooms, scene, levels),
        floor_level=lambda o: levels.get(o.floor_id or ""),
        relations=graph.edges(EdgeKind.RELATION),
    )
    return {
        "noise": noise,
        "frames": summary["frames"],
        "keyframes": summary["keyframes"],
        "build_s": round(seconds, 1),
        "geometry_fps": summary["geometry_fps"],
        "semantic_keyframes_per_s": summary["semantic_keyframes_per_s"],
        "stage_seconds": summary["timings_s"],
        "quality": quality.to_dict(),
        "map_bytes": size["bytes_total"],
    }


def main() -> None:
    """Run clean and noisy builds and write the results."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--out", type=Path, default=Path("bench/results/mapping.json"))
    args = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="isg-bench-mapping-"))
    try:
        results = [
            run(args.seed, noise, args.width, args.height, work) for noise in ("clean", "noisy")
        ]
    finally:
        shutil.rmtree(work, ignore_errors=True)
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    report = {
        "seed": args.seed,
        "size": f"{args.width}x{args.height}",
        "peak_rss_mb": round(peak_mb),
        "runs": results,
    }
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=1))
    print(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
