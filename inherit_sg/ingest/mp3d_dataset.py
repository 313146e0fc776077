"""A Matterport3D ``.house`` file as a renderable world with a walk and ground truth.

:func:`load_house_world` parses the file, plans walls and openings, builds the mesh and
the room lights; :func:`write_house_dataset` renders the walk into an isg folder through
the same frame pipeline as generated houses (noise model, per-frame instance ids,
``scene.json``, visibility, walk truth, queries and conversations).

Coordinates stay the file's own (z-up metres): object centroids in ``scene.json`` are
the ``O`` lines' box centres, camera poses are in the same frame. The ground truth adds
what the world builder decided: each object's rendered colour name (``colour``
attribute), how its box was adjusted to be seen (``drawn`` attribute, only when it was:
see :mod:`inherit_sg.ingest.mp3d_drawn`) and every opening between rooms as a door (``DoorGT``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from inherit_sg.errors import DatasetError, InputError
from inherit_sg.ingest.mp3d_drawn import Drawn, drawn_objects
from inherit_sg.ingest.mp3d_house import HouseFile, parse_house
from inherit_sg.ingest.mp3d_space import Level, LevelSpace, blocks_walking, house_levels
from inherit_sg.ingest.mp3d_walk import plan_house_walk
from inherit_sg.ingest.mp3d_walls import WallPlan, plan_walls
from inherit_sg.ingest.mp3d_world import build_house_world, colour_name, house_lights
from inherit_sg.ingest.synthetic.generate import WALK_STREAM, DatasetSummary, Progress, write_walk
from inherit_sg.ingest.synthetic.render import RoomLights
from inherit_sg.ingest.synthetic.scene import DoorGT, Scene
from inherit_sg.ingest.synthetic.trajectory import Trajectory
from inherit_sg.ingest.synthetic.world import WorldMesh


@dataclass
class HouseWorld:
    """A parsed house with everything needed to walk and render it."""

    source: Path
    house: HouseFile
    levels: list[Level]
    spaces: list[LevelSpace]
    walls: WallPlan
    world: WorldMesh
    lights: RoomLights
    drawn: dict[str, Drawn] = field(default_factory=dict)  # object id -> boxes drawn

    @property
    def scene(self) -> Scene:
        """Ground truth (the parsed scene, completed by :func:`load_house_world`)."""
        return self.house.scene

    def trajectory(self, seed: int = 0) -> Trajectory:
        """The exploration walk, deterministic by ``seed``."""
        if seed < 0:
            raise InputError(f"seed must be a non-negative integer, got {seed}")
        rng = np.random.default_rng([seed, WALK_STREAM])
        return plan_house_walk(self.levels, self.spaces, self.walls.walls, rng)


def _complete_scene(
    scene: Scene, walls: WallPlan, levels: list[Level], drawn: dict[str, Drawn]
) -> None:
    for obj in scene.objects:
        obj.attributes.setdefault("colour", colour_name(obj.label))
        note = drawn[obj.id].note if obj.id in drawn else ""
        if note:
            obj.attributes["drawn"] = note
    floor_of = {room_id: lv for lv in levels for room_id in lv.outlines}
    scene.doors = []
    for k, opening in enumerate(walls.openings):
        level = floor_of[opening.rooms[0]]
        x, y = (round(float(v), 4) for v in opening.centre)
        scene.doors.append(
            DoorGT(
                id=f"d{k}",
                floor=level.index,
                position=[x, y, round(level.z, 4)],
                width=round(opening.width, 4),
                rooms=list(opening.rooms),
            )
        )


def _block_extended(house: HouseFile, spaces: list[LevelSpace], drawn: dict[str, Drawn]) -> None:
    """Boxes drawn larger than annotated block the walk where they now stand."""
    space_of = {s.level.index: s for s in spaces}
    for obj in house.scene.objects:
        space = space_of.get(obj.floor)
        d = drawn.get(obj.id)
        if space is None or d is None or not any(n.startswith("proud") for n in d.notes):
            continue
        if blocks_walking(obj.label, obj.bbox_min[2], space.level.z):
            space.block([part.corners() for part in d.parts])


def load_house_world(path: str | Path) -> HouseWorld:
    """Parse a ``.house`` file and build its world; DatasetError when it has no region
    with a usable outline."""
    source = Path(path)
    house = parse_house(source)
    levels = house_levels(house)
    if not levels:
        raise DatasetError(f"{source}: no region belongs to a level")
    spaces = [LevelSpace(house, level) for level in levels]
    walls = plan_walls(house, levels, spaces)
    drawn = drawn_objects(house, levels, spaces, walls)
    _block_extended(house, spaces, drawn)
    world = build_house_world(house, levels, walls, drawn)
    _complete_scene(house.scene, walls, levels, drawn)
    return HouseWorld(source, house, levels, spaces, walls, world, house_lights(levels), drawn)


def write_house_dataset(
    house: HouseWorld,
    out_dir: str | Path,
    *,
    seed: int = 0,
    noise: str = "clean",
    width: int = 640,
    height: int = 480,
    progress: Progress | None = None,
    workers: int | None = None,
    max_frames: int | None = None,
    shadows: bool = False,
) -> DatasetSummary:
    """Walk ``house``, render every pose and write an isg folder with ground truth
    (arguments as in :func:`inherit_sg.ingest.synthetic.generate.write_dataset`)."""
    return write_walk(
        house.world,
        house.lights,
        house.scene,
        house.trajectory(seed),
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
