"""Top-level pipeline: generate a house, walk it, render every pose and write an isg
dataset folder (intrinsics, poses, frames, ground-truth ``scene.json``).

:func:`write_walk` is the world-agnostic part (any mesh, lights, scene and walk: MP3D
houses use it too); :func:`render_frame` is the per-frame render + noise step.

Everything is deterministic by seed: the same seed gives a byte-identical
``scene.json`` and identical frames. Rendering runs in worker processes when more than
one core is available; frames are written in order by the calling process.
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.errors import InputError
from inherit_sg.ingest.isg import IsgWriter
from inherit_sg.ingest.synthetic.furnish import AreaPlan, furnish
from inherit_sg.ingest.synthetic.ground_truth_files import VisibilityLog, write_ground_truth_extras
from inherit_sg.ingest.synthetic.house_truth import build_scene
from inherit_sg.ingest.synthetic.layout import MAX_FLOORS, MAX_ROOMS, MIN_ROOMS, STYLES, plan_house
from inherit_sg.ingest.synthetic.noise import (
    NoiseConfig,
    PoseDrift,
    degrade_depth,
    degrade_instances,
    noise_config,
    renumber,
)
from inherit_sg.ingest.synthetic.placement import Placed
from inherit_sg.ingest.synthetic.plan import HousePlan
from inherit_sg.ingest.synthetic.render import Renderer, RoomLights
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.ingest.synthetic.trajectory import Trajectory, plan_trajectory
from inherit_sg.ingest.synthetic.world import WorldMesh, build_world
from inherit_sg.model import Intrinsics, Pose

HFOV_FX_640 = 350.0  # fx at 640 px width: a horizontal field of view of about 85°
WALK_STREAM, FRAME_STREAM, DRIFT_STREAM = 2, 3, 5  # seed streams

Progress = Callable[[int, int], None]


@dataclass
class House:
    """A generated house: plan, objects, ground truth and the triangle mesh to render."""

    seed: int
    plan: HousePlan
    objects: list[Placed]
    areas: list[AreaPlan]
    scene: Scene
    world: WorldMesh

    def trajectory(self, seed: int | None = None, close: bool = True) -> Trajectory:
        """The exploration walk (deterministic by ``seed``, default the house seed);
        ``close`` off leaves out the close looks and ceiling glances."""
        rng = np.random.default_rng([self.seed if seed is None else seed, WALK_STREAM])
        return plan_trajectory(self.plan, self.objects, rng, close=close)


@dataclass
class DatasetSummary:
    """What :func:`write_dataset` wrote."""

    out_dir: str
    floors: int
    rooms: int
    objects: int
    frames: int
    seconds: float
    noise: str
    width: int
    height: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return asdict(self)


def generate_house(
    seed: int,
    floors: int,
    rooms_per_floor: int | None = None,
    *,
    style: str = "real",
    open_plan: bool | None = None,
) -> House:
    """A procedural house with ``floors`` storeys and ``rooms_per_floor`` rooms each
    (hallway included; random 5–8 when None).

    ``style`` "real" (default) draws Matterport3D room types in realistic proportions,
    open-plan ground floors, the real-world object catalogue and continuous colours;
    "classic" is the earlier generator (nine room types, a twelve-colour palette).
    ``open_plan`` True forces an open-plan ground floor (where the rooms allow it), False
    gives walled rooms only (no open border anywhere); None draws it, about two houses
    in five. The classic style has none.
    """
    if seed < 0:
        raise InputError(f"seed must be a non-negative integer, got {seed}")
    if not 1 <= floors <= MAX_FLOORS:
        raise InputError(f"floors must be between 1 and {MAX_FLOORS}, got {floors}")
    if rooms_per_floor is not None and not MIN_ROOMS <= rooms_per_floor <= MAX_ROOMS:
        raise InputError(
            f"rooms per floor must be between {MIN_ROOMS} and {MAX_ROOMS}, got {rooms_per_floor}"
        )
    if style not in STYLES:
        raise InputError(f"style must be one of {', '.join(STYLES)}, got {style!r}")
    plan = plan_house(np.random.default_rng([seed, 0]), floors, rooms_per_floor, style, open_plan)
    furnishing = furnish(plan, np.random.default_rng([seed, 1]), style)
    world = build_world(plan, furnishing.objects, np.random.default_rng([seed, 4]))
    scene = build_scene(f"synthetic house {seed}", seed, plan, furnishing, style)
    return House(seed, plan, furnishing.objects, furnishing.areas, scene, world)


def make_intrinsics(width: int = 640, height: int = 480) -> Intrinsics:
    """Pinhole intrinsics like an HM3D walk's camera, scaled to ``width``."""
    if width < 16 or height < 16:
        raise InputError(f"image size must be at least 16x16, got {width}x{height}")
    f = HFOV_FX_640 * width / 640.0
    return Intrinsics(width, height, f, f, (width - 1) / 2.0, (height - 1) / 2.0, 1000.0)


# Worker-process state: one renderer per process.
_RENDERER: Renderer | None = None


def _init_worker(
    world: WorldMesh, lights: HousePlan | RoomLights, intrinsics: Intrinsics, shadows: bool
) -> None:
    global _RENDERER
    _RENDERER = Renderer(world, lights, intrinsics, shadows=shadows)


FrameResult = tuple[int, np.ndarray, np.ndarray, np.ndarray, dict[int, str], dict[int, int]]


