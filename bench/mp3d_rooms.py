"""Rooms of the real Matterport3D house: room precision and recall of a map against every
region of the ``.house`` file, region by region.

The script renders ``../shared/data/real/mp3d/example_mp3d_scene.house`` into
``WORK/dataset`` and maps it into ``WORK/map`` when they are missing (both kept for the
next run), then compares the map's room masks with the ten region polygons of the
ground truth (:func:`inherit_sg.benchmark.metrics.mapping.match_rooms`):

* overlap: the area (m²) of a region that a map room's mask covers, sampled on a 0.1 m
  grid; "of region" is that area over the part of the region that any map room covers
  (what the map saw of it), "of map room" over the map room's whole mask;
* match (mutual majority): a map room and a region match when more than half of the map
  room lies in the region and the map room covers more than half of what the map saw of
  the region; the matching is one-to-one. A map room spanning several regions (an
  open-plan floor left whole) matches none of them unless one holds most of it, and a
  region split between map rooms is matched only when one part holds most of it.
* precision = matched / map rooms; recall = matched / regions (every region counts;
  ``recall_seen`` leaves out regions no map room touches);
* label: the matched map room's label, and whether it is the region's type, exactly or
  among the map room's inferred types (top 2).

It prints one line per region (true type, MP3D code, the map rooms overlapping it with
their overlap, label and match) and per unmatched map room, then the totals, and
writes the JSON results.

Run::

    python bench/mp3d_rooms.py [--work /tmp/mp3d_rooms_eval] [--rebuild-map]
        [--out bench/results/mp3d_rooms.json] [--house FILE]
"""

from __future__ import annotations

import argparse
import json
import shutil
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.benchmark.metrics.mapping import RoomMatching, match_rooms
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.model import FloorNode, RoomNode

ROOT = Path(__file__).resolve().parents[1]
HOUSE = ROOT / ".." / "shared" / "data" / "real" / "mp3d" / "example_mp3d_scene.house"
OUT = ROOT / "bench" / "results" / "mp3d_rooms.json"
WIDTH, HEIGHT = 640, 480
MIN_LISTED_M2 = 0.2  # overlaps smaller than this are not listed per region


def ensure_dataset(work: Path, house: Path) -> Path:
    """``work/dataset``, rendered from ``house`` when missing (into a side folder moved
    into place when complete, so an interrupted render is redone)."""
    dataset = work / "dataset"
    if (dataset / "scene.json").is_file():
        print(f"dataset: {dataset} (cached)", flush=True)
        return dataset
    if not house.is_file():
        raise SystemExit(f"house file not found: {house}")
    from inherit_sg.ingest.mp3d_dataset import load_house_world, write_house_dataset

    partial = work / "dataset.partial"
    shutil.rmtree(partial, ignore_errors=True)
    work.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    print(f"dataset: rendering {house.name} into {dataset}", flush=True)
    summary = write_house_dataset(
        load_house_world(house), partial, seed=0, width=WIDTH, height=HEIGHT
    )
    partial.rename(dataset)
    print(
        f"dataset: {summary.frames} frames, {summary.objects} objects "
        f"({time.perf_counter() - t0:.0f} s)",
        flush=True,
    )
    return dataset


def ensure_map(work: Path, dataset: Path, rebuild: bool) -> Path:
    """``work/map``, built from ``dataset`` when missing (or ``rebuild``)."""
    map_dir = work / "map"
    if rebuild:
        shutil.rmtree(map_dir, ignore_errors=True)
    if (map_dir / "map.json").is_file():
        print(f"map: {map_dir} (cached)", flush=True)
        return map_dir
    from inherit_sg.facade import build_map

    partial = work / "map.partial"
    shutil.rmtree(partial, ignore_errors=True)
    t0 = time.perf_counter()
    print(f"map: mapping {dataset} into {map_dir}", flush=True)
    summary = build_map(dataset, partial)
    partial.rename(map_dir)
    print(
        f"map: {summary.get('objects')} objects, {summary.get('rooms')} rooms "
        f"({time.perf_counter() - t0:.0f} s)",
        flush=True,
    )
    return map_dir


def _labels(room: RoomNode) -> list[str]:
    """The map room's label first, then its inferred types (best first)."""
    out = [room.label.strip().lower()]
    for name, _probability in room.types:
        if name.strip().lower() not in out:
            out.append(name.strip().lower())
    return out


