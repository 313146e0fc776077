"""List the requests a built map answers wrongly, with a reason class for each.

For every request whose answer is not within 1 m of a target, the script prints the
expected target(s), our answer and the first cause that explains the miss:

- ``parser``: the parsed request names no kind of thing the target is;
- ``missing``: no map object lies within 1 m of any target;
- ``wrong label``: map objects lie at a target, none with the target's label;
- ``wrong room``: the target's map object sits in a room of another type;
- ``wrong attribute``: an asked colour / material / size differs on the target's map
  object (``unknown`` when the map has no value);
- ``scoring``: the target is in the map as asked, but ranked below the answer.

Run: ``python bench/retrieval_failures.py --built MAP_DIR:DATASET_DIR [--built ...]
[--category E] [--verify] [--json out.json]`` (use training seeds only).
"""

from __future__ import annotations

import argparse
import json
import math
from collections import Counter
from pathlib import Path
from typing import Any

from inherit_sg.ingest.synthetic.queries import QueryGT, generate_queries
from inherit_sg.ingest.synthetic.scene import ObjectGT, Scene
from inherit_sg.model import ObjectNode
from inherit_sg.retrieval.constraints import FunctionConstraint, LabelConstraint
from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.retrieval.snapshot import MapSnapshot, canonical_labels
from inherit_sg.store import MapStore
from inherit_sg.vocab.rooms import room_type

NEAR_M = 1.0


def _box_distance(obj: ObjectGT, p: tuple[float, float, float]) -> float:
    d = [max(lo - v, 0.0, v - hi) for lo, hi, v in zip(obj.bbox_min, obj.bbox_max, p, strict=True)]
    return math.hypot(*d)


def _canon(label: str) -> set[str]:
    return set(canonical_labels(label)) or {label.lower()}


def _map_twin(snap: MapSnapshot, gt: ObjectGT) -> tuple[ObjectNode | None, list[ObjectNode]]:
    """The map object standing for ``gt`` (same kind, nearest) and all objects near it."""
    near = [o for o in snap.objects.values() if _box_distance(gt, o.position) <= NEAR_M]
    same = [o for o in near if _canon(o.label) & _canon(gt.label)]
    twin = min(same, key=lambda o: _box_distance(gt, o.position)) if same else None
    return twin, near


def _wanted_labels(engine: QueryEngine, text: str) -> set[str] | None:
    """Canonical labels the parsed request asks for (None: it names no kind)."""
    plan = engine.plan(engine.parse(text))
    out: set[str] = set()
    for con in plan.target.constraints:
        if isinstance(con, LabelConstraint | FunctionConstraint) and not con.negated:
            out |= set(con.labels)
    return out or None


def classify(engine: QueryEngine, snap: MapSnapshot, scene: Scene, q: QueryGT) -> str:
    """The reason class of a missed request (see the module docstring)."""
    parsed = engine.parse(q.text)
    if not parsed.has_target:
        return f"parser (no target: {parsed.no_target_reason})"
    gts = [o for o in scene.objects if o.id in q.target_ids]
    wanted = _wanted_labels(engine, q.text)
    if wanted is not None and gts and not any(_canon(g.label) & wanted for g in gts):
        return f"parser (asked {sorted(wanted)}, target is {gts[0].label})"
    twins = [(g, *_map_twin(snap, g)) for g in gts]
    if gts and not any(near for _, _, near in twins):
        return "missing"
    found = [(g, t) for g, t, _ in twins if t is not None]
    if gts and not found:
        labels = sorted({o.label for _, _, near in twins for o in near})
        return f"wrong label (map has {labels} there)"
    room = q.gt_constraints.get("room") or {}
    if found and room.get("type"):
        rooms = [snap.rooms.get(snap.room_of.get(t.id) or "") for _, t in found]
        types = [room_type(r.label.lower()) if r is not None else None for r in rooms]
        if room["type"] not in types:
            return f"wrong room (map: {types}, asked {room['type']})"
    attrs = q.gt_constraints.get("attributes") or []
    for attr in attrs:
        key, value = attr["key"], attr["value"]
        haves = {str(t.attributes.get(key, "unknown")) for _, t in found}
        if key != "size" and value not in haves:
            return f"wrong attribute ({key}: map {sorted(haves)}, asked {value})"
    return "scoring"


def failures(map_dir: str, dataset: str, args: argparse.Namespace) -> list[dict[str, Any]]:
    """Missed requests of one built map with their reason class."""
    scene = Scene.load(dataset)
    queries = generate_queries(scene, scene.seed or 0)
    out = []
    with MapStore.open(map_dir) as store:
        engine = QueryEngine(store)
        snap = engine.snapshot()[0]
        for q in queries:
            if args.category and q.category not in args.category:
                continue
            r = engine.query(q.text, verify=args.verify)
            pos = (r.answer or {}).get("position")
            dist = math.inf
            if pos is not None:
                dist = min((math.dist(pos, t) for t in q.target_positions), default=math.inf)
            if dist <= NEAR_M:
                continue
            answer = snap.node(r.answer_id) if r.answer_id else None
            out.append(
                {
                    "map": map_dir,
                    "id": q.id,
                    "category": q.category,
                    "subcategory": q.subcategory,
                    "text": q.text,
                    "targets": [
                        f"{o.id} {o.label} {o.attributes}"
                        for o in scene.objects
                        if o.id in q.target_ids
                    ],
                    "answer": f"{r.answer_id} {getattr(answer, 'label', '')} "
                    f"{getattr(answer, 'attributes', '')}",
                    "distance": None if math.isinf(dist) else round(dist, 2),
                    "reason": classify(engine, snap, scene, q),
                }
            )
    return out


def main() -> None:
    """Print the missed requests and a count per reason class."""
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--built", action="append", required=True, help="MAP_DIR:DATASET_DIR")
    ap.add_argument("--category", default="", help="only these categories, e.g. 'E' or 'DE'")
    ap.add_argument("--verify", action="store_true")
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()
    rows: list[dict[str, Any]] = []
    for spec in args.built:
        map_dir, dataset = spec.split(":", 1)
        rows += failures(map_dir, dataset, args)
    for row in rows:
        print(f"[{row['category']} {row['subcategory']}] {row['text']}")
        print(f"    expected {row['targets']}")
        print(f"    answered {row['answer']} (d={row['distance']})  -> {row['reason']}")
    counts = Counter((r["category"], r["reason"].split(" (")[0]) for r in rows)
    print("\nmissed requests by category and reason:")
    for (cat, reason), n in sorted(counts.items()):
        print(f"  {cat} {reason:16s} {n}")
    if args.json is not None:
        args.json.write_text(json.dumps(rows, indent=2))


if __name__ == "__main__":
    main()
