"""``inherit-sg bench``: benchmark a dataset with ground truth end to end.

``inherit-sg bench --dataset DIR [--map DIR] --out results.json [--set key=value ...]
[--no-ablations] [--max-queries N]``. Without ``--map`` the dataset is mapped into a
temporary directory first (which also gives the mapping speed and memory figures).

Register on the main app with ``app.command("bench")(bench_cmd.bench)``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from inherit_sg.cli.output import handle_errors, jsonable, print_table


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
        Path, typer.Option("--dataset", "-d", help="Dataset folder with scene.json.")
    ],
    out: Annotated[Path, typer.Option("--out", "-o", help="Results JSON file to write.")],
    map_dir: Annotated[
        Path | None,
        typer.Option("--map", "-m", help="Existing map of the dataset (default: build one)."),
    ] = None,
    config_file: Annotated[Path | None, typer.Option("--config", help="TOML config file.")] = None,
    overrides: Annotated[
        list[str] | None, typer.Option("--set", help="Config override section.field=value.")
    ] = None,
    no_ablations: Annotated[
        bool, typer.Option("--no-ablations", help="Skip the ablation runs.")
    ] = False,
    max_queries: Annotated[
        int | None,
        typer.Option("--max-queries", min=1, help="Use at most N requests (all categories)."),
    ] = None,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress lines.")] = False,
) -> None:
    """Measure retrieval accuracy (ours vs flat baseline), ablations, mapping speed and
    quality, storage per node type and query latency on one dataset."""
    from inherit_sg.benchmark.runner import BenchOptions, run_benchmark
    from inherit_sg.config import load_config

    cfg = load_config(config_file, overrides or [])
    opts = BenchOptions(
        dataset=dataset,
        map_dir=map_dir,
        config=cfg,
        overrides=list(overrides or []),
        ablations=not no_ablations,
        max_queries=max_queries,
    )

    def say(line: str) -> None:
        if not quiet:
            typer.echo(f"[bench] {line}", err=True)

    doc = run_benchmark(opts, say)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(jsonable(doc), indent=1) + "\n", encoding="utf-8")
    if not quiet:
        _headline(doc)
    typer.echo(f"results written to {out}")
