"""Objects that are part of the building: door frames, windows and staircases."""

from __future__ import annotations

import numpy as np

from inherit_sg.ingest.synthetic.colour_models import palette_for, sample_colour
from inherit_sg.ingest.synthetic.colour_naming import colour_term
from inherit_sg.ingest.synthetic.placement import Placed
from inherit_sg.ingest.synthetic.plan import STAIR_WIDTH, WALL_T, HousePlan, Opening
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

JAMB = 0.06  # width of a door or window frame member


def _opening_object(
    opening: Opening,
    z_floor: float,
    colour: str,
    material: str,
    rgb: tuple[int, int, int] | None = None,
) -> Placed:
    x, y = opening.center_xy
    kind = OBJECT_KINDS[opening.kind]
    return Placed(
        label=opening.kind,
        floor=opening.floor,
        room_id=opening.rooms[0],
        x=round(x, 4),
        y=round(y, 4),
        z=round(z_floor + opening.z0, 4),
        dims=(round(opening.width, 4), WALL_T + 0.04, round(opening.z1 - opening.z0, 4)),
        quarter=0 if opening.axis == "x" else 1,
        colour=colour,
        material=material,
        scale=round(opening.width / kind.size[0], 3),
        structural=True,
        params={"jamb": JAMB, "opening": opening.id},
        rgb=rgb,
        raw=opening.kind,
    )


def _look(
    palette: str, material: str, rng: np.random.Generator
) -> tuple[str, tuple[int, int, int]]:
    """A sampled colour (name, sRGB) of a real-world structural object."""
    rgb = sample_colour(palette_for(palette, material), rng)
    return colour_term(rgb), rgb


def structural_objects(
    plan: HousePlan, rng: np.random.Generator, style: str = "classic"
) -> list[Placed]:
    """Door frames, windows and stairs of the whole house; ``style`` "real" samples
    their colours continuously, "classic" from the named palette."""
    real = style == "real"
    out: list[Placed] = []
    door_kind = OBJECT_KINDS["door"]
    for floor in plan.floors:
        if real:
            door_palette = "white" if rng.random() < 0.6 else "natural wood"
            colour, rgb = _look(door_palette, "wood", rng)
        else:
            colour, rgb = str(rng.choice(door_kind.colours)), None
        for door in floor.doors:
            out.append(_opening_object(door, floor.z, colour, "wood", rgb))
        frame = _look("white", "glass", rng) if real else ("white", None)
        for window in floor.windows:
            out.append(_opening_object(window, floor.z, frame[0], "glass", frame[1]))
    stair_kind = OBJECT_KINDS["stairs"]
    for stairs in plan.stairs:
        r = stairs.rect
        if real:
            material = str(rng.choice(stair_kind.materials))
            colour, rgb = _look("", material, rng)
        else:
            colour, rgb = str(rng.choice(stair_kind.colours)), None
            material = str(rng.choice(stair_kind.materials))
        out.append(
            Placed(
                label="stairs",
                floor=stairs.from_floor,
                room_id=stairs.room_bottom,
                x=round(r.cx, 4),
                y=round(r.cy, 4),
                z=stairs.z0,
                dims=(STAIR_WIDTH, round(r.h, 4), round(stairs.z1 - stairs.z0, 4)),
                quarter=0 if stairs.direction < 0 else 2,
                colour=colour,
                material=material,
                structural=True,
                params={"n_steps": stairs.n_steps, "stairs": stairs.id},
                rgb=rgb,
                raw="stairs",
            )
        )
    return out
