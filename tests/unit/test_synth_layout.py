"""Procedural houses: determinism, room counts, door connectivity, stairs."""

from __future__ import annotations

import json
from collections import deque

import numpy as np
import pytest

from inherit_sg.errors import InputError
from inherit_sg.ingest.synthetic.generate import generate_house
from inherit_sg.ingest.synthetic.geom import Rect
from inherit_sg.ingest.synthetic.layout import plan_house
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.ingest.synthetic.taxonomy import ROOM_TYPES


def _poly_rect(poly: list[list[float]]) -> Rect:
    xs, ys = [p[0] for p in poly], [p[1] for p in poly]
    return Rect(min(xs), min(ys), max(xs), max(ys))


def test_same_seed_gives_identical_scene_json(tmp_path):
    a = generate_house(11, 2)
    b = generate_house(11, 2)
    a.scene.save(tmp_path)
    first = (tmp_path / "scene.json").read_bytes()
    b.scene.save(tmp_path)
    assert (tmp_path / "scene.json").read_bytes() == first
    assert np.array_equal(a.world.vertices, b.world.vertices)
    other = generate_house(12, 2)
    assert json.dumps(other.scene.to_dict()) != json.dumps(a.scene.to_dict())


@pytest.mark.parametrize("rooms", [4, 7, 12, None])
def test_rooms_per_floor_in_range(rooms):
    for seed in range(4):
        plan = plan_house(np.random.default_rng(seed), 3, rooms)
        for floor in plan.floors:
            assert 4 <= len(floor.rooms) <= 12
            if rooms is not None:
                assert len(floor.rooms) == rooms
            assert floor.rooms[0].type == "hallway"
            # rooms tile the footprint without overlap
            area = sum(r.rect.area for r in floor.rooms)
            assert area == pytest.approx(plan.footprint.area, rel=1e-6)
            for i, a in enumerate(floor.rooms):
                assert min(a.rect.w, a.rect.h) >= 2.3
                for b in floor.rooms[i + 1 :]:
                    assert not a.rect.overlaps(b.rect)


def _reachable(scene: Scene, floor: int) -> set[str]:
    """Rooms of ``floor`` reachable from its first through doors and open borders."""
    rooms = [r.id for r in scene.rooms if r.floor == floor]
    links: dict[str, set[str]] = {r: set() for r in rooms}
    for door in scene.doors:
        if door.floor == floor and len(door.rooms) == 2:
            a, b = door.rooms
            links[a].add(b)
            links[b].add(a)
    for room in scene.rooms:
        if room.floor == floor:
            links[room.id] |= set(room.attributes.get("open_to", []))
    seen = {rooms[0]}
    todo = deque(seen)
    while todo:
        for nxt in links[todo.popleft()] - seen:
            seen.add(nxt)
            todo.append(nxt)
    return seen


@pytest.mark.parametrize(("seed", "style"), [(s, "real") for s in range(6)] + [(0, "classic")])
def test_every_room_reachable_through_doors(seed, style):
    scene = generate_house(seed, 3, style=style).scene
    for floor in scene.floors:
        rooms = {r.id for r in scene.rooms if r.floor == floor.index}
        assert _reachable(scene, floor.index) == rooms
    outside = [d for d in scene.doors if len(d.rooms) == 1]
    assert len(outside) == 1 and outside[0].floor == 0


def test_doors_lie_on_the_wall_between_their_rooms():
    scene = generate_house(3, 2).scene
    for door in scene.doors:
        for room_id in door.rooms:
            rect = _poly_rect(scene.room(room_id).polygon)
            x, y = door.position[:2]
            on_x = abs(x - rect.x0) < 1e-3 or abs(x - rect.x1) < 1e-3
            on_y = abs(y - rect.y0) < 1e-3 or abs(y - rect.y1) < 1e-3
            assert (on_x or on_y) and rect.contains(x, y)


def test_room_types_by_floor_and_names():
    scene = generate_house(5, 2, 6).scene
    ground = {r.type for r in scene.rooms if r.floor == 0}
    upper = {r.type for r in scene.rooms if r.floor == 1}
    assert {"kitchen", "living room", "hallway"} <= ground
    assert {"bedroom", "bathroom", "hallway"} <= upper
    assert all(r.type in ROOM_TYPES for r in scene.rooms)
    assert all(r.attributes["mp3d_code"] == ROOM_TYPES[r.type].code for r in scene.rooms)
    names = [r.name for r in scene.rooms]
    assert len(set(names)) == len(names)
    assert "hallway 2" in names
    classic = generate_house(5, 2, 6, style="classic").scene
    assert {"kitchen", "living room", "dining room", "hallway"} <= {
        r.type for r in classic.rooms if r.floor == 0
    }
    assert all(not r.attributes for r in classic.rooms)


def test_stairs_join_floors_through_a_stairwell():
    house = generate_house(2, 3)
    plan, scene = house.plan, house.scene
    assert len(scene.stairs) == 2
    for stairs, sgt in zip(plan.stairs, scene.stairs, strict=True):
        lower, upper = plan.floors[stairs.from_floor], plan.floors[stairs.from_floor + 1]
        assert sgt.bottom[2] == pytest.approx(lower.z)
        assert sgt.top[2] == pytest.approx(upper.z)
        assert stairs.rect in upper.holes
        for floor, room_id in ((lower, stairs.room_bottom), (upper, stairs.room_top)):
            hall = plan.room(room_id)
            assert hall.type == "hallway" and hall.floor == floor.index
            assert hall.rect.contains_rect(stairs.rect)
        assert 2.7 <= lower.height <= 3.0
        assert stairs.rise < 0.2


def test_invalid_arguments_raise_input_errors():
    with pytest.raises(InputError, match="floors"):
        generate_house(1, 4)
    with pytest.raises(InputError, match="rooms per floor"):
        generate_house(1, 2, 13)
    with pytest.raises(InputError, match="seed"):
        generate_house(-1, 2)
    with pytest.raises(InputError, match="style"):
        generate_house(1, 2, style="baroque")
