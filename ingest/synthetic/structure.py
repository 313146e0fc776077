"""Objects that are part of the building: door frames, windows and staircases."""

from __future__ import annotations

import numpy as np

from ingest.synthetic.placement import Placed
from ingest.synthetic.plan import STAIR_WIDTH, WALL_T, HousePlan, Opening
from ingest.synthetic.vocabulary import OBJECT_KINDS

JAMB = 0.06  # width of a door or window frame member


def _opening_object(opening: Opening, z_floor: float, colour: str, material: str) -> Placed:
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
    )


def structural_objects(plan: HousePlan, rng: np.random.Generator) -> list[Placed]:
    """Door frames, windows and stairs of the whole house."""
    out: list[Placed] = []
    door_kind = OBJECT_KINDS["door"]
    for floor in plan.floors:
        colour = str(rng.choice(door_kind.colours))
        for door in floor.doors:
            out.append(_opening_object(door, floor.z, colour, "wood"))
        for window in floor.windows:
            out.append(_opening_object(window, floor.z, "white", "glass"))
    stair_kind = OBJECT_KINDS["stairs"]
    for stairs in plan.stairs:
        r = stairs.rect
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
                colour=str(rng.choice(stair_kind.colours)),
                material=str(rng.choice(stair_kind.materials)),
                structural=True,
                params={"n_steps": stairs.n_steps, "stairs": stairs.id},
            )
        )
    return out
