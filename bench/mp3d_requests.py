"""Human-written requests for the real Matterport3D house: retrieval accuracy per form.

The requests (``bench/data/mp3d_requests.jsonl``: 150 lines ``{"id", "text", "form",
"target_ids", "target_positions", "notes"}``) were written by hand for the house of
``../shared/data/real/mp3d/example_mp3d_scene.house`` and checked against the ground
truth of its rendered walk: they use the words people use ("armchair", "nightstand",
"powder room", "foyer") rather than the dataset's labels. ``form`` is one of named,
room, relation, attribute, negation, superlative, ordinal_viewpoint, function, synonym,
description; any listed target is a correct answer.

The script renders the house into ``WORK/dataset`` and maps it into ``WORK/map`` when
they are missing (both kept for the next run), checks the request file against the
dataset's ``scene.json``, answers every request with ``MapService.query`` (verification
on unless ``--no-verify``) and judges the answer's position by its distance to the
nearest target's box: within 1 m and within 0.5 m; *semantic* when the ground-truth
object nearest to the answer is a target. It prints accuracy per form and overall, the
misses (id, text, answer label and room, distance, parsed target), and writes the JSON
results.

Run::

    python bench/mp3d_requests.py [--work /tmp/mp3d_bench] [--no-verify]
        [--out bench/results/mp3d_requests.json] [--requests FILE] [--rebuild-map]
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.metrics.retrieval import GroundTruth, _box_distance, percentile
from inherit_sg.ingest.synthetic.scene import ObjectGT, Scene

ROOT = Path(__file__).resolve().parents[1]
HOUSE = ROOT / ".." / "shared" / "data" / "real" / "mp3d" / "example_mp3d_scene.house"
REQUESTS = ROOT / "bench" / "data" / "mp3d_requests.jsonl"
OUT = ROOT / "bench" / "results" / "mp3d_requests.json"
WIDTH, HEIGHT = 640, 480
FORMS = (
    "named",
    "room",
    "relation",
    "attribute",
    "negation",
    "superlative",
    "ordinal_viewpoint",
    "function",
    "synonym",
    "description",
)
NEAR_M, CLOSE_M = 1.0, 0.5


@dataclass(frozen=True)
class Request:
    """One hand-written request with its ground truth."""

    id: str
    text: str
    form: str
    target_ids: tuple[str, ...]
    target_positions: tuple[tuple[float, float, float], ...]
    notes: str = ""


def load_requests(path: Path) -> list[Request]:
    """The requests of a JSONL file (blank lines skipped)."""
    out = []
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip():
            continue
        d = json.loads(line)
        try:
            out.append(
                Request(
                    id=str(d["id"]),
                    text=str(d["text"]),
                    form=str(d["form"]),
                    target_ids=tuple(str(t) for t in d["target_ids"]),
                    target_positions=tuple(
                        (float(p[0]), float(p[1]), float(p[2])) for p in d["target_positions"]
                    ),
                    notes=str(d.get("notes", "")),
                )
            )
        except (KeyError, TypeError, IndexError, ValueError) as exc:
            raise SystemExit(f"{path}:{n}: bad request line ({exc!r})") from None
    return out


def check_requests(requests: Sequence[Request], scene: Scene) -> list[str]:
    """Problems of the request file against the ground truth (empty when sound): unique
    ids and texts, known forms, targets that exist, positions that are their centroids."""
    objects = {o.id: o for o in scene.objects}
    problems: list[str] = []
    seen_ids: set[str] = set()
    seen_texts: set[str] = set()
    for r in requests:
        if r.id in seen_ids:
            problems.append(f"{r.id}: duplicate id")
        if r.text.lower() in seen_texts:
            problems.append(f"{r.id}: duplicate text {r.text!r}")
        seen_ids.add(r.id)
        seen_texts.add(r.text.lower())
        if r.form not in FORMS:
            problems.append(f"{r.id}: unknown form {r.form!r}")
        if not r.target_ids or len(r.target_ids) != len(r.target_positions):
            problems.append(f"{r.id}: target_ids and target_positions differ in length")
        for tid, pos in zip(r.target_ids, r.target_positions, strict=False):
            obj = objects.get(tid)
            if obj is None:
                problems.append(f"{r.id}: target {tid} is not in scene.json")
            elif math.dist(obj.centroid, pos) > 1e-3:
                problems.append(f"{r.id}: position of {tid} is not its centroid")
    return problems


# ------------------------------------------------------------------ dataset and map
def ensure_dataset(work: Path, house: Path) -> Path:
    """``work/dataset``, rendered from ``house`` when missing (written to a side folder
    and moved into place when complete, so an interrupted render is redone)."""
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
    step = {"last": -1}

    def progress(done: int, total: int) -> None:
        pct = 100 * done // max(total, 1)
        if pct // 10 != step["last"] // 10 or done == total:
            step["last"] = pct
            print(f"  render {done}/{total} frames ({time.perf_counter() - t0:.0f} s)", flush=True)

    summary = write_house_dataset(
        load_house_world(house), partial, seed=0, width=WIDTH, height=HEIGHT, progress=progress
    )
    partial.rename(dataset)
    print(f"dataset: {summary.frames} frames, {summary.objects} objects", flush=True)
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
    frames = {"total": 0, "last": -1}

    def total(n: int) -> None:
        frames["total"] = n
        print(f"map: mapping {n} frames into {map_dir}", flush=True)

    def progress(p: Any) -> None:
        done = int(getattr(p, "frames", 0))
        pct = 100 * done // max(frames["total"], 1)
        if pct // 10 != frames["last"] // 10:
            frames["last"] = pct
            print(
                f"  map {done}/{frames['total']} frames, {getattr(p, 'objects', '?')} objects "
                f"({time.perf_counter() - t0:.0f} s)",
                flush=True,
            )

    summary = build_map(dataset, partial, progress=progress, total=total)
    partial.rename(map_dir)
    print(
        f"map: {summary.get('objects')} objects, {summary.get('rooms')} rooms "
        f"({time.perf_counter() - t0:.0f} s)",
        flush=True,
    )
    return map_dir


# ------------------------------------------------------------------ judging
def _parsed(constraints: dict[str, Any]) -> dict[str, Any]:
    """What the parser made of the request: target labels, function, rooms, other kinds."""
    target = constraints.get("target") or {}
    cons = constraints.get("constraints") or []
    rooms = [
        ("not " if c.get("negated") else "") + str(c.get("type") or f"?{c.get('name', '')}")
        for c in cons
        if c.get("kind") == "room"
    ]
    labels = list(target.get("labels") or [])
    for c in cons:
        if c.get("kind") in ("label", "function") and not c.get("negated"):
            labels += [str(x) for x in c.get("labels") or [] if x not in labels]
    return {
        "labels": labels,
        "noun": target.get("noun") or "",
        "function": target.get("function") or "",
        "rooms": rooms,
        "kinds": [("not " if c.get("negated") else "") + str(c.get("kind")) for c in cons],
        "no_target_reason": constraints.get("no_target_reason"),
    }


def _parsed_text(p: dict[str, Any]) -> str:
    text = "/".join(p["labels"]) or (f"({p['noun']})" if p["noun"] else "-")
    if p["function"]:
        text += f" fn={p['function']}"
    if p["rooms"]:
        text += " in " + ",".join(p["rooms"])
    if p["no_target_reason"]:
        text += f" [no target: {p['no_target_reason']}]"
    return text


def judge(
    request: Request,
    result: dict[str, Any],
    objects: dict[str, ObjectGT],
    truth: GroundTruth,
) -> dict[str, Any]:
    """One result row: the answer, its distance to the nearest target box, the verdicts
    and the parsed request."""
    answer = result.get("answer") or {}
    pos = answer.get("position")
    targets = [objects[t] for t in request.target_ids]
    dist = min((_box_distance(o, pos) for o in targets), default=math.inf) if pos else math.inf
    nearest = truth.nearest(pos) if pos else None
    parsed = _parsed(result.get("constraints") or {})
    return {
        "id": request.id,
        "form": request.form,
        "text": request.text,
        "target_ids": list(request.target_ids),
        "target_labels": sorted({o.label for o in targets}),
        "answer_id": answer.get("id"),
        "answer_label": answer.get("label"),
        "answer_room": answer.get("room"),
        "answer_position": pos,
        "nearest_gt": None if nearest is None else f"{nearest} {objects[nearest].label}",
        "distance": None if math.isinf(dist) else round(dist, 3),
        "within_1m": dist <= NEAR_M,
        "within_0.5m": dist <= CLOSE_M,
        "semantic": nearest in request.target_ids,
        "parsed": parsed,
        "parsed_target_labels": parsed["labels"],
        "timings_ms": result.get("timings_ms") or {},
    }


def summarise(rows: Sequence[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """Accuracy (%) within 1 m, within 0.5 m and semantic, per form present and overall."""
    out: dict[str, dict[str, Any]] = {}
    forms = [f for f in FORMS if any(r["form"] == f for r in rows)]
    for name in [*forms, "overall"]:
        sel = [r for r in rows if name == "overall" or r["form"] == name]
        n = len(sel)
        out[name] = {
            "n": n,
            "within_1m": 100.0 * sum(r["within_1m"] for r in sel) / n if n else math.nan,
            "within_0.5m": 100.0 * sum(r["within_0.5m"] for r in sel) / n if n else math.nan,
            "semantic": 100.0 * sum(r["semantic"] for r in sel) / n if n else math.nan,
        }
    return out


def _latency(rows: Sequence[dict[str, Any]]) -> dict[str, dict[str, float]]:
    stages = sorted({k for r in rows for k in r["timings_ms"]})
    out = {}
    for stage in stages:
        values = sorted(float(r["timings_ms"][stage]) for r in rows if stage in r["timings_ms"])
        out[stage] = {"p50": percentile(values, 50), "p99": percentile(values, 99)}
    return out


def print_table(totals: dict[str, dict[str, Any]]) -> None:
    """Accuracy per form, one line each."""
    print(f"\n{'form':18s} {'n':>4s} {'<=1 m':>7s} {'<=0.5 m':>8s} {'semantic':>9s}")
    for name, s in totals.items():
        if name == "overall":
            print("-" * 50)
        print(
            f"{name:18s} {s['n']:4d} {s['within_1m']:6.1f}% {s['within_0.5m']:7.1f}% "
            f"{s['semantic']:8.1f}%"
        )


def print_misses(rows: Sequence[dict[str, Any]]) -> None:
    """The requests not answered within 1 m."""
    misses = [r for r in rows if not r["within_1m"]]
    print(f"\nmisses ({len(misses)} of {len(rows)}, answer farther than {NEAR_M:g} m):")
    for r in misses:
        dist = "no answer" if r["distance"] is None else f"{r['distance']:.2f} m"
        print(f"  {r['id']} [{r['form']}] {r['text']}")
        print(
            f"      answer {r['answer_id']} {r['answer_label']!r} in {r['answer_room']!r} "
            f"({dist}; nearest truth {r['nearest_gt']}) | wanted {'/'.join(r['target_labels'])} "
            f"| parsed {_parsed_text(r['parsed'])}"
        )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Prepare the data, answer and judge every request; the report."""
    from inherit_sg.facade import MapService
    from inherit_sg.retrieval.engine import QueryEngine  # noqa: F401  (fail before rendering)

    dataset = ensure_dataset(args.work, args.house)
    map_dir = ensure_map(args.work, dataset, args.rebuild_map)
    scene = Scene.load(dataset)
    requests = load_requests(args.requests)
    problems = check_requests(requests, scene)
    if problems:
        raise SystemExit(
            "request file does not match the ground truth:\n  " + "\n  ".join(problems)
        )
    objects = {o.id: o for o in scene.objects}
    truth = GroundTruth(scene)
    rows = []
    verify = not args.no_verify
    t0 = time.perf_counter()
    print(f"\nanswering {len(requests)} requests (verify={verify})", flush=True)
    with MapService.open(map_dir) as svc:
        for k, req in enumerate(requests, 1):
            result = svc.query(req.text, verify=verify).to_dict()
            rows.append(judge(req, result, objects, truth))
            if k % 25 == 0 or k == len(requests):
                print(f"  {k}/{len(requests)} ({time.perf_counter() - t0:.0f} s)", flush=True)
    totals = summarise(rows)
    return {
        "house": str(args.house),
        "dataset": str(dataset),
        "map": str(map_dir),
        "requests_file": str(args.requests),
        "verify": verify,
        "totals": totals,
        "latency_ms": _latency(rows),
        "results": rows,
    }


def main(argv: Sequence[str] | None = None) -> None:
    """Run the benchmark, print the table and the misses, write the JSON results."""
    ap = argparse.ArgumentParser(
        description=(__doc__ or "").split("\n\n")[0],
        epilog="Rendering and mapping are cached under --work and reused.",
    )
    ap.add_argument(
        "--work",
        type=Path,
        default=Path("/tmp/mp3d_bench"),
        help="folder for the rendered dataset and the map (default: %(default)s)",
    )
    ap.add_argument("--no-verify", action="store_true", help="answer without verification")
    ap.add_argument("--out", type=Path, default=OUT, help="JSON results (default: %(default)s)")
    ap.add_argument(
        "--requests", type=Path, default=REQUESTS, help="request file (default: %(default)s)"
    )
    ap.add_argument("--house", type=Path, default=HOUSE, help="Matterport3D .house file")
    ap.add_argument("--rebuild-map", action="store_true", help="map the dataset again")
    args = ap.parse_args(argv)
    report = run(args)
    print_table(report["totals"])
    print_misses(report["results"])
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    print(f"\nwritten {args.out}")


if __name__ == "__main__":
    main()
