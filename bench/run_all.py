"""Run ``inherit-sg bench`` on a fixed set of datasets and render ``docs/benchmarks.md``.

The set: generated two-floor houses at the generator's default 640×480 (seeds 811 and
812, 812 with an open-plan ground floor, each with clean and with the generator's noisy
perception), the Matterport3D house of
``../shared/data/real/mp3d/`` rendered with ``inherit-sg sim render-house`` (skipped
when absent); then the request sets measured by their own scripts: the parser on the
development set (``bench/parse.py``) and two human-written request sets on the MP3D house
(``bench/mp3d_requests.py``); last, the earlier generator's houses (``--style classic``,
seeds 201 and 202) so that the page shows past figures beside the new ones
(``--only NAME[,NAME]`` runs a part of the set). Each dataset is mapped from its frames by the benchmark itself, so the
mapping figures are measured too. Results go to ``bench/results/run_all/<name>.json``;
the page gets tables and figures (``docs/img/bench_*.png``), including latency by map
size from ``bench/results/retrieval.json``.

    python bench/run_all.py [--max-queries 400] [--no-ablations] [--work DIR] [--ray]
    python bench/run_all.py --report-only      # re-render the page from the JSON files
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results" / "run_all"
SCALE_JSON = ROOT / "bench" / "results" / "retrieval.json"
PARSE_JSON = ROOT / "bench" / "results" / "parse.json"
MP3D_REQUESTS_JSON = ROOT / "bench" / "results" / "mp3d_requests.json"
# Further request sets for the MP3D house, each by its own author: page key -> file stem
# (bench/data/<stem>.jsonl, bench/results/<stem>.json).
MP3D_MORE = {
    "mp3d_independent": "mp3d_requests_independent",
    "mp3d_third": "mp3d_requests_third",
    "mp3d_fourth": "mp3d_requests_fourth",
    "mp3d_fifth": "mp3d_requests_fifth",
    "mp3d_sixth": "mp3d_requests_sixth",
    "mp3d_seventh": "mp3d_requests_seventh",
    "mp3d_eighth": "mp3d_requests_eighth",
    "mp3d_ninth": "mp3d_requests_ninth",
    "mp3d_tenth": "mp3d_requests_tenth",
    "mp3d_eleventh": "mp3d_requests_eleventh",
    "mp3d_twelfth": "mp3d_requests_twelfth",
    "mp3d_thirteenth": "mp3d_requests_thirteenth",
    "mp3d_fourteenth": "mp3d_requests_fourteenth",
    "mp3d_fifteenth": "mp3d_requests_fifteenth",
}
MP3D_ROOMS_JSON = ROOT / "bench" / "results" / "mp3d_rooms.json"
MP3D_OBJECTS_JSON = ROOT / "bench" / "results" / "mp3d_objects.json"
DOCS = ROOT / "docs"
MP3D_HOUSE = ROOT / ".." / "shared" / "data" / "real" / "mp3d" / "example_mp3d_scene.house"
WIDTH, HEIGHT = 640, 480


@dataclass(frozen=True)
class DatasetSpec:
    """One dataset of the fixed set."""

    name: str
    description: str
    kind: str  # "house" (generated) or "mp3d"
    seed: int = 0
    noise: str = "clean"
    style: str = "real"  # the generator: "real" (default) or "classic" (the earlier one)
    open_plan: bool | None = None  # None: drawn by the generator


def _house(
    seed: int, noise: str, style: str = "real", open_plan: bool | None = None
) -> DatasetSpec:
    prefix = "classic-" if style == "classic" else ""
    plan = {True: ", open-plan ground floor", False: ", walled rooms", None: ""}[open_plan]
    what = "earlier generator (--style classic)" if style == "classic" else "generated house"
    return DatasetSpec(
        f"{prefix}house-{seed}-{noise}",
        f"{what}, seed {seed}, 2 floors{plan}, {noise}",
        "house",
        seed,
        noise,
        style,
        open_plan,
    )


# The current generator on seeds never used while tuning it (one of them forced open-plan),
# the real MP3D house, then the earlier generator's houses for comparison with past figures.
DATASETS = (
    _house(811, "clean"),
    _house(811, "noisy"),
    _house(812, "clean", open_plan=True),
    _house(812, "noisy", open_plan=True),
    DatasetSpec("mp3d-house", "Matterport3D example house, rendered, clean", "mp3d"),
    _house(201, "clean", "classic"),
    _house(201, "noisy", "classic"),
    _house(202, "clean", "classic"),
    _house(202, "noisy", "classic"),
)


def make_dataset(spec: DatasetSpec, out: Path) -> bool:
    """Write the dataset folder (kept when already there); False when its source is
    missing."""
    if (out / "scene.json").is_file():
        return True
    if spec.kind == "mp3d":
        if not MP3D_HOUSE.is_file():
            return False
        from inherit_sg.ingest.mp3d_dataset import load_house_world, write_house_dataset

        write_house_dataset(
            load_house_world(MP3D_HOUSE), out, seed=spec.seed, width=WIDTH, height=HEIGHT
        )
        return True
    from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset

    house = generate_house(spec.seed, 2, style=spec.style, open_plan=spec.open_plan)
    write_dataset(house, out, noise=spec.noise, width=WIDTH, height=HEIGHT, seed=spec.seed)
    return True


def _bench_cmd(datasets: list[Path], out: Path, args: argparse.Namespace) -> list[str]:
    cmd = [sys.executable, "-m", "inherit_sg.cli.main", "bench"]
    for dataset in datasets:
        cmd += ["--dataset", str(dataset)]
    cmd += ["--out", str(out), "--max-queries", str(args.max_queries)]
    return cmd + (["--no-ablations"] if args.no_ablations else [])


def _labelled(spec: DatasetSpec, found: Path) -> Path:
    """The bench JSON ``found`` of ``spec``, labelled, as ``RESULTS/NAME.json``."""
    doc = json.loads(found.read_text(encoding="utf-8"))
    doc.update(label=spec.name, description=spec.description)
    out = RESULTS / f"{spec.name}.json"
    out.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    return out


def run_one(spec: DatasetSpec, dataset: Path, args: argparse.Namespace) -> Path:
    """``inherit-sg bench`` on one dataset in its own process; the JSON path."""
    out = RESULTS / f"{spec.name}.json"
    subprocess.run(_bench_cmd([dataset], out, args), check=True, cwd=ROOT)
    return _labelled(spec, out)


def run_on_ray(specs: list[DatasetSpec], work: Path, args: argparse.Namespace) -> list[Path]:
    """``inherit-sg bench --ray`` on every dataset at once (one Ray task each); the JSON
    paths (the same documents as one by one)."""
    out = work / "bench-ray"
    cmd = [*_bench_cmd([work / spec.name for spec in specs], out, args), "--ray"]
    if args.ray_address:
        cmd += ["--ray-address", args.ray_address]
    subprocess.run(cmd, check=True, cwd=ROOT)
    return [_labelled(spec, out / f"{spec.name}.json") for spec in specs]


def load_docs() -> list[dict[str, Any]]:
    """The result documents of the fixed set that exist, in the set's order."""
    docs = []
    for spec in DATASETS:
        path = RESULTS / f"{spec.name}.json"
        if path.is_file():
            docs.append(json.loads(path.read_text(encoding="utf-8")))
    return docs


