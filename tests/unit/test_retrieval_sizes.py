"""Sizes as requests mean them: flat boxes keep their area, single-view slivers are not
compared, and size words are relative to the kind (scored on a built snapshot)."""

from __future__ import annotations

import pytest

from inherit_sg.model import BBox3D, Layer, ObjectNode, SceneGraph, make_id
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.candidates import Candidates
from inherit_sg.retrieval.constraints import AttributeConstraint
from inherit_sg.retrieval.graph_checks import GraphChecker
from inherit_sg.retrieval.plan import Compiler
from inherit_sg.retrieval.scoring import Scored, Scorer, attribute_sim
from inherit_sg.retrieval.sizes import (
    bulk,
    face_area,
    kind_sizes,
    linear_size,
    measured_in_views,
    robust_volume,
    size_word,
    size_word_sim,
)
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from tests.unit.retrieval_fixtures import hash_similarity


def _obj(
    key: int,
    label: str,
    size: tuple[float, float, float],
    views: int = 5,
    at: tuple[float, float, float] = (0.0, 0.0, 0.5),
) -> ObjectNode:
    return ObjectNode(
        id=make_id(Layer.OBJECT, key),
        label=label,
        position=at,
        bbox=BBox3D.from_center_size(at, size),
        observation_count=views,
    )


def _snapshot(objects: list[ObjectNode]) -> MapSnapshot:
    graph = SceneGraph()
    for obj in objects:
        graph.add_or_update(obj)
    return build_snapshot(graph, (1,))


def _rank(snap: MapSnapshot, text: str) -> list[Scored]:
    spec = Compiler(snap, hash_similarity()).compile(parse_rules(text)).target
    cands = Candidates(found_by={oid: ["test"] for oid in snap.objects})
    return Scorer(snap, GraphChecker(snap)).score(spec, cands, {})[0]


def test_robust_volume_keeps_the_area_of_flat_boxes() -> None:
    assert robust_volume((1.0, 2.0, 0.5)) == pytest.approx(1.0)
    # a wall clock seen from the front: 0.3 × 0.3 m and 0.1 mm deep
    assert robust_volume((0.3, 0.0001, 0.3)) == pytest.approx(0.3 * 0.03 * 0.3)
    assert robust_volume((0.0, 0.0, 0.0)) == 0.0
    assert linear_size(_obj(1, "box", (0.2, 0.2, 0.2))) == pytest.approx(0.2)


def test_the_biggest_tv_has_the_biggest_screen_not_the_deepest_box() -> None:
    assert face_area((0.07, 1.89, 1.15)) == pytest.approx(1.89 * 1.15)
    assert face_area((0.0, 0.0, 0.0)) == 0.0 and bulk((0.0, 0.0, 0.0)) == 0.0
    # a TV seen face on (a thin box) and one mapped deep from the side
    tvs = [_obj(1, "tv", (0.07, 1.89, 1.15)), _obj(2, "tv", (0.36, 1.47, 0.86))]
    assert _rank(_snapshot(tvs), "which telly is the biggest")[0].id == "obj:1"
    assert _rank(_snapshot(tvs), "the smallest tv")[0].id == "obj:2"
    # a floor pouf is bigger than a flat cushion with a slightly larger face
    pillows = [_obj(3, "pillow", (0.43, 0.58, 0.05)), _obj(4, "pillow", (0.41, 0.29, 0.47))]
    assert _rank(_snapshot(pillows), "the biggest pillow")[0].id == "obj:4"


def test_size_words_are_relative_to_the_kind() -> None:
    assert size_word(0.8) == "small" and size_word(1.0) == "medium" and size_word(1.3) == "large"
    assert size_word_sim(1.0, "medium") == 1.0 and size_word_sim(1.0, "large") < 1.0
    # outside its band a word's match falls off gradually, not at once
    assert 0.0 < size_word_sim(1.15, "medium") < 1.0 and size_word_sim(2.0, "medium") == 0.0
    assert size_word_sim(1.0, "heavy") == 0.0
    mugs = [_obj(i, "mug", (s, s, s)) for i, s in enumerate((0.08, 0.1, 0.12), 1)]
    tables = [_obj(i, "table", (s, s, 0.75)) for i, s in enumerate((1.0, 1.2, 1.4), 10)]
    sliver = _obj(20, "mug", (0.5, 0.5, 0.5), views=1)  # not measured: no reference
    refs = kind_sizes([*mugs, *tables, sliver])
    assert set(refs) == {"mug", "table"}
    assert refs["mug"] == pytest.approx(0.1)
    # two measured objects of a kind already compare ("the large TV" of two);
    # a single one has no reference
    assert kind_sizes(mugs[:2]) == {"mug": pytest.approx(0.09)}
    assert kind_sizes(mugs[:1]) == {}
    assert not measured_in_views(sliver) and measured_in_views(mugs[0])


