"""The ground-truth :class:`Scene` of a generated house (what ``scene.json`` holds)."""

from __future__ import annotations

from ingest.synthetic.furnish import Furnishing
from ingest.synthetic.placement import Placed, size_word
from ingest.synthetic.plan import HousePlan
from ingest.synthetic.scene import AreaGT, DoorGT, FloorGT, ObjectGT, RoomGT, Scene, StairsGT


def _r(values: tuple[float, ...] | list[float]) -> list[float]:
    return [round(float(v), 4) for v in values]


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
        attributes={"colour": obj.colour, "material": obj.material, "size": size_word(obj.scale)},
        supported_by=obj.support.id if obj.support is not None else None,
        structural=obj.structural,
    )


def build_scene(name: str, seed: int, plan: HousePlan, furnishing: Furnishing) -> Scene:
    """Ground truth of a planned and furnished house."""
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