def report(scene: Scene, rooms: Sequence[RoomNode], matching: RoomMatching) -> dict[str, Any]:
    """Per-region and per-map-room rows and the totals."""
    ov = matching.overlaps
    assert ov is not None
    by_id = {r.id: r for r in rooms}
    matched_by_true = {t: p for p, t in matching.pairs.items()}
    regions = []
    for j, true in enumerate(scene.rooms):
        overlapping = []
        for i, pred_id in enumerate(ov.pred_ids):
            area = float(ov.overlap[i, j])
            if area < MIN_LISTED_M2:
                continue
            overlapping.append(
                {
                    "map_room": pred_id,
                    "label": by_id[pred_id].label,
                    "overlap_m2": round(area, 2),
                    "of_region": round(area / ov.mapped[j], 3) if ov.mapped[j] else 0.0,
                    "of_map_room": round(area / ov.pred_area[i], 3) if ov.pred_area[i] else 0.0,
                }
            )
        overlapping.sort(key=lambda row: -float(row["overlap_m2"]))
        match = matched_by_true.get(true.id)
        labels = _labels(by_id[match]) if match else []
        regions.append(
            {
                "region": true.id,
                "type": true.type,
                "mp3d_code": true.attributes.get("mp3d_code"),
                "area_m2": round(float(ov.true_area[j]), 2),
                "mapped_m2": round(float(ov.mapped[j]), 2),
                "matched": match,
                "label": labels[0] if labels else None,
                "label_exact": bool(labels) and labels[0] == true.type,
                "label_top2": true.type in labels[:2],
                "map_rooms": overlapping,
            }
        )
    unmatched = []
    for i, pred_id in enumerate(ov.pred_ids):
        if pred_id in matching.pairs:
            continue
        order = np.argsort(-ov.overlap[i], kind="stable")
        spans = [
            {"region": ov.true_ids[j], "overlap_m2": round(float(ov.overlap[i, j]), 2)}
            for j in order.tolist()
            if ov.overlap[i, j] >= MIN_LISTED_M2
        ]
        unmatched.append(
            {
                "map_room": pred_id,
                "label": by_id[pred_id].label,
                "area_m2": round(float(ov.pred_area[i]), 2),
                "regions": spans,
            }
        )
    n = len(regions)
    return {
        "rule": (
            "mutual majority: a map room and a region match when more than half of the "
            "map room's mask lies in the region and the map room covers more than half "
            "of the region's mapped area; one-to-one; precision = matched / map rooms, "
            "recall = matched / all regions"
        ),
        "totals": {
            "regions": n,
            "map_rooms": matching.predicted,
            "matched": matching.matched,
            "precision": round(matching.precision, 3),
            "recall": round(matching.recall, 3),
            "recall_seen": round(matching.recall_seen, 3),
            "unseen": matching.unseen,
            "label_exact": sum(r["label_exact"] for r in regions),
            "label_top2": sum(r["label_top2"] for r in regions),
        },
        "regions": regions,
        "unmatched_map_rooms": unmatched,
    }


def print_report(rep: dict[str, Any]) -> None:
    """One block per region, the unmatched map rooms, then the totals."""
    print(f"\n{'region':7s} {'type':13s} code {'seen m2':>8s}  map rooms", end=" ")
    print("(overlap, share of region / of map room)")
    for r in rep["regions"]:
        rooms = (
            "; ".join(
                f"{m['map_room']} {m['label']!r} {m['overlap_m2']:.1f} m2 "
                f"({100 * m['of_region']:.0f}%/{100 * m['of_map_room']:.0f}%)"
                for m in r["map_rooms"]
            )
            or "-"
        )
        verdict = (
            f"matched {r['matched']} label {r['label']!r}"
            + (" ok" if r["label_exact"] else " (top2)" if r["label_top2"] else " wrong")
            if r["matched"]
            else "not matched"
        )
        print(
            f"{r['region']:7s} {r['type']:13s} {r['mp3d_code'] or '?':4s} "
            f"{r['mapped_m2']:5.1f}/{r['area_m2']:<5.1f} {rooms}\n{'':33s}-> {verdict}"
        )
    if rep["unmatched_map_rooms"]:
        print("\nmap rooms matching no region:")
        for m in rep["unmatched_map_rooms"]:
            spans = ", ".join(f"{s['region']} {s['overlap_m2']:.1f} m2" for s in m["regions"])
            print(f"  {m['map_room']} {m['label']!r} {m['area_m2']:.1f} m2 over {spans or '-'}")
    t = rep["totals"]
    print(
        f"\nrooms: {t['matched']} matched of {t['map_rooms']} map rooms and {t['regions']} "
        f"regions: precision {t['precision']:.2f}, recall {t['recall']:.2f} "
        f"(seen regions {t['recall_seen']:.2f}); labels exact {t['label_exact']}/{t['regions']}, "
        f"in top 2 {t['label_top2']}/{t['regions']}"
    )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Prepare the data and evaluate the map's rooms."""
    from inherit_sg.store import MapStore

    dataset = ensure_dataset(args.work, args.house)
    map_dir = ensure_map(args.work, dataset, args.rebuild_map)
    scene = Scene.load(dataset)
    with MapStore.open(map_dir) as store:
        graph = store.load_graph()
    levels = {n.id: n.level for n in graph.nodes() if isinstance(n, FloorNode)}
    rooms = [n for n in graph.nodes() if isinstance(n, RoomNode)]
    rep = report(scene, rooms, match_rooms(rooms, scene, levels))
    return {"house": str(args.house), "dataset": str(dataset), "map": str(map_dir), **rep}


def main(argv: Sequence[str] | None = None) -> None:
    """Evaluate, print and write the results."""
    ap = argparse.ArgumentParser(
        description=(__doc__ or "").split("\n\n")[0],
        epilog="Rendering and mapping are cached under --work and reused.",
    )
    ap.add_argument(
        "--work",
        type=Path,
        default=Path("/tmp/mp3d_rooms_eval"),
        help="folder for the rendered dataset and the map (default: %(default)s)",
    )
    ap.add_argument("--out", type=Path, default=OUT, help="JSON results (default: %(default)s)")
    ap.add_argument("--house", type=Path, default=HOUSE, help="Matterport3D .house file")
    ap.add_argument("--rebuild-map", action="store_true", help="map the dataset again")
    args = ap.parse_args(argv)
    rep = run(args)
    print_report(rep)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(rep, indent=1) + "\n", encoding="utf-8")
    print(f"\nwritten {args.out}")


if __name__ == "__main__":
    main()