def test_a_large_mug_is_the_largest_mug_not_the_table() -> None:
    mugs = [_obj(i, "mug", (s, s, s)) for i, s in enumerate((0.08, 0.1, 0.125), 1)]
    snap = _snapshot([*mugs, _obj(9, "table", (1.2, 0.8, 0.75))])
    large = AttributeConstraint(key="size", value="large")
    small = AttributeConstraint(key="size", value="small")
    sim, why = attribute_sim(snap, "obj:3", large)
    assert sim > 0.9 and "large for a mug" in why  # 1.25 × the median: large, not extreme
    assert attribute_sim(snap, "obj:1", small)[0] > 0.9
    assert attribute_sim(snap, "obj:1", large)[0] == 0.0
    assert _rank(snap, "the large mug")[0].id == "obj:3"
    assert _rank(snap, "a medium-sized mug")[0].id == "obj:2"


def test_smallest_ignores_single_view_slivers_and_flat_boxes_keep_their_area() -> None:
    desks = [
        _obj(1, "desk", (1.2, 0.6, 0.75)),
        _obj(2, "desk", (1.0, 0.5, 0.7)),
        _obj(3, "desk", (0.04, 0.0001, 0.34), views=1),  # a sliver of a desk's edge
    ]
    ranked = _rank(_snapshot(desks), "which desk is the smallest")
    assert ranked[0].id == "obj:2"
    sliver = next(c for c in ranked if c.id == "obj:3")
    assert "one view" in next(t.why for t in sliver.terms.values() if t.kind == "superlative")
    # two wall clocks seen from the front (flat boxes): the smaller face wins
    clocks = [
        _obj(4, "clock", (0.29, 0.0001, 0.28)),
        _obj(5, "clock", (0.245, 0.025, 0.22)),
    ]
    assert _rank(_snapshot(clocks), "the smallest clock")[0].id == "obj:5"
    # with only single-view boxes there is nothing better: they are compared
    lone = [_obj(6, "vase", (0.1, 0.1, 0.3), views=1), _obj(7, "vase", (0.2, 0.2, 0.5), views=1)]
    assert _rank(_snapshot(lone), "the largest vase")[0].id == "obj:7"


def test_a_size_word_prefers_the_more_extreme_inside_its_band() -> None:
    """'The big sofa' among big sofas: the biggest scores highest."""
    assert (
        0.85
        < size_word_sim(1.12, "large")
        < size_word_sim(1.4, "large")
        < size_word_sim(2.5, "large")
        == 1.0
    )
    assert 0.85 < size_word_sim(0.9, "small") < size_word_sim(0.4, "small") == 1.0


def test_the_only_one_of_its_kind_is_not_ruled_out_by_its_absolute_size() -> None:
    # one toilet (no peers to compare with) and two small toiletries: "the small toilet"
    # is the toilet, whose absolute box size (medium) cannot contradict "small"
    toilet = _obj(1, "toilet", (0.4, 0.7, 0.8))
    toiletries = [_obj(i, "toiletry", (s, s, 2 * s)) for i, s in ((2, 0.05), (3, 0.08))]
    snap = _snapshot([toilet, *toiletries])
    small = AttributeConstraint(key="size", value="small")
    sim, why = attribute_sim(snap, "obj:1", small)
    assert 0.0 < sim < 1.0 and "no other toilet to compare with" in why
    # an absolute size that agrees still confirms the word
    large = AttributeConstraint(key="size", value="large")
    assert attribute_sim(_snapshot([_obj(1, "sofa", (2.2, 0.9, 0.9))]), "obj:1", large)[0] == 1.0
