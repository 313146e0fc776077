"""``inherit-sg map``: build maps from RGB-D datasets."""

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

app = typer.Typer(
    name="map", help="Build and extend maps from posed RGB-D datasets.", no_args_is_help=True
)

ROS = "ROS bag (--format rosbag)"


@app.command("build")
@handle_errors
def build(
    dataset: Annotated[
        Path,
        typer.Argument(help="Dataset folder (isg, Replica, ScanNet, TUM, HM3D) or ROS bag."),
    ],
    map_dir: Annotated[
        Path, typer.Option("--map", "-m", help="Map directory (created when absent).")
    ],
    fmt: Annotated[
        str,
        typer.Option(
            "--format",
            "-f",
            help="auto, isg, replica, scannet, tum, hm3d, mp3d, record3d (.r3d) or rosbag.",
        ),
    ] = "auto",
    session: Annotated[str | None, typer.Option(help="Session name (default session-N).")] = None,
    max_frames: Annotated[int | None, typer.Option(min=1, help="Only the first N frames.")] = None,
    config_file: ConfigFileOption = None,
    overrides: OverridesOption = None,
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
    rgb: Annotated[
        str | None,
        typer.Option(help="Colour image topic (Image or CompressedImage).", rich_help_panel=ROS),
    ] = None,
    depth: Annotated[
        str | None,
        typer.Option(
            help="Depth image topic (16UC1 or 32FC1), aligned to colour.", rich_help_panel=ROS
        ),
    ] = None,
    camera_info: Annotated[
        str | None,
        typer.Option(help="CameraInfo topic of the colour camera.", rich_help_panel=ROS),
    ] = None,
    pose: Annotated[
        str | None,
        typer.Option(
            help="Camera pose topic (PoseStamped, PoseWithCovarianceStamped, TransformStamped "
            "or Odometry) in a z-up world.",
            rich_help_panel=ROS,
        ),
    ] = None,
    tf: Annotated[
        str | None,
        typer.Option(
            metavar="PARENT:CHILD",
            help="Camera pose from /tf and /tf_static, e.g. map:camera_color_optical_frame.",
            rich_help_panel=ROS,
        ),
    ] = None,
    depth_scale: Annotated[
        float | None,
        typer.Option(
            help="Metres per unit of 16UC1 depth (default 0.001: millimetres).", rich_help_panel=ROS
        ),
    ] = None,
    camera_axes: Annotated[
        str | None,
        typer.Option(
            help="Axes of the posed frame: optical (x right, y down, z forward; the "
            "default) or body (x forward, y left, z up, e.g. camera_link).",
            rich_help_panel=ROS,
        ),
    ] = None,
) -> None:
    """Map DATASET into a map directory as a new session (appends to an existing map).

    ROS bags: topics left out are picked by message type and name; when that is
    ambiguous the error lists the candidates. See them with `inherit-sg map topics BAG`.
    """
    from inherit_sg.config import load_config
    from inherit_sg.facade import build_map

    ros = {
        "rgb_topic": rgb,
        "depth_topic": depth,
        "camera_info_topic": camera_info,
        "pose_topic": pose,
        "tf": tf,
        "depth_scale": depth_scale,
        "camera_axes": camera_axes,
    }
    reader_options = _rosbag_options(dataset, fmt, ros)
    cfg = load_config(config_file, overrides or [])
    observer = None
    if rerun is not None:
        from inherit_sg.viz.rerun_log import RerunLog

        observer = RerunLog(rerun, image_every=rerun_images, name=f"map build {dataset}")
    with counting_bars(transient=as_json) as bars:
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
            reader_options=reader_options,
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


def _rosbag_options(dataset: Path, fmt: str, options: dict[str, Any]) -> dict[str, Any]:
    """The ROS bag options given; InputError when they are given for another format."""
    from inherit_sg.errors import InputError
    from inherit_sg.ingest.readers import detect_format

    given = {k: v for k, v in options.items() if v is not None}
    if given and (fmt if fmt != "auto" else detect_format(dataset)) != "rosbag":
        flags = ", ".join("--" + k.removesuffix("_topic").replace("_", "-") for k in given)
        raise InputError(f"{flags}: options of ROS bags (--format rosbag) only")
    return given


@app.command("topics")
@handle_errors
def topics(
    bag: Annotated[Path, typer.Argument(help="ROS 1 .bag file or ROS 2 bag folder.")],
    as_json: Annotated[bool, typer.Option("--json", help="Print the topics as JSON.")] = False,
) -> None:
    """List a ROS bag's topics and which ones `map build` would pick by itself."""
    from inherit_sg.ingest.readers.rosbag import list_topics, topic_roles

    found = list_topics(bag)
    roles, problems = topic_roles(found)
    if as_json:
        rows = [{**t.__dict__, "role": roles.get(t.name, "")} for t in found]
        print_json({"bag": str(bag), "topics": rows, "problems": problems})
        return
    # plain columns, not a table: topic names must stay whole to be pasted into options
    width = max((len(t.name) for t in found), default=5)
    type_width = max((len(t.msgtype) for t in found), default=4)
    typer.echo(f"{'topic':<{width}}  {'type':<{type_width}}  {'messages':>8}  picked as")
    for t in found:
        role = roles.get(t.name, "")
        typer.echo(f"{t.name:<{width}}  {t.msgtype:<{type_width}}  {t.count:>8}  {role}".rstrip())
    for problem in problems:
        typer.echo(f"note: {problem}")


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
