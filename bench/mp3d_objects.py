"""Objects of the real Matterport3D house: which categories reach the map.

For every object category of the rendered house (the label of ``scene.json``, with the
object's raw Matterport3D category and mpcat40 class), count the objects seen in the walk
(``visibility.json``: in at least ``--min-frames`` frames), those the map found (a map
object with a compatible label within 0.5 m, one-to-one, as in the mapping benchmark) and
those it *holds* (a map object with a compatible label whose centre lies within 1 m of
the object's box: a sofa seen from one end is there even when its centre is off). A
category is *missing* when some of its objects were in view and the map holds none.

The dataset and map are the ones ``bench/mp3d_rooms.py`` / ``bench/mp3d_requests.py``
keep under their work folder (built there when missing).

Run::

    python bench/mp3d_objects.py [--work /tmp/mp3d_rooms_eval] [--min-frames 2]
        [--out bench/results/mp3d_objects.json]
"""

from __future__ import annotations

import argparse
import json
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.metrics.mapping import labels_compatible, match_objects
from inherit_sg.benchmark.metrics.retrieval import _box_distance
from inherit_sg.ingest.synthetic.ground_truth_files import seen_objects
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.model import ObjectNode
from inherit_sg.store import MapStore

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "results" / "mp3d_objects.json"


HELD_M = 1.0


def _held(obj: Any, objects: Sequence[ObjectNode]) -> bool:
    """Whether a map object of a compatible label has its centre within 1 m of ``obj``'s box."""
    return any(
        labels_compatible(node.label, obj.label) and _box_distance(obj, node.position) <= HELD_M
        for node in objects
    )


def category_report(
    scene: Scene, labels_by_true: dict[str, str], seen: set[str], objects: Sequence[ObjectNode]
) -> dict[str, Any]:
    """Per category: objects in the house, seen, found, held; the missing categories."""
    total: Counter[str] = Counter()
    in_view: Counter[str] = Counter()
    found: Counter[str] = Counter()
    held: Counter[str] = Counter()
    raw: dict[str, set[str]] = {}
    for obj in scene.objects:
        if obj.structural:
            continue
        total[obj.label] += 1
        raw.setdefault(obj.label, set()).add(str(obj.attributes.get("mp3d_category", obj.label)))
        if obj.id in seen:
            in_view[obj.label] += 1
            if obj.id in labels_by_true:
                found[obj.label] += 1
            if obj.id in labels_by_true or _held(obj, objects):
                held[obj.label] += 1
    rows = [
        {
            "category": label,
            "raw": sorted(raw[label]),
            "objects": total[label],
            "seen": in_view[label],
            "found": found[label],
            "held": held[label],
        }
        for label in sorted(total, key=lambda k: (-in_view[k], k))
    ]
    missing = [r["category"] for r in rows if r["seen"] and not r["held"]]
    seen_cats = sum(1 for r in rows if r["seen"])
    return {
        "categories": len(rows),
        "categories_seen": seen_cats,
        "categories_found": seen_cats - len(missing),
        "objects_seen": sum(in_view.values()),
        "objects_found": sum(found.values()),
        "objects_held": sum(held.values()),
        "missing": missing,
        "rows": rows,
    }


def run(work: Path, min_frames: int) -> dict[str, Any]:
    """The report for the dataset and map under ``work``."""
    dataset, map_dir = work / "dataset", work / "map"
    if not (dataset / "scene.json").is_file() or not map_dir.is_dir():
        raise SystemExit(
            f"no dataset/map under {work}: run bench/mp3d_rooms.py --work {work} first"
        )
    scene = Scene.load(dataset)
    seen = seen_objects(dataset, min_frames=min_frames)
    with MapStore.open(map_dir) as store:
        objects = list(store.load_graph().objects())
    truth = [o for o in scene.objects if not o.structural and o.id in seen]
    pairs = match_objects(objects, truth)
    labels = {true: pred for pred, true in pairs.items()}
    report = category_report(scene, labels, seen, objects)
    report.update(dataset=str(dataset), map=str(map_dir), min_frames=min_frames)
    return report


def main(argv: Sequence[str] | None = None) -> None:
    """Print the per-category table and write the JSON."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", type=Path, default=Path("/tmp/mp3d_rooms_eval"))
    ap.add_argument("--min-frames", type=int, default=2, help="frames an object must be in")
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args(argv)
    report = run(args.work, args.min_frames)
    print(f"{'category':22} {'objects':>7} {'seen':>5} {'found':>5} {'held':>5}  raw")
    for row in report["rows"]:
        flag = "  MISSING" if row["seen"] and not row["held"] else ""
        raw = ", ".join(row["raw"])[:40]
        print(
            f"{row['category']:22} {row['objects']:7d} {row['seen']:5d} {row['found']:5d} "
            f"{row['held']:5d}  "
            f"{raw}{flag}"
        )
    print(
        f"\ncategories seen {report['categories_seen']}, found {report['categories_found']}; "
        f"objects seen {report['objects_seen']}, found {report['objects_found']} (0.5 m), "
        f"held {report['objects_held']} (1 m); "
        f"missing: {', '.join(report['missing']) or 'none'}"
    )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    print(f"written {args.out}")


if __name__ == "__main__":
    main()
