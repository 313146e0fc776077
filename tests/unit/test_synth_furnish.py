"""Furnishing: no interpenetration, small objects on surfaces, attributes, ambiguity."""

from __future__ import annotations

from collections import defaultdict

import pytest

from inherit_sg.ingest.synthetic.arrange import support_spots
from inherit_sg.ingest.synthetic.catalogue import REAL_MATERIALS
from inherit_sg.ingest.synthetic.colour_naming import BASIC_TERMS, colour_term
from inherit_sg.ingest.synthetic.generate import generate_house
from inherit_sg.ingest.synthetic.geom import Rect
from inherit_sg.ingest.synthetic.vocabulary import COLOURS, OBJECT_KINDS, SIZE_WORDS

HOUSES = ((0, "real"), (7, "real"), (21, "real"), (7, "classic"))


@pytest.fixture(scope="module", params=HOUSES, ids=[f"{s}-{k}" for s, k in HOUSES])
def house(request):
    seed, style = request.param
    return generate_house(seed, 2, style=style)


def _box(obj):
    return obj.bbox_min, obj.bbox_max


def _overlap(a, b, tol=1e-4):
    return all(a[0][i] < b[1][i] - tol and b[0][i] < a[1][i] - tol for i in range(3))


def test_floor_standing_furniture_does_not_interpenetrate(house):
    standing = [
        o
        for o in house.scene.objects
        if not o.structural and o.supported_by is None and o.bbox_max[2] - o.bbox_min[2] >= 0.05
    ]
    assert len(standing) > 20
    for i, a in enumerate(standing):
        for b in standing[i + 1 :]:
            assert not _overlap(_box(a), _box(b)), (a.id, a.label, b.id, b.label)


def test_small_objects_rest_on_their_supporter(house):
    scene = house.scene
    real = bool(scene.rooms[0].attributes)  # real-world rooms carry their region codes
    placed = {o.id: o for o in house.objects}
    small = [o for o in scene.objects if OBJECT_KINDS[o.label].small]
    assert small
    for obj in small:
        kind = OBJECT_KINDS[obj.label]
        if obj.supported_by is None:  # on the floor or hung on a wall, where its kind may be
            assert {"floor", "wall"} & set(kind.rests_on), obj.label
            continue
        sup = scene.object(obj.supported_by)
        if real:
            assert sup.label in kind.rests_on, (obj.label, sup.label)
        else:
            assert OBJECT_KINDS[sup.label].surface
        spots = support_spots(placed[sup.id])
        footprint = Rect(obj.bbox_min[0], obj.bbox_min[1], obj.bbox_max[0], obj.bbox_max[1])
        assert any(
            abs(obj.bbox_min[2] - z) < 2e-3 and top.grown(1e-3).contains_rect(footprint)
            for z, top in spots
        ), (obj.label, sup.label)
        assert obj.room_id == sup.room_id


def test_objects_have_ids_rooms_and_attributes(house):
    scene = house.scene
    real = bool(scene.rooms[0].attributes)
    ids = [o.id for o in scene.objects]
    instances = [o.instance_id for o in scene.objects]
    assert len(set(ids)) == len(ids)
    assert len(set(instances)) == len(instances) and min(instances) >= 1
    rooms = {r.id: r for r in scene.rooms}
    for obj in scene.objects:
        kind = OBJECT_KINDS[obj.label]
        assert obj.attributes["size"] in SIZE_WORDS
        if real:
            # a sampled colour, named by its basic colour term
            rgb = tuple(obj.attributes["rgb"])
            assert obj.attributes["colour"] == colour_term(rgb) in BASIC_TERMS
            materials = REAL_MATERIALS.get(obj.label, kind.materials)
            assert obj.attributes["mpcat40"] == kind.mpcat40
            assert obj.attributes["mp3d_category"] in (kind.raw or (obj.label,))
        else:
            assert obj.attributes["colour"] in COLOURS and "rgb" not in obj.attributes
            materials = kind.materials
        assert obj.attributes["material"] in materials or obj.structural
        assert obj.room_id in rooms and rooms[obj.room_id].floor == obj.floor
        if not obj.structural:
            if not real:
                assert obj.attributes["colour"] in kind.colours
            poly = rooms[obj.room_id].polygon
            x, y = obj.centroid[:2]
            assert poly[0][0] <= x <= poly[2][0] and poly[0][1] <= y <= poly[2][1]
        for lo, c, hi in zip(obj.bbox_min, obj.centroid, obj.bbox_max, strict=True):
            assert lo <= c <= hi


def test_areas_group_members_of_one_room(house):
    scene = house.scene
    assert scene.areas
    for area in scene.areas:
        assert area.object_ids
        for oid in area.object_ids:
            obj = scene.object(oid)
            assert obj.room_id == area.room_id and obj.area_id == area.id


def test_structural_objects_match_the_building(house):
    scene = house.scene
    doors = [o for o in scene.objects if o.label == "door"]
    assert len(doors) == len(scene.doors) and all(o.structural for o in doors)
    windows = [o for o in scene.objects if o.label == "window"]
    assert windows and all(o.structural and o.bbox_min[2] > 0.5 for o in windows)
    stairs = [o for o in scene.objects if o.label == "stairs"]
    assert len(stairs) == len(scene.stairs) == 1


@pytest.mark.parametrize("style", ["real", "classic"])
def test_labels_repeat_across_rooms_and_floors(style):
    scene = generate_house(4, 2, style=style).scene
    where = defaultdict(set)
    floors = defaultdict(set)
    for o in scene.objects:
        if not o.structural:
            where[o.label].add(o.room_id)
            floors[o.label].add(o.floor)
    repeated = [label for label, rooms in where.items() if len(rooms) >= 2]
    assert len(repeated) >= 5
    assert sum(len(f) == 2 for f in floors.values()) >= 3