def render(docs: list[dict[str, Any]]) -> Path:
    """Write the figures and ``docs/benchmarks.md`` from ``docs``."""
    from inherit_sg.benchmark.page import render_page
    from inherit_sg.benchmark.plots import plot_accuracy, plot_latency_scale, plot_storage

    img = DOCS / "img"
    images = {
        "accuracy": plot_accuracy(docs, img / "bench_accuracy.png"),
        "storage": plot_storage(docs, img / "bench_storage.png"),
    }
    scale = None
    if SCALE_JSON.is_file():
        scale = json.loads(SCALE_JSON.read_text(encoding="utf-8")).get("latency")
        if scale:
            images["latency_scale"] = plot_latency_scale(scale, img / "bench_latency_scale.png")
    preamble = (
        "Generated by `python bench/run_all.py` (re-render with `--report-only`) from "
        "`bench/results/run_all/*.json`, each written by `inherit-sg bench --dataset DIR "
        "--out FILE`. CPU only, offline describer and verifier, rule parser; images "
        f"{WIDTH}×{HEIGHT}. Requests are a category-balanced cut of each dataset's "
        "`queries.jsonl` (`--max-queries`). Generated `house-811-*` / `house-812-*` rows come "
        "from the current generator (Matterport3D room types and object categories, "
        "open-plan floors, continuous colours) on seeds that were fresh when first measured "
        "(see *Fresh generated houses* for seeds nobody had looked at); "
        "`classic-house-*` rows are the earlier generator's figures (`--style classic`), "
        "kept for comparison with past results."
    )
    rel = {k: str(v.relative_to(DOCS)) for k, v in images.items()}
    sets = {
        name: json.loads(path.read_text(encoding="utf-8"))
        for name, path in (
            ("parse", PARSE_JSON),
            ("probe", RESULTS.parent / "probe_requests.json"),
            ("mp3d", MP3D_REQUESTS_JSON),
            *((key, RESULTS.parent / f"{stem}.json") for key, stem in MP3D_MORE.items()),
            ("mp3d_rooms", MP3D_ROOMS_JSON),
            ("mp3d_objects", MP3D_OBJECTS_JSON),
            ("fresh_seeds", RESULTS.parent / "fresh_seeds.json"),
            ("hostile", RESULTS.parent / "hostile.json"),
            ("cypher_isolation", RESULTS.parent / "cypher_isolation.json"),
            ("performance", RESULTS.parent / "performance.json"),
            ("service", RESULTS.parent / "service.json"),
            ("gpu_adapters", RESULTS.parent / "gpu_adapters.json"),
        )
        if path.is_file()
    }
    page = DOCS / "benchmarks.md"
    page.write_text(render_page(docs, scale, rel, preamble, sets), encoding="utf-8")
    return page


