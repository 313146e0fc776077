"""The ground-truth :class:`Scene` of a generated house (what ``scene.json`` holds)."""

from __future__ import annotations

from typing import Any

from inherit_sg.ingest.synthetic.furnish import Furnishing
from inherit_sg.ingest.synthetic.open_plan import open_neighbours
from inherit_sg.ingest.synthetic.placement import Placed, size_word
from inherit_sg.ingest.synthetic.plan import FloorPlan, HousePlan, RoomPlan
from inherit_sg.ingest.synthetic.scene import (
    AreaGT,
    DoorGT,
    FloorGT,
    ObjectGT,
    RoomGT,
    Scene,
    StairsGT,
)
from inherit_sg.ingest.synthetic.taxonomy import region_code
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS


def _r(values: tuple[float, ...] | list[float]) -> list[float]:
    return [round(float(v), 4) for v in values]


def _attributes(obj: Placed) -> dict[str, Any]:
    """Colour, material and size; for real-world houses also the sampled sRGB colour and
    the Matterport3D raw category name and 40-class grouping."""
    out: dict[str, Any] = {
        "colour": obj.colour,
        "material": obj.material,
        "size": size_word(obj.scale),
    }
    if obj.rgb is not None:
        out["rgb"] = [int(v) for v in obj.rgb]
        out["mp3d_category"] = obj.raw or obj.label
        out["mpcat40"] = OBJECT_KINDS[obj.label].mpcat40
    return out


def _room_attributes(room: RoomPlan, floor: FloorPlan, style: str) -> dict[str, Any]:
    """A real-world room's Matterport3D region code and the rooms it opens onto."""
    if style != "real":
        return {}
    out: dict[str, Any] = {"mp3d_code": region_code(room.type)}
    if room.open_group:
        out["open_group"] = room.open_group
        out["open_to"] = open_neighbours(floor, room.id)
    return out


def _object(obj: Placed, area_of: dict[int, str]) -> ObjectGT:
    box = obj.box
    lo = (box.rect.x0, box.rect.y0, box.z0)
    hi = (box.rect.x1, box.rect.y1, box.z1)
    return ObjectGT(
        id=obj.id,
        instance_id=obj.instance_id,
        label=obj.label,
        room_id=obj.room_id,
        floor=obj.floor,
        centroid=_r([(a + b) / 2 for a, b in zip(lo, hi, strict=True)]),
        bbox_min=_r(lo),
        bbox_max=_r(hi),
        area_id=area_of.get(id(obj)),
        attributes=_attributes(obj),
        supported_by=obj.support.id if obj.support is not None else None,
        structural=obj.structural,
    )


def build_scene(
    name: str, seed: int, plan: HousePlan, furnishing: Furnishing, style: str = "classic"
) -> Scene:
    """Ground truth of a planned and furnished house (``style``: the generator's)."""
    area_of = {id(m): area.id for area in furnishing.areas for m in area.members}
    scene = Scene(name=name, seed=seed)
    for floor in plan.floors:
        scene.floors.append(
            FloorGT(index=floor.index, z=round(floor.z, 4), height=round(floor.height, 4))
        )
        for room in floor.rooms:
            scene.rooms.append(
                RoomGT(
                    id=room.id,
                    type=room.type,
                    floor=floor.index,
                    polygon=room.rect.polygon(),
                    name=room.name,
                    attributes=_room_attributes(room, floor, style),
                )
            )
        for door in floor.doors:
            x, y = door.center_xy
            scene.doors.append(
                DoorGT(
                    id=door.id,
                    floor=floor.index,
                    position=_r((x, y, floor.z)),
                    width=round(door.width, 4),
                    rooms=list(door.rooms),
                )
            )
    for stairs in plan.stairs:
        cx = stairs.rect.cx
        scene.stairs.append(
            StairsGT(
                id=stairs.id,
                from_floor=stairs.from_floor,
                bottom=_r((cx, stairs.y_bottom, stairs.z0)),
                top=_r((cx, stairs.y_top, stairs.z1)),
                footprint=stairs.rect.polygon(),
            )
        )
    for area in furnishing.areas:
        scene.areas.append(
            AreaGT(
                id=area.id,
                label=area.label,
                room_id=area.room_id,
                object_ids=[m.id for m in area.members],
            )
        )
    scene.objects = [_object(obj, area_of) for obj in furnishing.objects]
    return scene
