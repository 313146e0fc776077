"""``inherit-sg bench``: benchmark a dataset with ground truth end to end.

``inherit-sg bench --dataset DIR [--map DIR] --out results.json [--set key=value ...]
[--no-ablations] [--max-queries N]``. Without ``--map`` the dataset is mapped into a
temporary directory first (which also gives the mapping speed and memory figures).
Several ``--dataset`` options write ``OUT/NAME.json`` each, one after the other, or with
``--ray [--ray-address A]`` one Ray task per dataset in parallel.

Register on the main app with ``app.command("bench")(bench_cmd.bench)``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from inherit_sg.cli.output import (
    ConfigFileOption,
    OverridesOption,
    counting_bars,
    handle_errors,
    jsonable,
    print_table,
)
from inherit_sg.errors import InputError

if TYPE_CHECKING:
    from inherit_sg.benchmark.runner import BenchOptions


def _headline(doc: dict) -> None:
    groups = ("A-C", "D", "E", "F", "overall", "group_mean")
    rows = []
    for system, summary in doc["accuracy"].items():
        for metric in ("within_1m", "within_0.5m", "semantic"):
            rows.append([system, metric, *(f"{summary[g][metric]:.1f}" for g in groups)])
    print_table(["system", "metric", *groups], rows, title="retrieval accuracy (%)")


@handle_errors
def bench(
    dataset: Annotated[
        list[Path],
        typer.Option(
            "--dataset", "-d", help="Dataset folder with scene.json (repeat for several)."
        ),
    ],
    out: Annotated[
        Path,
        typer.Option(
            "--out",
            "-o",
            help="Results JSON file; with several datasets a folder (one NAME.json each).",
        ),
    ],
    map_dir: Annotated[
        Path | None,
        typer.Option("--map", "-m", help="Existing map of the dataset (default: build one)."),
    ] = None,
    config_file: ConfigFileOption = None,
    overrides: OverridesOption = None,
    no_ablations: Annotated[
        bool, typer.Option("--no-ablations", help="Skip the ablation runs.")
    ] = False,
    max_queries: Annotated[
        int | None,
        typer.Option("--max-queries", min=1, help="Use at most N requests (all categories)."),
    ] = None,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress lines.")] = False,
    ray: Annotated[
        bool,
        typer.Option("--ray", help="One Ray task per dataset, in parallel (needs the ray extra)."),
    ] = False,
    ray_address: Annotated[
        str | None,
        typer.Option("--ray-address", help="With --ray: a running cluster (default: a local one)."),
    ] = None,
) -> None:
    """Measure retrieval accuracy (ours vs flat baseline), ablations, mapping speed and
    quality, storage per node type and query latency on one dataset or several."""
    from inherit_sg.benchmark.runner import BenchOptions
    from inherit_sg.config import load_config

    cfg = load_config(config_file, overrides or [])
    if map_dir is not None and len(dataset) > 1:
        raise InputError("--map names the map of one dataset: give one --dataset with it")
    options = [
        BenchOptions(
            dataset=d,
            map_dir=map_dir,
            config=cfg,
            overrides=list(overrides or []),
            ablations=not no_ablations,
            max_queries=max_queries,
        )
        for d in dataset
    ]
    if len(options) == 1 and not ray:
        _bench_one(options[0], out, quiet)
        return
    _bench_several(options, out, ray=ray, address=ray_address, quiet=quiet)


def _bench_one(opts: BenchOptions, out: Path, quiet: bool) -> None:
    from inherit_sg.benchmark.runner import run_benchmark

    def say(line: str) -> None:
        if not quiet:
            typer.echo(f"[bench] {line}", err=True)

    doc = run_benchmark(opts, say)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(jsonable(doc), indent=1) + "\n", encoding="utf-8")
    if not quiet:
        _headline(doc)
    typer.echo(f"results written to {out}")


def _bench_several(
    options: list[BenchOptions], out: Path, *, ray: bool, address: str | None, quiet: bool
) -> None:
    """Several datasets into ``out/NAME.json``: on Ray in parallel, else one by one."""
    from inherit_sg.scale.bench_many import BenchJob, bench_many, run_bench_job

    names = [o.dataset.resolve().name for o in options]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise InputError(f"two datasets share the folder name {twice[0]!r}: results would clash")
    if out.suffix == ".json":
        raise InputError(f"--out {out}: with several datasets (or --ray) give a folder")
    jobs = [BenchJob(o, out / f"{n}.json") for o, n in zip(options, names, strict=True)]
    with counting_bars(transient=quiet) as bars:
        bar = bars.add_task("datasets", total=len(jobs))

        def done(record: dict[str, Any]) -> None:
            bars.update(bar, advance=1, description=f"datasets (last: {record['dataset']})")

        if ray:
            report = bench_many(jobs, address=address, on_done=done)
            records = report["datasets"]
        else:
            records = []
            for job in jobs:
                records.append(run_bench_job(job))
                done(records[-1])
    rows = [
        [
            r["dataset"],
            r["status"],
            r.get("requests", ""),
            f"{r['within_1m']:.1f}" if "within_1m" in r else r.get("error", ""),
            r.get("seconds", ""),
        ]
        for r in records
    ]
    print_table(["dataset", "status", "requests", "within 1 m %", "seconds"], rows, title="bench")
    typer.echo(f"results written to {out}/")
    if any(r["status"] != "done" for r in records):
        raise typer.Exit(1)