def run_request_sets(work: Path) -> None:
    """The parser's development set and probe sets, and the MP3D human-written request
    sets (each script writes its JSON under bench/results/)."""
    print("== request parsing (bench/parse.py --dev)", flush=True)
    subprocess.run([sys.executable, str(ROOT / "bench" / "parse.py"), "--dev"], check=True)
    print("== probe request sets (bench/probe_requests.py)", flush=True)
    subprocess.run([sys.executable, str(ROOT / "bench" / "probe_requests.py")], check=True)
    if MP3D_HOUSE.is_file():
        print("== MP3D human-written requests (bench/mp3d_requests.py)", flush=True)
        script = ROOT / "bench" / "mp3d_requests.py"
        subprocess.run(
            [sys.executable, str(script), "--work", str(work / "mp3d-requests")], check=True
        )
        for stem in MP3D_MORE.values():
            print(f"== MP3D requests, {stem} (bench/mp3d_requests.py --requests …)", flush=True)
            subprocess.run(
                [
                    sys.executable, str(script), "--work", str(work / "mp3d-requests"),
                    "--requests", str(ROOT / "bench" / "data" / f"{stem}.jsonl"),
                    "--out", str(RESULTS.parent / f"{stem}.json"),
                ],
                check=True,
            )  # fmt: skip


def main() -> None:
    """Run the fixed set (unless --report-only) and render the page."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-queries", type=int, default=400, help="requests per dataset")
    ap.add_argument("--no-ablations", action="store_true")
    ap.add_argument("--report-only", action="store_true", help="only re-render the page")
    ap.add_argument("--work", type=Path, help="keep (and reuse) datasets in this folder")
    ap.add_argument("--only", default="", help="comma-separated dataset names to run")
    ap.add_argument("--no-request-sets", action="store_true", help="skip parse and MP3D sets")
    ap.add_argument("--ray", action="store_true", help="bench the datasets in parallel on Ray")
    ap.add_argument("--ray-address", help="with --ray: a running cluster (default: local)")
    args = ap.parse_args()
    if not args.report_only:
        RESULTS.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory(prefix="isg-run-all-") as tmp:
            work = args.work or Path(tmp)
            only = {n.strip() for n in args.only.split(",") if n.strip()}
            unknown = only - {spec.name for spec in DATASETS}
            if unknown:
                sys.exit(f"unknown dataset name(s): {', '.join(sorted(unknown))}")
            ready: list[DatasetSpec] = []
            for spec in DATASETS:
                if only and spec.name not in only:
                    continue
                t0 = time.perf_counter()
                dataset = work / spec.name
                print(f"== {spec.name}: dataset", flush=True)
                if not make_dataset(spec, dataset):
                    print(f"== {spec.name}: skipped (source not found)", flush=True)
                    continue
                if args.ray:
                    ready.append(spec)
                    continue
                print(f"== {spec.name}: bench", flush=True)
                out = run_one(spec, dataset, args)
                print(f"== {spec.name}: {out} ({time.perf_counter() - t0:.0f} s)", flush=True)
            if ready:
                t0 = time.perf_counter()
                print(f"== bench on Ray: {', '.join(s.name for s in ready)}", flush=True)
                outs = run_on_ray(ready, work, args)
                print(f"== {len(outs)} results ({time.perf_counter() - t0:.0f} s)", flush=True)
            if not args.no_request_sets:
                run_request_sets(work)
    docs = load_docs()
    if not docs:
        sys.exit("no results in bench/results/run_all/ to report")
    print(f"written {render(docs)}")


if __name__ == "__main__":
    main()
