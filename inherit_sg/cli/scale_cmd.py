"""``inherit-sg map build-many MANIFEST --out ROOT [--ray ADDRESS]``: many maps on Ray.

Register with ``map_cmd.app.command("build-many")(scale_cmd.build_many)``. Ray is
imported only when the command runs (see :mod:`inherit_sg.scale`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from inherit_sg.cli.output import (
    ConfigFileOption,
    OverridesOption,
    counting_bars,
    handle_errors,
    print_json,
    print_table,
)

SUMMARY_COLUMNS = ("map", "status", "sessions", "frames", "rooms", "objects", "seconds", "error")


def summary_rows(report: dict[str, Any]) -> list[list[Any]]:
    """One table row per map of a build-many report."""
    return [
        [
            r["map"],
            r["status"],
            len(r.get("sessions", [])),
            r.get("frames", ""),
            r.get("rooms", ""),
            r.get("objects", ""),
            r.get("seconds", ""),
            r.get("error", ""),
        ]
        for r in report["maps"]
    ]


@handle_errors
def build_many(
    manifest: Annotated[
        Path,
        typer.Argument(
            help="JSONL manifest: one map per line, {dataset, format?, map?, session?, "
            "max_frames?} or {map?, format?, sessions: [{dataset, format?, session?, "
            "max_frames?}, ...]}."
        ),
    ],
    out: Annotated[Path, typer.Option("--out", "-o", help="Root folder of the maps.")],
    ray_address: Annotated[
        str | None,
        typer.Option(
            "--ray",
            metavar="ADDRESS",
            help="Ray cluster to run on (auto, HOST:6379, ray://HOST:10001); "
            "default: a local cluster sized to this machine.",
        ),
    ] = None,
    retries: Annotated[
        int, typer.Option(min=0, max=10, help="Retries of a failed or killed task.")
    ] = 2,
    cpus_per_map: Annotated[
        float, typer.Option(min=0.1, help="CPUs Ray reserves for each map's task.")
    ] = 1.0,
    config_file: ConfigFileOption = None,
    overrides: OverridesOption = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the report as JSON.")] = False,
) -> None:
    """Build one map per manifest line under ROOT, one Ray task per map: different maps
    in parallel, a map's sessions in order. A map appears under ROOT only once all its
    sessions are built; a failed task is retried, then reported. Exit code 1 when some
    map failed."""
    from inherit_sg.config import load_config
    from inherit_sg.scale import require_ray
    from inherit_sg.scale.build_many import build_many as run
    from inherit_sg.scale.manifest import read_manifest

    cfg = load_config(config_file, overrides or [])  # sent to every task
    jobs = read_manifest(manifest)
    require_ray()
    with counting_bars(transient=as_json) as bars:
        bar = bars.add_task("maps", total=len(jobs))

        def done(record: dict[str, Any]) -> None:
            bars.update(bar, advance=1, description=f"maps (last: {record['map']})")

        report = run(
            jobs,
            out,
            address=ray_address,
            config=cfg,
            max_retries=retries,
            cpus_per_map=cpus_per_map,
            on_done=done,
        )
    if as_json:
        print_json(report)
    else:
        print_table(
            SUMMARY_COLUMNS,
            summary_rows(report),
            title=f"build-many {report['root']} on {report['ray']['address']} Ray "
            f"({report['ray']['cpus']} CPUs)",
        )
        typer.echo(
            f"{report['built']} built, {report['failed']} failed in {report['seconds']:.1f} s"
        )
    if report["failed"]:
        raise typer.Exit(code=1)
