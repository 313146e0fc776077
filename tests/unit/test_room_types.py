"""Room types as a ranked distribution (mapping/room_semantics.py) over the room
vocabulary: evidence for and against, size and shape cues, what a Room node keeps."""

from __future__ import annotations

import math

import numpy as np
import pytest

from inherit_sg.mapping.room_semantics import (
    KEEP_TYPES,
    RoomShape,
    infer_room_type,
    infer_room_types,
    kept_types,
    room_label,
    room_shape,
    room_type_scores,
)
from inherit_sg.model import RoomMask
from inherit_sg.vocab import rooms as room_vocab


def _types(dist: list[tuple[str, float]]) -> list[str]:
    return [t for t, _ in dist]


def _p(dist: list[tuple[str, float]], rtype: str) -> float:
    return dict(dist)[rtype]


def test_a_distribution_over_every_type_best_first() -> None:
    dist = infer_room_types(["bed", "nightstand", "lamp"])
    assert sorted(_types(dist)) == sorted(room_vocab.room_types())
    assert math.isclose(sum(p for _, p in dist), 1.0, abs_tol=1e-9)
    probs = [p for _, p in dist]
    assert probs == sorted(probs, reverse=True)
    assert dist[0][0] == "bedroom" and dist[0][1] > 0.9


def test_toilet_and_sink_without_a_shower_is_a_toilet_then_a_bathroom() -> None:
    dist = infer_room_types(["toilet", "sink"])
    assert _types(dist)[:2] == ["toilet", "bathroom"]
    # a bathtub is evidence for a bathroom and against a toilet room
    with_bath = infer_room_types(["toilet", "sink", "bathtub"])
    assert with_bath[0][0] == "bathroom"
    assert _p(with_bath, "toilet") < 0.05 < _p(dist, "toilet")


def test_tv_and_sofa_are_a_tv_room_or_a_living_or_family_room() -> None:
    top3 = _types(infer_room_types(["tv", "sofa"]))[:3]
    assert "tv room" in top3
    assert {"living room", "family room"} & set(top3)
    # a sofa group with a coffee table and armchairs leans to the living room
    lounge = infer_room_types(["sofa", "coffee table", "armchair", "tv"])
    assert lounge[0][0] == "living room" and "tv room" in _types(lounge)[:3]


def test_labels_count_by_their_kind() -> None:
    # dataset names: "couch" is a sofa, "bedside table" a nightstand, "shower wall" a shower
    assert infer_room_types(["couch", "tv", "tv stand", "speaker"])[0][0] == "tv room"
    assert infer_room_types(["bedside table", "bed"])[0][0] == "bedroom"
    assert infer_room_types(["shower wall", "towel", "bathrobe"])[0][0] == "bathroom"
    # one vote per kind: "couch" and "sofa" together weigh as one sofa
    both = room_type_scores(["couch", "sofa"])
    assert both == room_type_scores(["sofa"])


def test_a_kind_counts_through_what_it_is_a_kind_of() -> None:
    # "bunk bed" has its own weight; "hospital bed" counts as a bed, a little less
    base = room_type_scores([])["bedroom"]
    bed = room_type_scores(["bed"])["bedroom"] - base
    hospital = room_type_scores(["hospital bed"])["bedroom"] - base
    assert 0 < hospital < bed


def test_empty_rooms_spread_their_probability() -> None:
    dist = infer_room_types([])
    assert dist[0][0] == "other room" and dist[0][1] < 0.3
    assert infer_room_type([]) == "room"
    assert infer_room_type(["chair", "plant"]) == "room"
    # only fixtures (doors, paintings): a hallway
    assert infer_room_type(["door", "painting"]) == "hallway"


def test_an_empty_narrow_room_is_a_hallway() -> None:
    corridor = RoomShape(area_m2=7.2, width_m=1.2, elongation=5.0)
    assert corridor.narrowness == 1.0
    dist = infer_room_types([], shape=corridor)
    assert dist[0][0] == "hallway" and dist[0][1] > 0.3
    square = RoomShape(area_m2=16.0, width_m=4.0, elongation=1.0)
    assert square.narrowness == 0.0
    assert infer_room_types([], shape=square)[0][0] == "other room"


def test_a_room_with_many_doors_joins_others() -> None:
    """Three doors or more say hallway, even around a staircase; a bedroom with its
    closet and bathroom doors stays a bedroom."""
    square = RoomShape(area_m2=16.0, width_m=4.0, elongation=1.0)
    hall = ["door", "door", "door", "console table", "painting", "rug"]
    assert infer_room_types(hall, shape=square)[0][0] == "hallway"
    assert infer_room_types(hall[2:], shape=square)[0][0] != "hallway"
    stair_hall = ["stairs", "door", "door", "door", "door", "window"]
    assert infer_room_types(stair_hall, shape=square)[0][0] == "hallway"
    bedroom = ["bed", "nightstand", "door", "door", "door", "wardrobe"]
    assert infer_room_types(bedroom, shape=square)[0][0] == "bedroom"


