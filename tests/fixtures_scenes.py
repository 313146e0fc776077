"""Hand-built ground-truth scenes for the truth and query-generator tests.

``small_scene`` places a few objects by hand so that each spatial predicate has a known
answer; ``house_scene`` lays out a two-floor house procedurally (a grid of rectangular
rooms filled from ``AREA_TEMPLATES``) that is big enough for a full query set.
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field

from inherit_sg.ingest.synthetic.scene import (
    AreaGT,
    DoorGT,
    FloorGT,
    ObjectGT,
    RoomGT,
    Scene,
    StairsGT,
)
from inherit_sg.ingest.synthetic.vocabulary import AREA_TEMPLATES, OBJECT_KINDS

FLOOR_HEIGHT = 3.0


def _rect(x0: float, y0: float, x1: float, y1: float) -> list[list[float]]:
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


@dataclass
class _Builder:
    scene: Scene
    areas: dict[str, AreaGT] = field(default_factory=dict)

    def add(
        self,
        oid: str,
        label: str,
        room: str | None,
        floor: int,
        xy: tuple[float, float],
        dims: tuple[float, float, float],
        z0: float = 0.0,
        *,
        area: str | None = None,
        on: str | None = None,
        structural: bool = False,
        attrs: dict[str, str] | None = None,
    ) -> ObjectGT:
        base = floor * FLOOR_HEIGHT + z0
        w, d, h = dims
        obj = ObjectGT(
            id=oid,
            instance_id=len(self.scene.objects) + 1,
            label=label,
            room_id=room,
            floor=floor,
            centroid=[xy[0], xy[1], base + h / 2],
            bbox_min=[xy[0] - w / 2, xy[1] - d / 2, base],
            bbox_max=[xy[0] + w / 2, xy[1] + d / 2, base + h],
            area_id=area,
            attributes=dict(attrs or {}),
            supported_by=on,
            structural=structural,
        )
        self.scene.objects.append(obj)
        if area is not None:
            self.areas[area].object_ids.append(oid)
        return obj

    def area(self, aid: str, label: str, room: str) -> None:
        self.areas[aid] = AreaGT(aid, label, room)
        self.scene.areas.append(self.areas[aid])


# id, label, room, centre xy, (w, d, h), bottom above floor, area, support, "colour material size"
SMALL_OBJECTS: tuple[
    tuple[str, str, str, tuple[float, float], tuple[float, float, float], float, str | None,
          str | None, str], ...
] = (
    ("t1", "table", "kitchen", (2.0, 2.0), (1.0, 0.7, 0.74), 0, "a_breakfast", None, "brown wood medium"),
    ("m1", "mug", "kitchen", (2.2, 2.0), (0.1, 0.1, 0.11), 0.74, "a_breakfast", "t1", "red ceramic medium"),
    ("c1", "chair", "kitchen", (2.9, 2.0), (0.5, 0.5, 0.9), 0, "a_breakfast", None, "blue wood large"),
    ("c2", "chair", "kitchen", (0.5, 3.5), (0.5, 0.5, 0.9), 0, "a_breakfast", None, "black metal medium"),
    ("f1", "refrigerator", "kitchen", (4.5, 0.5), (0.7, 0.7, 1.8), 0, "a_cooking", None, "white metal medium"),
    ("k1", "counter", "kitchen", (4.0, 3.6), (2.0, 0.6, 0.9), 0, "a_cooking", None, "grey stone medium"),
    ("m2", "mug", "kitchen", (3.5, 3.6), (0.1, 0.1, 0.11), 0.9, "a_cooking", "k1", "blue ceramic small"),
    ("w1", "window", "kitchen", (2.0, 3.95), (1.2, 0.1, 1.2), 0.9, None, None, "white glass -"),
    ("d1", "door", "kitchen", (5.0, 2.0), (0.1, 0.9, 2.05), 0, None, None, "white wood -"),
    ("s1", "sofa", "living", (7.5, 3.4), (2.0, 0.9, 0.85), 0, "a_tv", None, "grey fabric large"),
    ("ct1", "coffee table", "living", (7.5, 2.0), (1.1, 0.6, 0.42), 0, "a_tv", None, "brown wood medium"),
    ("r1", "rug", "living", (7.5, 2.0), (2.0, 1.4, 0.02), 0, "a_tv", None, "red fabric large"),
    ("m3", "mug", "living", (7.1, 2.0), (0.1, 0.1, 0.11), 0.42, "a_tv", "ct1", "white ceramic medium"),
    ("v1", "vase", "living", (7.5, 2.0), (0.18, 0.18, 0.35), 0.42, "a_tv", "ct1", "blue ceramic medium"),
    ("b1", "book", "living", (7.9, 2.0), (0.2, 0.15, 0.04), 0.42, "a_tv", "ct1", "green fabric medium"),
    ("l1", "lamp", "living", (9.0, 3.5), (0.4, 0.4, 1.6), 0, "a_reading", None, "black metal medium"),
    ("t2", "table", "living", (6.0, 0.5), (1.0, 0.7, 0.74), 0, None, None, "white metal small"),
    ("l2", "lamp", "living", (6.85, 0.5), (0.4, 0.4, 1.6), 0, None, None, "yellow metal medium"),
    ("a1", "armchair", "living", (9.3, 1.0), (0.85, 0.85, 0.9), 0, "a_reading", None, "green leather medium"),
    ("p1", "plant", "living", (8.4, 2.2), (0.45, 0.45, 1.1), 0, "a_reading", None, "green ceramic medium"),
    ("bd1", "bed", "bedroom", (2.5, 3.0), (1.6, 2.0, 0.55), 0, "a_sleep", None, "white wood large"),
    ("pt1", "painting", "bedroom", (2.5, 3.98), (0.9, 0.04, 0.6), 1.3, None, None, "blue wood medium"),
    ("n1", "nightstand", "bedroom", (1.3, 3.7), (0.45, 0.4, 0.55), 0, "a_sleep", None, "brown wood medium"),
    ("tl1", "table lamp", "bedroom", (1.3, 3.7), (0.25, 0.25, 0.45), 0.55, "a_sleep", "n1", "white ceramic medium"),
    ("c3", "chair", "bedroom", (4.5, 0.5), (0.5, 0.5, 0.9), 0, None, None, "red plastic small"),
    ("l3", "lamp", "bedroom", (0.3, 0.3), (0.4, 0.4, 1.6), 0, None, None, "white metal medium"),
    ("sk1", "sink", "bathroom", (6.0, 3.7), (0.6, 0.5, 0.9), 0, "a_wash", None, "white ceramic medium"),
    ("mr1", "mirror", "bathroom", (6.0, 3.98), (0.6, 0.04, 0.9), 1.0, "a_wash", None, "grey glass medium"),
    ("tt1", "toilet", "bathroom", (8.0, 3.6), (0.4, 0.65, 0.8), 0, None, None, "white ceramic medium"),
)  # fmt: skip


def small_scene() -> Scene:
    """Two floors, four rooms, ~30 objects placed so every predicate has a known answer.

    Floor 0: kitchen (x 0–5) with table t1 + mug m1 on it, chair c1 next to t1, chair c2
    far from it, counter k1 next to window w1 with mug m2 on it; living room (x 5–10) with
    sofa s1, coffee table ct1 on rug r1, mug m3 / vase v1 / book b1 in a row on ct1, lamp l1
    beside the sofa, lamp l2 next to table t2, plant p1 between sofa and armchair a1.
    Floor 1: bedroom with bed bd1 under painting pt1, nightstand n1 + table lamp tl1, chair
    c3, lamp l3; bathroom with sink sk1 under mirror mr1 and toilet tt1.
    """
    scene = Scene(name="small", seed=None)
    scene.floors = [FloorGT(0, 0.0, FLOOR_HEIGHT), FloorGT(1, FLOOR_HEIGHT, FLOOR_HEIGHT)]
    scene.rooms = [
        RoomGT("kitchen", "kitchen", 0, _rect(0, 0, 5, 4), "kitchen"),
        RoomGT("living", "living room", 0, _rect(5, 0, 10, 4), "living room"),
        RoomGT("bedroom", "bedroom", 1, _rect(0, 0, 5, 4), "bedroom"),
        RoomGT("bathroom", "bathroom", 1, _rect(5, 0, 10, 4), "bathroom"),
    ]
    b = _Builder(scene)
    for aid, label, room in (
        ("a_breakfast", "breakfast area", "kitchen"),
        ("a_cooking", "cooking area", "kitchen"),
        ("a_tv", "tv area", "living"),
        ("a_reading", "reading corner", "living"),
        ("a_sleep", "sleeping area", "bedroom"),
        ("a_wash", "washing area", "bathroom"),
    ):
        b.area(aid, label, room)
    for oid, label, room, xy, dims, z0, area, on, looks in SMALL_OBJECTS:
        floor = 1 if room in ("bedroom", "bathroom") else 0
        colour, material, size = looks.split()
        attrs = {"colour": colour, "material": material}
        if size != "-":
            attrs["size"] = size
        structural = label in ("door", "window")
        b.add(
            oid,
            label,
            room,
            floor,
            xy,
            dims,
            z0,
            area=area,
            on=on,
            structural=structural,
            attrs=attrs,
        )
    scene.doors = [DoorGT("door1", 0, [5.0, 2.0, 0.0], 0.9, ["kitchen", "living"])]
    scene.stairs = [StairsGT("st1", 0, [9.5, 0.5, 0.0], [9.5, 3.5, 3.0], _rect(9, 0, 10, 4))]
    return scene


# Two floors of 3 x 2 rooms, each ROOM_W x ROOM_D metres.
HOUSE_ROOMS = (
    ("kitchen", "living room", "dining room", "hallway", "bathroom", "garage"),
    ("bedroom", "bedroom", "bathroom", "office", "hallway", "laundry room"),
)
ROOM_W, ROOM_D = 6.0, 5.0
GAP = 0.3
SCALES = {"small": 0.9, "medium": 1.0, "large": 1.1}


def house_scene(seed: int = 0) -> Scene:
    """A deterministic two-floor, twelve-room house with ~140 objects (incl. doors, windows)."""
    rng = random.Random(seed)
    scene = Scene(name=f"house-{seed}", seed=seed)
    scene.floors = [FloorGT(i, i * FLOOR_HEIGHT, FLOOR_HEIGHT) for i in range(len(HOUSE_ROOMS))]
    b = _Builder(scene)
    counts: dict[str, int] = {}
    for floor, types in enumerate(HOUSE_ROOMS):
        for slot, room_type in enumerate(types):
            counts[room_type] = counts.get(room_type, 0) + 1
            same = sum(1 for f in HOUSE_ROOMS for t in f if t == room_type)
            name = f"{room_type} {counts[room_type]}" if same > 1 else room_type
            x0, y0 = (slot % 3) * ROOM_W, (slot // 3) * ROOM_D
            rid = f"f{floor}_r{slot}"
            scene.rooms.append(
                RoomGT(rid, room_type, floor, _rect(x0, y0, x0 + ROOM_W, y0 + ROOM_D), name)
            )
            _furnish(b, rng, rid, room_type, floor, x0, y0)
            wy = y0 + 0.05 if slot < 3 else y0 + ROOM_D - 0.05
            b.add(
                f"{rid}_window",
                "window",
                rid,
                floor,
                (x0 + ROOM_W / 2 + 1.0, wy),
                (1.2, 0.1, 1.2),
                0.9,
                structural=True,
                attrs={"colour": "white", "material": "glass"},
            )
        for left in (0, 1, 3, 4):
            lid, rid = f"f{floor}_r{left}", f"f{floor}_r{left + 1}"
            x, y = (left % 3 + 1) * ROOM_W, (left // 3) * ROOM_D + 1.0
            b.add(
                f"{lid}_door",
                "door",
                lid,
                floor,
                (x, y),
                (0.1, 0.9, 2.05),
                structural=True,
                attrs={"colour": "white", "material": "wood"},
            )
            scene.doors.append(
                DoorGT(f"{lid}_d", floor, [x, y, floor * FLOOR_HEIGHT], 0.9, [lid, rid])
            )
    hall = (ROOM_W * 1.5, ROOM_D * 1.5)
    scene.stairs.append(
        StairsGT(
            "stairs0",
            0,
            [hall[0], hall[1] - 1.5, 0.0],
            [hall[0], hall[1] + 1.5, FLOOR_HEIGHT],
            _rect(hall[0] - 0.5, hall[1] - 1.5, hall[0] + 0.5, hall[1] + 1.5),
        )
    )
    return scene


def _furnish(
    b: _Builder, rng: random.Random, rid: str, room_type: str, floor: int, x0: float, y0: float
) -> None:
    groups = list(AREA_TEMPLATES[room_type].items())
    cols = 2 if len(groups) > 1 else 1
    rows = 2 if len(groups) > 2 else 1
    cw, cd = ROOM_W / cols, ROOM_D / rows
    for i, (label, members) in enumerate(groups):
        aid = f"{rid}_a{i}"
        b.area(aid, label, rid)
        col, row = i % cols, i // cols
        cx, cy = x0 + (col + 0.5) * cw, y0 + (row + 0.5) * cd
        wall_y = y0 + ROOM_D - 0.02 if row == rows - 1 else y0 + 0.02
        _place_group(b, rng, aid, rid, floor, members, (cx, cy), wall_y)


def _place_group(
    b: _Builder,
    rng: random.Random,
    aid: str,
    rid: str,
    floor: int,
    members: tuple[str, ...],
    centre: tuple[float, float],
    wall_y: float,
) -> None:
    placed: list[ObjectGT] = []
    surfaces: list[ObjectGT] = []
    smalls: list[tuple[str, tuple[float, float, float], dict[str, str]]] = []
    anchor: ObjectGT | None = None
    ring = 0
    for n, label in enumerate(members):
        kind = OBJECT_KINDS[label]
        size_word = rng.choice(("small", "medium", "large"))
        s = SCALES[size_word]
        size = (kind.size[0] * s, kind.size[1] * s, kind.size[2] * s)
        attrs = {
            "colour": rng.choice(kind.colours),
            "material": rng.choice(kind.materials),
            "size": size_word,
        }
        oid = f"{aid}_o{n}"
        if kind.small:
            smalls.append((label, size, attrs))
            continue
        if kind.mount_height > 0:
            b.add(
                oid,
                label,
                rid,
                floor,
                (centre[0] + 0.6, wall_y),
                size,
                kind.mount_height,
                area=aid,
                attrs=attrs,
            )
            continue
        if label == "rug":
            under = next((p for p in placed if OBJECT_KINDS[p.label].surface), anchor)
            xy = (under.centroid[0], under.centroid[1]) if under is not None else centre
            b.add(oid, label, rid, floor, xy, size, area=aid, attrs=attrs)
            continue
        if anchor is None:
            obj = b.add(oid, label, rid, floor, centre, size, area=aid, attrs=attrs)
            anchor = obj
        else:
            obj = b.add(
                oid, label, rid, floor, _ring_xy(anchor, size, ring), size, area=aid, attrs=attrs
            )
            ring += 1
        placed.append(obj)
        if OBJECT_KINDS[label].surface:
            surfaces.append(obj)
    _place_smalls(b, aid, rid, floor, smalls, surfaces, anchor, centre, ring)


def _ring_xy(anchor: ObjectGT, size: tuple[float, float, float], ring: int) -> tuple[float, float]:
    """Slots around the anchor: front, right, left, back, then a wider ring."""
    ax, ay = anchor.centroid[0], anchor.centroid[1]
    hw = (anchor.bbox_max[0] - anchor.bbox_min[0]) / 2
    hd = (anchor.bbox_max[1] - anchor.bbox_min[1]) / 2
    dx = hw + GAP + size[0] / 2 + (ring // 4) * (size[0] + GAP)
    dy = hd + GAP + size[1] / 2 + (ring // 4) * (size[1] + GAP)
    return [(ax, ay - dy), (ax + dx, ay), (ax - dx, ay), (ax, ay + dy)][ring % 4]


def _place_smalls(
    b: _Builder,
    aid: str,
    rid: str,
    floor: int,
    smalls: list[tuple[str, tuple[float, float, float], dict[str, str]]],
    surfaces: list[ObjectGT],
    anchor: ObjectGT | None,
    centre: tuple[float, float],
    ring: int,
) -> None:
    per: dict[str, int] = {}
    for n, (label, size, attrs) in enumerate(smalls):
        oid = f"{aid}_s{n}"
        if not surfaces:
            xy = _ring_xy(anchor, size, ring + n) if anchor is not None else centre
            b.add(oid, label, rid, floor, xy, size, area=aid, attrs=attrs)
            continue
        surf = surfaces[n % len(surfaces)]
        k = per.get(surf.id, 0)
        per[surf.id] = k + 1
        slots = max(1, sum(1 for i in range(len(smalls)) if i % len(surfaces) == n % len(surfaces)))
        width = surf.bbox_max[0] - surf.bbox_min[0]
        x = surf.bbox_min[0] + (k + 0.5) * width / slots
        top = surf.bbox_max[2] - floor * FLOOR_HEIGHT
        b.add(
            oid,
            label,
            rid,
            floor,
            (x, surf.centroid[1]),
            size,
            top,
            area=aid,
            on=surf.id,
            attrs=attrs,
        )
