"""Paint for background surfaces: each room's walls, floor and ceiling get their own
finish; outside the house there is a facade and grass."""

from __future__ import annotations

import numpy as np

from inherit_sg.ingest.synthetic.plan import FloorPlan, HousePlan

WALL_PAINTS = (
    (232, 226, 212),
    (214, 222, 232),
    (226, 214, 200),
    (206, 218, 204),
    (236, 232, 226),
    (222, 208, 214),
)
FLOOR_FINISH = {
    "bathroom": (200, 200, 196),
    "kitchen": (190, 184, 172),
    "laundry room": (196, 196, 190),
    "garage": (150, 150, 146),
    "hallway": (150, 110, 75),
}
WOODS = ((150, 108, 70), (170, 130, 90), (120, 90, 60), (140, 130, 120))
CEILING = (244, 244, 240)
FACADE = (205, 195, 180)
GROUND = (95, 125, 70)


class Painter:
    """Colours background surfaces by the room they face."""

    def __init__(self, plan: HousePlan, rng: np.random.Generator) -> None:
        self.plan = plan
        self.wall: dict[str, tuple[int, int, int]] = {}
        self.floor: dict[str, tuple[int, int, int]] = {}
        for room in plan.all_rooms:
            self.wall[room.id] = WALL_PAINTS[int(rng.integers(len(WALL_PAINTS)))]
            wood = WOODS[int(rng.integers(len(WOODS)))]
            self.floor[room.id] = FLOOR_FINISH.get(room.type, wood)

    def colour(self, point: np.ndarray, normal: np.ndarray) -> tuple[int, int, int]:
        """sRGB colour of a background surface at ``point`` facing along ``normal``."""
        probe = point + normal * 0.05
        inside = self.plan.footprint.contains(float(probe[0]), float(probe[1]))
        if not inside:
            return GROUND if normal[2] > 0.5 and probe[2] < 0.05 else FACADE
        floor = self._floor_at(float(probe[2]))
        room = floor.room_at(float(probe[0]), float(probe[1])) if floor else None
        if room is None:
            return FACADE
        if normal[2] > 0.5:
            return self.floor[room.id]
        if normal[2] < -0.5:
            return CEILING
        return self.wall[room.id]

    def _floor_at(self, z: float) -> FloorPlan | None:
        for floor in self.plan.floors:
            if floor.z - 1e-3 <= z <= floor.z + floor.height + 1e-3:
                return floor
        return None