def test_size_hints() -> None:
    # a toilet with towels and a cabinet: the small room is a toilet, the large a bathroom
    labels = ["toilet", "sink", "towel", "bathroom cabinet", "mirror"]
    small = infer_room_types(labels, area_m2=1.8)
    large = infer_room_types(labels, area_m2=12.0)
    assert small[0][0] == "toilet" and large[0][0] == "bathroom"
    assert _p(large, "toilet") < _p(small, "toilet")


def test_room_shape_of_masks() -> None:
    corridor = np.zeros((20, 80), dtype=bool)
    corridor[8:13, 5:75] = True  # 0.25 m × 3.5 m at 5 cm
    shape = room_shape(RoomMask(0.0, 0.0, 0.05, corridor))
    assert shape is not None
    assert shape.area_m2 == pytest.approx(0.875)
    assert shape.width_m == pytest.approx(0.25, abs=0.06) and shape.elongation > 10
    square = np.zeros((60, 60), dtype=bool)
    square[5:55, 5:55] = True
    square[20:30, 20:30] = False  # a hole where furniture stands is filled
    box = room_shape(RoomMask(0.0, 0.0, 0.1, square))
    assert box is not None and box.area_m2 == pytest.approx(25.0)
    assert box.width_m > 4.0 and box.narrowness == 0.0
    assert room_shape(None) is None
    assert room_shape(RoomMask(0.0, 0.0, 0.1, np.zeros((4, 4), dtype=bool))) is None


def test_label_and_what_a_room_keeps() -> None:
    assert room_label([("other room", 0.4), ("hallway", 0.2)]) == "room"
    assert room_label([]) == "room"
    assert room_label([("tv room", 0.5), ("living room", 0.3)]) == "tv room"
    dist = infer_room_types(["tv", "sofa"])
    kept = kept_types(dist)
    assert 2 <= len(kept) <= KEEP_TYPES and kept[0] == (dist[0][0], round(dist[0][1], 4))
    assert all(p >= 0.02 for _, p in kept[1:])
    assert kept_types([("bedroom", 0.99), ("other room", 0.005)]) == (("bedroom", 0.99),)


def test_one_per_storey_types_go_to_the_strongest_claim() -> None:
    from inherit_sg.mapping.room_semantics import separate_single_types

    strong = [("living room", 0.69), ("family room", 0.26), ("tv room", 0.05)]
    weak = [("living room", 0.56), ("family room", 0.19), ("other room", 0.25)]
    bedroom = [("bedroom", 0.9), ("other room", 0.1)]
    other_floor = [("living room", 0.5), ("family room", 0.5)]
    out = separate_single_types(
        [
            {"room:a": strong, "room:b": weak, "room:c": bedroom, "room:d": list(bedroom)},
            {"room:e": other_floor},
        ]
    )
    assert out["room:a"] == strong  # the strongest claim keeps its type untouched
    assert out["room:b"][0][0] == "other room" or out["room:b"][0][0] == "family room"
    assert out["room:b"][0][0] != "living room"
    assert abs(sum(p for _, p in out["room:b"]) - 1.0) < 1e-9
    assert out["room:c"] == bedroom and out["room:d"] == bedroom  # two bedrooms are common
    assert out["room:e"] == other_floor  # another storey has its own living room


def test_a_discounted_room_moves_on_to_its_next_free_type() -> None:
    from inherit_sg.mapping.room_semantics import separate_single_types

    first = [("kitchen", 0.8), ("dining room", 0.2)]
    second = [("kitchen", 0.5), ("dining room", 0.4), ("other room", 0.1)]
    third = [("kitchen", 0.45), ("dining room", 0.35), ("bar", 0.2)]
    out = separate_single_types([{"k1": first, "k2": second, "k3": third}])
    labels = {rid: types[0][0] for rid, types in out.items()}
    assert labels["k1"] == "kitchen"
    assert labels["k2"] == "dining room"  # the stronger of the two dining claims
    assert labels["k3"] == "bar"  # kitchen and dining room are both held


def test_an_entryway_is_where_the_building_is_entered() -> None:
    """A hall with a bench is an entryway on the storey with the exterior door, a
    hallway on a storey without one (when another storey has it)."""
    hall = RoomShape(area_m2=8.0, width_m=2.2, elongation=1.6)
    labels = ["bench", "plant", "thermostat", "painting", "light switch", "window", "door"]
    assert infer_room_types(labels, shape=hall)[0][0] == "entryway"
    upstairs = infer_room_types(labels, shape=hall, off_entrance=True)
    assert upstairs[0][0] != "entryway"
    assert _p(upstairs, "entryway") < _p(infer_room_types(labels, shape=hall), "entryway")
