"""``inherit-sg sim``: synthetic multi-floor houses (``generate``) and Matterport3D
``.house`` layouts (``render-house``) walked and rendered into isg datasets, and real
scanned meshes rendered along their recorded trajectory (``render-mesh``).

Heavy imports (trimesh, embreex, scipy) happen inside the commands so that
``inherit-sg --help`` stays fast.
"""

from __future__ import annotations

import shutil
from collections.abc import Callable
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, TypeVar

import typer

from inherit_sg.cli.output import handle_errors, print_json, print_table
from inherit_sg.errors import InputError

if TYPE_CHECKING:
    from inherit_sg.ingest.synthetic.generate import DatasetSummary
    from inherit_sg.model import Intrinsics

Progress = Callable[[int, int], None]
Summary = TypeVar("Summary")

app = typer.Typer(
    name="sim",
    help="Simulated walks: synthetic or Matterport3D houses rendered into isg datasets.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


@app.callback()
def _sim() -> None:
    """Synthetic multi-floor houses and Matterport3D house renders."""


# What `generate` and `render-house` write into the output folder; --force replaces only these.
DATASET_ENTRIES = (
    "frames",
    "intrinsics.json",
    "poses.txt",
    "scene.json",
    "instances.json",
    "visibility.json",
    "walk.json",
    "queries.jsonl",
    "conversations.jsonl",
)


class NoiseLevel(StrEnum):
    """Perception noise levels (see inherit_sg.ingest.synthetic.noise)."""

    clean = "clean"
    noisy = "noisy"


class HouseStyle(StrEnum):
    """Generators of synthetic houses (see inherit_sg.ingest.synthetic.generate)."""

    real = "real"
    classic = "classic"


# Options shared by the commands that render walks.
NoiseOption = Annotated[NoiseLevel, typer.Option(help="Perception noise level.")]
WidthOption = Annotated[int, typer.Option(min=16, max=4096, help="Image width.")]
HeightOption = Annotated[int, typer.Option(min=16, max=4096, help="Image height.")]
WorkersOption = Annotated[
    int | None, typer.Option(min=1, help="Render processes (default: one per core).")
]
MaxFramesOption = Annotated[
    int | None, typer.Option(min=1, help="Keep only the first N frames of the walk.")
]
ShadowsOption = Annotated[
    bool, typer.Option("--shadows", help="Cast shadows from the room lights (slower).")
]
ForceOption = Annotated[bool, typer.Option("--force", help="Overwrite an existing dataset.")]
JsonOption = Annotated[bool, typer.Option("--json", help="Print the summary as JSON.")]


def _prepare_out(out: Path, force: bool) -> None:
    if out.exists() and not out.is_dir():
        raise InputError(f"output path {out} exists and is not a directory")
    if out.is_dir() and any(out.iterdir()):
        if not force:
            raise InputError(f"output directory {out} is not empty (use --force to overwrite)")
        for name in DATASET_ENTRIES:
            path = out / name
            if path.is_dir():
                shutil.rmtree(path)
            elif path.exists():
                path.unlink()
    out.mkdir(parents=True, exist_ok=True)


@app.command()
@handle_errors
def generate(
    out: Annotated[Path, typer.Option("--out", "-o", help="Dataset folder to write.")],
    seed: Annotated[int, typer.Option(min=0, help="Random seed (same seed, same house).")] = 0,
    floors: Annotated[int, typer.Option(min=1, max=3, help="Number of storeys.")] = 2,
    rooms_per_floor: Annotated[
        int | None,
        typer.Option(min=4, max=12, help="Rooms per storey incl. the hallway (default 5-8)."),
    ] = None,
    style: Annotated[
        HouseStyle,
        typer.Option(
            help="real: Matterport3D room types and object categories in real proportions, "
            "open-plan ground floors, continuous colours; classic: the earlier generator "
            "(nine room types, twelve named colours)."
        ),
    ] = HouseStyle.real,
    open_plan: Annotated[
        bool | None,
        typer.Option(
            "--open-plan/--no-open-plan",
            help="Force an open-plan ground floor (kitchen, dining and living rooms without "
            "walls between them) on or off; default: drawn, about two houses in five.",
            show_default=False,
        ),
    ] = None,
    noise: NoiseOption = NoiseLevel.clean,
    width: WidthOption = 640,
    height: HeightOption = 480,
    workers: WorkersOption = None,
    max_frames: MaxFramesOption = None,
    shadows: ShadowsOption = False,
    close_looks: Annotated[
        bool,
        typer.Option(
            "--close-looks/--no-close-looks",
            help="Besides a look-around in every room, glance at the ceiling and step up "
            "to the walls and furniture seen only from afar (about twice the frames).",
        ),
    ] = True,
    force: ForceOption = False,
    as_json: JsonOption = False,
) -> None:
    """Generate a house, walk through every room and write an isg dataset folder.

    Default houses: Matterport3D room types and objects in real proportions, open-plan floors.
    """
    from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset

    _prepare_out(out, force)
    house = generate_house(seed, floors, rooms_per_floor, style=style.value, open_plan=open_plan)
    summary = _with_progress(
        as_json,
        lambda progress: write_dataset(
            house,
            out,
            noise=noise.value,
            width=width,
            height=height,
            seed=seed,
            progress=progress,
            workers=workers,
            max_frames=max_frames,
            shadows=shadows,
            close_looks=close_looks,
        ),
    )
    _report(summary, as_json)


@app.command("render-house")
@handle_errors
def render_house(
    house_file: Annotated[
        Path, typer.Argument(help="Matterport3D .house file (region and object annotations).")
    ],
    out: Annotated[Path, typer.Option("--out", "-o", help="Dataset folder to write.")],
    seed: Annotated[int, typer.Option(min=0, help="Random seed of the walk and the noise.")] = 0,
    noise: NoiseOption = NoiseLevel.clean,
    width: WidthOption = 640,
    height: HeightOption = 480,
    workers: WorkersOption = None,
    max_frames: MaxFramesOption = None,
    shadows: ShadowsOption = False,
    force: ForceOption = False,
    as_json: JsonOption = False,
) -> None:
    """Render a Matterport3D house into an isg dataset with ground truth and queries.

    Regions become rooms, object boxes objects; coordinates stay the file's own (z-up metres).
    """
    from inherit_sg.ingest.mp3d_dataset import load_house_world, write_house_dataset

    if not house_file.is_file():
        raise InputError(f"house file not found: {house_file}")
    world = load_house_world(house_file)
    _prepare_out(out, force)
    summary = _with_progress(
        as_json,
        lambda progress: write_house_dataset(
            world,
            out,
            seed=seed,
            noise=noise.value,
            width=width,
            height=height,
            progress=progress,
            workers=workers,
            max_frames=max_frames,
            shadows=shadows,
        ),
    )
    _report(summary, as_json)


@app.command("render-mesh")
@handle_errors
def render_mesh(
    mesh_file: Annotated[
        Path, typer.Argument(help="Coloured triangle mesh (PLY/OBJ) of a scanned place.")
    ],
    trajectory: Annotated[
        Path,
        typer.Option(
            "--trajectory",
            "-t",
            help="Camera-to-world poses, one row-major 4×4 matrix per line (NICE-SLAM "
            "traj.txt; z-up world, OpenCV camera).",
        ),
    ],
    camera: Annotated[
        Path,
        typer.Option(
            "--camera",
            "-c",
            help="Camera intrinsics: cam_params.json (NICE-SLAM) or an isg intrinsics.json.",
        ),
    ],
    out: Annotated[Path, typer.Option("--out", "-o", help="Dataset folder to write.")],
    frames: Annotated[
        int, typer.Option(min=1, help="Frames to render, spread evenly over the trajectory.")
    ] = 200,
    scale: Annotated[
        float,
        typer.Option(min=0.05, max=4.0, help="Image size relative to the camera's own."),
    ] = 0.5,
    force: ForceOption = False,
    as_json: JsonOption = False,
) -> None:
    """Render a real scanned mesh along its recorded trajectory into an isg dataset.

    The frames have no instance masks, like a real RGB-D recording: `map build` finds objects
    with the classical segmenter. Example (Replica office0):
    `inherit-sg sim render-mesh office0_mesh.ply -t traj.txt -c cam_params.json -o office0`.
    """
    from inherit_sg.ingest.mesh_render import MeshRenderer, write_mesh_dataset
    from inherit_sg.ingest.readers.replica import read_trajectory

    intrinsics = _read_camera(camera).scaled(scale)
    poses = read_trajectory(trajectory)
    renderer = MeshRenderer.load(mesh_file)
    _prepare_out(out, force)
    summary = _with_progress(
        as_json,
        lambda progress: write_mesh_dataset(
            renderer, poses, intrinsics, out, frames=frames, progress=progress
        ),
    )
    if as_json:
        print_json(summary.to_dict())
        return
    print_table(
        ["frames", "size", "mesh", "seconds", "folder"],
        [
            [
                summary.frames,
                f"{summary.width}×{summary.height}",
                f"{summary.vertices} vertices, {summary.faces} faces",
                f"{summary.seconds:.1f}",
                summary.out_dir,
            ]
        ],
    )


def _read_camera(path: Path) -> Intrinsics:
    """Intrinsics from a NICE-SLAM ``cam_params.json`` or an isg ``intrinsics.json``."""
    import json

    from inherit_sg.errors import DatasetError, FrameError
    from inherit_sg.ingest.readers.replica import read_cam_params
    from inherit_sg.model import Intrinsics

    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"camera file not found: {path}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: invalid JSON: {exc}") from None
    if isinstance(data, dict) and ("camera" in data or "w" in data):
        return read_cam_params(path)
    try:
        return Intrinsics.from_dict(data)
    except (FrameError, TypeError, AttributeError) as exc:
        raise DatasetError(f"{path}: not camera intrinsics: {exc}") from None


def _with_progress(as_json: bool, work: Callable[[Progress], Summary]) -> Summary:
    """Run ``work`` with a frame progress bar on stderr (cleared when printing JSON)."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, TimeRemainingColumn
    from rich.progress import Progress as Bar

    columns = (
        "[progress.description]{task.description}",
        BarColumn(),
        MofNCompleteColumn(),
        TimeRemainingColumn(),
    )
    with Bar(*columns, console=Console(stderr=True), transient=as_json) as bar:
        task = bar.add_task("rendering frames", total=None)

        def progress(done: int, total: int) -> None:
            bar.update(task, completed=done, total=total)

        return work(progress)


def _report(summary: DatasetSummary, as_json: bool) -> None:
    if as_json:
        print_json(summary.to_dict())
        return
    print_table(
        ["floors", "rooms", "objects", "frames", "seconds", "noise", "size"],
        [
            [
                summary.floors,
                summary.rooms,
                summary.objects,
                summary.frames,
                f"{summary.seconds:.1f}",
                summary.noise,
                f"{summary.width}x{summary.height}",
            ]
        ],
        title=f"dataset written to {summary.out_dir}",
    )
