"""What the synthetic world draws, over many generated houses (generation only, no
rendering): rooms per type, the share of open-plan ground floors, object categories
and how their frequencies follow Matterport3D's, and the time per house.

Run: ``python bench/synthetic_world.py [--seeds 700-719] [--floors 2] [--style real]
[--out bench/results/synthetic_world.json]``.
"""

from __future__ import annotations

import argparse
import json
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.ingest.synthetic.generate import generate_house
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS


def _seeds(text: str) -> list[int]:
    out: list[int] = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            out += list(range(int(a), int(b) + 1))
        elif part.strip():
            out.append(int(part))
    return out


def _spearman(a: list[float], b: list[float]) -> float:
    ra = np.argsort(np.argsort(a)).astype(float)
    rb = np.argsort(np.argsort(b)).astype(float)
    return float(np.corrcoef(ra, rb)[0, 1])


def measure(seeds: list[int], floors: int, style: str) -> dict[str, Any]:
    """Statistics of the houses ``seeds`` (``floors`` storeys, ``style`` generator)."""
    rooms: Counter[str] = Counter()
    houses_with: Counter[str] = Counter()
    labels: Counter[str] = Counter()
    open_plan = 0
    seconds = []
    objects = []
    for seed in seeds:
        start = time.perf_counter()
        house = generate_house(seed, floors, style=style)
        seconds.append(time.perf_counter() - start)
        scene = house.scene
        types = Counter(r.type for r in scene.rooms)
        rooms.update(types)
        houses_with.update(types.keys())
        ground = [r for r in scene.rooms if r.floor == 0]
        core = {"kitchen", "dining room", "living room"}
        open_plan += any(r.type in core and r.attributes.get("open_group") for r in ground)
        found = [o.label for o in scene.objects if not o.structural]
        labels.update(found)
        objects.append(len(found))
    ranked: list[tuple[float, float]] = []
    for label, n in labels.items():
        rank = OBJECT_KINDS[label].mp3d_rank
        if rank is not None:
            ranked.append((float(n), float(rank)))
    return {
        "houses": len(seeds),
        "floors": floors,
        "style": style,
        "open_plan_share": round(open_plan / len(seeds), 3),
        "rooms_per_type": dict(rooms.most_common()),
        "houses_with_type": dict(houses_with.most_common()),
        "object_categories": len(labels),
        "objects_per_house": round(float(np.mean(objects)), 1),
        "objects_per_category": dict(labels.most_common()),
        # how the categories' counts here follow their Matterport3D frequency ranks
        # (-1: the most frequent here are the most frequent there)
        "spearman_count_vs_mp3d_rank": round(
            _spearman([n for n, _ in ranked], [r for _, r in ranked]), 3
        ),
        "seconds_per_house": round(float(np.mean(seconds)), 3),
    }


def main() -> None:
    """Command line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="700-719")
    parser.add_argument("--floors", type=int, default=2)
    parser.add_argument("--style", default="real")
    parser.add_argument("--out", default="bench/results/synthetic_world.json")
    args = parser.parse_args()
    result = measure(_seeds(args.seeds), args.floors, args.style)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(result, indent=1), encoding="utf-8")
    summary = {k: v for k, v in result.items() if k != "objects_per_category"}
    print(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