def render_frame(
    renderer: Renderer,
    index: int,
    pose: Pose,
    seed: int,
    config: NoiseConfig,
    labels: dict[int, str],
) -> FrameResult:
    """Render walk frame ``index`` and pass it through the perception noise model.

    Returns (index, rgb, depth, per-frame renumbered instance ids, their labels, true
    instance id -> visible pixels). Deterministic by (``seed``, ``index``).
    """
    out = renderer.render(pose)
    rng = np.random.default_rng([seed, FRAME_STREAM, index])
    true_ids, pixels = np.unique(out.instances, return_counts=True)
    visible = {int(k): int(n) for k, n in zip(true_ids, pixels, strict=True) if k != 0}
    present = {k: labels[k] for k in visible}
    ids, frame_labels = degrade_instances(out.instances, present, config, rng)
    ids16, frame_labels = renumber(ids, frame_labels, rng)
    depth = degrade_depth(out.depth, config, rng)
    return index, out.rgb, depth, ids16, frame_labels, visible


def _render_job(job: tuple[int, Pose, int, NoiseConfig, dict[int, str]]) -> FrameResult:
    assert _RENDERER is not None
    return render_frame(_RENDERER, *job)


def _frames(
    world: WorldMesh,
    lights: HousePlan | RoomLights,
    intrinsics: Intrinsics,
    jobs: list[Any],
    workers: int,
    shadows: bool,
) -> Iterator[FrameResult]:
    if workers <= 1:
        _init_worker(world, lights, intrinsics, shadows)
        yield from map(_render_job, jobs)
        return
    # Forking a process that already runs LanceDB's async runtime can deadlock the
    # child; start clean workers then (slower start, same frames).
    context = multiprocessing.get_context("forkserver" if "lancedb" in sys.modules else None)
    with ProcessPoolExecutor(
        max_workers=workers,
        initializer=_init_worker,
        initargs=(world, lights, intrinsics, shadows),
        mp_context=context,
    ) as pool:
        yield from pool.map(_render_job, jobs, chunksize=4)


def write_dataset(
    house: House,
    out_dir: str | Path,
    *,
    noise: str = "clean",
    width: int = 640,
    height: int = 480,
    seed: int | None = None,
    progress: Progress | None = None,
    workers: int | None = None,
    max_frames: int | None = None,
    shadows: bool = False,
    close_looks: bool = True,
) -> DatasetSummary:
    """Walk ``house``, render every pose and write an isg folder with ``scene.json``.

    ``seed`` drives the walk and the noise (default: the house seed); ``progress`` is
    called with (frames done, total); ``workers`` is the number of render processes
    (default: one per core, at most 4); ``max_frames`` keeps only the start of the walk
    (quick demos); ``shadows`` casts shadow rays towards each room's light (slower);
    ``close_looks`` off walks only from room to room with look-arounds (about half the
    frames; small things far from the look-around spots stay unseen).
    """
    seed = house.seed if seed is None else seed
    return write_walk(
        house.world,
        house.plan,
        house.scene,
        house.trajectory(seed, close=close_looks),
        out_dir,
        seed=seed,
        noise=noise,
        width=width,
        height=height,
        progress=progress,
        workers=workers,
        max_frames=max_frames,
        shadows=shadows,
    )


def write_walk(
    world: WorldMesh,
    lights: HousePlan | RoomLights,
    scene: Scene,
    traj: Trajectory,
    out_dir: str | Path,
    *,
    seed: int,
    noise: str = "clean",
    width: int = 640,
    height: int = 480,
    progress: Progress | None = None,
    workers: int | None = None,
    max_frames: int | None = None,
    shadows: bool = False,
    intrinsics: Intrinsics | None = None,
) -> DatasetSummary:
    """Render the walk ``traj`` through ``world`` and write an isg folder: frames, poses,
    ``scene.json`` and the ground-truth extras (visibility, walk truth, queries).

    Shared by generated houses and MP3D houses; the arguments after ``out_dir`` are as in
    :func:`write_dataset` (``intrinsics`` defaults to :func:`make_intrinsics`).
    """
    config = noise_config(noise)
    intrinsics = make_intrinsics(width, height) if intrinsics is None else intrinsics
    start = time.perf_counter()
    out = Path(out_dir)
    poses = traj.poses[:max_frames] if max_frames is not None else traj.poses
    drift = PoseDrift(config, np.random.default_rng([seed, DRIFT_STREAM]))
    written_poses = [drift.apply(p) for p in poses]
    labels = {o.instance_id: o.label for o in scene.objects}
    jobs = [(i, pose, seed, config, labels) for i, pose in enumerate(poses)]
    n_workers = workers if workers is not None else min(4, os.cpu_count() or 1)
    seen = VisibilityLog(intrinsics.width * intrinsics.height)
    with IsgWriter(out, intrinsics) as writer:
        scene.save(out)
        for index, rgb, depth, ids, frame_labels, visible in _frames(
            world, lights, intrinsics, jobs, n_workers, shadows
        ):
            writer.write(f"{index:06d}", rgb, depth, written_poses[index], ids, frame_labels)
            seen.add(visible)
            if progress is not None:
                progress(index + 1, len(jobs))
    instance_to_object = {o.instance_id: o.id for o in scene.objects}
    write_ground_truth_extras(
        out,
        scene,
        seed,
        visibility=seen.by_object(instance_to_object),
        frame_floors=list(traj.floors[: len(jobs)]),
        frame_rooms=list(traj.rooms[: len(jobs)]),
    )
    return DatasetSummary(
        out_dir=str(out),
        floors=len(scene.floors),
        rooms=len(scene.rooms),
        objects=len(scene.objects),
        frames=len(jobs),
        seconds=round(time.perf_counter() - start, 3),
        noise=noise,
        width=intrinsics.width,
        height=intrinsics.height,
    )
