"""Two storeys and equal scores: a light upstairs is not "near the TV" right below it,
and among equally good answers the one the map observed more often leads."""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.model import BBox3D, FloorNode, Layer, ObjectNode, SceneGraph, make_id
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from tests.unit.retrieval_rank import rank

Obj = tuple[str, str, float, float, int, int]  # key, label, x, y, level, observations


def _two_storeys(objects: list[Obj]) -> MapSnapshot:
    g = SceneGraph()
    floors = [
        FloorNode(make_id(Layer.FLOOR, 0), 0, "ground", 0.0, 2.8),
        FloorNode(make_id(Layer.FLOOR, 1), 1, "upstairs", 3.0, 5.8),
    ]
    for floor in floors:
        g.add_or_update(floor)
    for key, label, x, y, level, seen in objects:
        z = floors[level].z_min
        node = ObjectNode(
            make_id(Layer.OBJECT, key),
            label,
            (x, y, z + 1.0),
            BBox3D((x - 0.25, y - 0.25, z + 0.8), (x + 0.25, y + 0.25, z + 1.2)),
            floor_id=floors[level].id,
        )
        g.add_or_update(replace(node, observation_count=seen))
    return build_snapshot(g, (1,))


def test_a_light_upstairs_is_not_near_the_tv_below_it() -> None:
    snap = _two_storeys(
        [
            ("tv", "tv", 0.0, 0.0, 0, 5),
            ("above", "ceiling light", 0.0, 0.0, 1, 5),  # right above the TV, upstairs
            ("beside", "ceiling light", 2.5, 0.0, 0, 5),  # the TV's own room, 2.5 m off
        ]
    )
    ranked, _ = rank(snap, parse_rules("the ceiling light near the tv"))
    assert ranked[0].id == "obj:beside"


def test_equal_answers_prefer_the_more_often_observed() -> None:
    snap = _two_storeys(
        [
            ("a1", "stairs", 0.0, 0.0, 0, 2),  # a fragment seen twice
            ("a2", "stairs", 0.0, 2.0, 0, 40),  # the flight itself
        ]
    )
    ranked, _ = rank(snap, parse_rules("the stairs"))
    assert [c.id for c in ranked[:2]] == ["obj:a2", "obj:a1"]
