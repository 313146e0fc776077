"""``inherit-sg map``: build maps from RGB-D datasets."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from inherit_sg.cli.output import handle_errors, print_json, print_table

app = typer.Typer(
    name="map", help="Build and extend maps from posed RGB-D datasets.", no_args_is_help=True
)


@app.command("build")
@handle_errors
def build(
    dataset: Annotated[
        Path, typer.Argument(help="Dataset folder (isg, Replica, ScanNet, TUM, HM3D).")
    ],
    map_dir: Annotated[
        Path, typer.Option("--map", "-m", help="Map directory (created when absent).")
    ],
    fmt: Annotated[
        str,
        typer.Option(
            "--format",
            "-f",
            help="auto, isg, replica, scannet, tum, hm3d, mp3d or record3d (.r3d).",
        ),
    ] = "auto",
    session: Annotated[str | None, typer.Option(help="Session name (default session-N).")] = None,
    max_frames: Annotated[int | None, typer.Option(min=1, help="Only the first N frames.")] = None,
    config_file: Annotated[Path | None, typer.Option("--config", help="TOML config file.")] = None,
    overrides: Annotated[
        list[str] | None,
        typer.Option("--set", help="Config override section.field=value (repeatable)."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the summary as JSON.")] = False,
    rerun: Annotated[
        str | None,
        typer.Option(
            "--rerun",
            metavar="FILE.rrd|URL",
            help="Log frames, the graph after each update and the BEV to Rerun: a .rrd file "
            "or a running viewer's URL (rerun+http://127.0.0.1:9876/proxy). Needs rerun-sdk.",
        ),
    ] = None,
    rerun_images: Annotated[
        int, typer.Option(min=1, help="With --rerun: log the RGB-D images of every Nth frame.")
    ] = 5,
) -> None:
    """Map DATASET into a map directory as a new session (appends to an existing map)."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from inherit_sg.config import load_config
    from inherit_sg.facade import build_map

    cfg = load_config(config_file, overrides or [])
    observer = None
    if rerun is not None:
        from inherit_sg.viz.rerun_log import RerunLog

        observer = RerunLog(rerun, image_every=rerun_images, name=f"map build {dataset}")
    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        transient=as_json,
    ) as bars:
        frames = bars.add_task("frames", total=None)
        keyframes = bars.add_task("keyframes (semantic)", total=None)
        objects = bars.add_task("objects", total=None)

        def total(n: int) -> None:
            bars.update(frames, total=n)

        def progress(p: Any) -> None:
            bars.update(frames, completed=p.frames)
            bars.update(keyframes, completed=p.keyframes_done, total=max(p.keyframes, 1))
            bars.update(objects, completed=p.objects, total=max(p.objects, 1))

        summary = build_map(
            dataset,
            map_dir,
            fmt=fmt,
            session_name=session,
            config=cfg,
            max_frames=max_frames,
            progress=progress,
            total=total,
            observer=observer,
        )
    if observer is not None:
        observer.bev([Path(p) for p in summary["bev"]])
        observer.close()
        summary["rerun"] = rerun
    if as_json:
        print_json(summary)
        return
    rows = [
        [k, summary[k]]
        for k in (
            "session_id",
            "frames",
            "keyframes",
            "dropped_keyframes",
            "floors",
            "rooms",
            "areas",
            "objects",
            "relations",
            "missing",
            "seconds",
            "geometry_fps",
            "semantic_keyframes_per_s",
        )
    ]
    rows.append(["updates", ", ".join(f"{k} {v}" for k, v in summary["updates"].items())])
    print_table(["", "value"], rows, title=f"map {summary['map']}")
    for png in summary["bev"]:
        typer.echo(f"BEV picture: {png}")
    if rerun is not None:
        typer.echo(f"Rerun recording: {rerun}")


@app.command("compact")
@handle_errors
def compact(
    map_dir: Annotated[Path, typer.Argument(help="Map directory.")],
    as_json: Annotated[bool, typer.Option("--json", help="Print the result as JSON.")] = False,
) -> None:
    """Rewrite a map's databases without the pages earlier writes left dead.

    Kuzu hardly reuses freed pages, so a map written many times grows far
    past its data. The graph is exported and imported again, checked table
    by table to hold the same rows, and only then put in place; the search
    index is built afresh. A build does this itself when it ends
    (store.compact_on_finish); use this for older maps or after live
    sessions. Needs the writer lock: no session may be mapping.
    """
    from inherit_sg.facade import compact_map

    result = compact_map(map_dir)
    if as_json:
        print_json(result)
        return
    rows = [
        [name, f"{result['before'][name]:,}", f"{result['after'][name]:,}"]
        for name in result["before"]
    ]
    print_table(["file", "bytes before", "bytes after"], rows, title=f"map {result['map']}")
    typer.echo(
        f"kept {result['rows']:,} rows in {result['tables']} tables; "
        f"freed {result['saved'] / 1e6:.1f} MB"
    )
