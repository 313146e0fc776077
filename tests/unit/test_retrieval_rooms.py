"""Room constraints against rooms' labels, inferred alternatives, aliases and related
types, then embeddings (retrieval/room_match.py through ``resolve_matches``)."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.model import (
    BBox3D,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    RoomMask,
    RoomNode,
    SceneGraph,
    make_id,
)
from inherit_sg.retrieval.constraints import LabelConstraint, RoomConstraint
from inherit_sg.retrieval.match import resolve_matches
from inherit_sg.retrieval.room_match import (
    ALT_HI,
    ALT_LO,
    LABEL_LO,
    LABEL_TIE_SPAN,
    QUALIFIER_MISS,
    RELATED_SCALE,
    alternative_sim,
    label_sim,
)
from inherit_sg.retrieval.snapshot import MapSnapshot, build_snapshot
from inherit_sg.vocab.rooms import room_qualifier
from tests.unit.retrieval_fixtures import hash_similarity
from tests.unit.retrieval_rank import rank, request

LIVING = (("living room", 0.5), ("tv room", 0.35), ("family room", 0.1), ("other room", 0.03))
BEDROOM = (("bedroom", 0.9), ("tv room", 0.04))
TOILET = (("toilet", 0.6), ("bathroom", 0.35))


def _graph(rooms: dict[str, tuple[str, tuple[tuple[str, float], ...]]]) -> SceneGraph:
    """One floor; each room ``key: (label, types)`` holds a tv at its own x."""
    g = SceneGraph()
    floor = FloorNode(make_id(Layer.FLOOR, 0), 0, "ground", 0.0, 2.8)
    g.add_or_update(floor)
    for i, (key, (label, types)) in enumerate(rooms.items()):
        room = RoomNode(
            make_id(Layer.ROOM, key),
            label,
            floor_id=floor.id,
            position=(10.0 * i, 0.0, 0.0),
            types=types,
        )
        g.add_or_update(room)
        g.add_edge(Edge.make(EdgeKind.HAS_ROOM, floor.id, room.id))
        x = 10.0 * i
        tv = ObjectNode(
            make_id(Layer.OBJECT, f"tv-{key}"),
            "tv",
            (x, 0.0, 1.0),
            BBox3D((x - 0.5, -0.1, 0.7), (x + 0.5, 0.1, 1.3)),
            room_id=room.id,
            floor_id=floor.id,
        )
        g.add_or_update(tv)
    return g


def _snap(rooms: dict[str, tuple[str, tuple[tuple[str, float], ...]]]) -> MapSnapshot:
    return build_snapshot(_graph(rooms), (1,))


def _room(snap: MapSnapshot, rtype: str | None, name: str) -> dict[str, tuple[float, str]]:
    found = resolve_matches(
        RoomConstraint(id="c2", type=rtype, name=name), "object", snap, hash_similarity()
    )
    assert found is not None
    return found


def test_alternative_similarity_is_graded_by_probability() -> None:
    assert alternative_sim(0.5, 0.5) == 1.0
    assert alternative_sim(0.35, 0.5) == pytest.approx(ALT_LO + (ALT_HI - ALT_LO) * 0.7)
    assert (alternative_sim(0.49, 0.5) or 0.0) < ALT_HI + 1e-9
    assert alternative_sim(0.05, 0.5) is None  # below the floor


def test_the_tv_room_finds_a_living_room_with_a_tv() -> None:
    snap = _snap({"a": ("living room", LIVING), "b": ("bedroom", BEDROOM)})
    assert snap.room_alternatives["room:a"][:2] == (("living room", 0.5), ("tv room", 0.35))
    found = _room(snap, "tv room", "tv room")
    assert set(found) == {"room:a"}  # the bedroom's 0.04 is below the floor
    value, why = found["room:a"]
    assert ALT_LO < value < ALT_HI
    assert "alternatives" in why and "tv room" in why and "p=0.35" in why


def test_the_label_comes_first() -> None:
    snap = _snap({"a": ("living room", LIVING), "t": ("tv room", (("tv room", 0.8),))})
    found = _room(snap, "tv room", "tv room")
    assert found["room:t"][0] == label_sim(0.8) and "label" in found["room:t"][1]
    assert found["room:a"][0] < found["room:t"][0]  # still a candidate, ranked below
    living = _room(snap, "living room", "living room")
    assert living["room:a"] == (
        label_sim(0.5),
        "room room:a is a living room (label: its label, inferred p=0.50)",
    )


def test_an_unsure_label_matches_a_little_less() -> None:
    unsure = (("living room", 0.22), ("family room", 0.13), ("entryway", 0.09))
    snap = _snap({"a": ("living room", LIVING), "u": ("living room", unsure)})
    found = _room(snap, "living room", "sitting room")
    assert found["room:a"][0] == label_sim(0.5)
    assert LABEL_LO < found["room:u"][0] < found["room:a"][0]
    assert found["room:u"][0] == pytest.approx(label_sim(0.22))
    # its alternatives never count more than its label
    family = _room(snap, "family room", "den")
    assert family["room:u"][0] <= found["room:u"][0]
    assert label_sim(None) == 1.0
    # a sure label matches within LABEL_TIE_SPAN of 1, more the surer the map was
    assert 1.0 - LABEL_TIE_SPAN <= label_sim(0.6) < label_sim(0.9) < label_sim(1.0) == 1.0
    assert label_sim(0.49) < label_sim(0.5) == pytest.approx(1.0 - LABEL_TIE_SPAN)


def test_the_request_words_are_read_through_aliases() -> None:
    snap = _snap({"w": ("toilet", TOILET), "a": ("living room", LIVING)})
    # an LLM parser may leave the type unset and keep the words
    found = _room(snap, None, "wc")
    assert set(found) == {"room:w"}
    assert found["room:w"][0] == label_sim(0.6) and "'wc' names a toilet" in found["room:w"][1]
    # a room word on the room layer (a LabelConstraint): "powder room" names a toilet
    label = LabelConstraint(id="c1", labels=("powder room",), noun="powder room")
    on_rooms = resolve_matches(label, "room", snap, hash_similarity())
    assert on_rooms is not None and on_rooms["room:w"][0] == label_sim(0.6)
    # the bathroom is the toilet room's second type
    bath = _room(snap, "bathroom", "master bath")
    assert ALT_LO < bath["room:w"][0] < 1.0 and "alternatives" in bath["room:w"][1]


def test_related_types_match_maps_without_alternatives() -> None:
    # an oracle map: labels only, no inferred types
    snap = _snap({"l": ("living room", ()), "k": ("kitchen", ())})
    found = _room(snap, "family room", "family lounge")
    assert set(found) == {"room:l"}
    value, why = found["room:l"]
    assert value == pytest.approx(RELATED_SCALE * 0.8) and "related" in why
    # "den" names a family room and, as often, a TV room (``also``): fully
    snap = _snap({"t": ("tv room", ()), "k": ("kitchen", ())})
    found = _room(snap, "family room", "den")
    assert set(found) == {"room:t"} and found["room:t"][0] == 1.0


def test_related_types_say_nothing_against_a_room() -> None:
    # "the table outside the dining room" must not penalise the kitchen
    snap = _snap({"k": ("kitchen", ()), "d": ("dining room", ())})
    found = resolve_matches(
        RoomConstraint(id="c2", type="dining room", name="dining room", negated=True),
        "object",
        snap,
        hash_similarity(),
    )
    assert found is not None and set(found) == {"room:d"}
    assert "room:k" in _room(snap, "dining room", "dining room")  # but helps a positive one


def test_embeddings_when_nothing_else_matches() -> None:
    snap = _snap({"a": ("atrium", ()), "k": ("kitchen", ())})
    found = _room(snap, None, "atrium space")
    assert "room:a" in found and "room:k" not in found
    assert "text embedding" in found["room:a"][1]


def test_ranking_prefers_the_room_inferred_as_the_one_asked_for() -> None:
    snap = _snap({"a": ("living room", LIVING), "b": ("bedroom", BEDROOM)})
    ranked, _ = rank(snap, request("tv", RoomConstraint(type="tv room", name="tv room")))
    assert ranked[0].id == "obj:tv-a"
    assert ranked[0].score > ranked[1].score


def _house_with_an_en_suite() -> MapSnapshot:
    """Bedrooms m (with its own bathroom e) and s; bathrooms e (off m) and g (off the
    hall h)."""
    bath = (("bathroom", 0.9),)
    bed = (("bedroom", 0.9),)
    g = _graph(
        {
            "m": ("bedroom", bed),
            "e": ("bathroom", bath),
            "g": ("bathroom", bath),
            "s": ("bedroom", bed),
            "h": ("hallway", (("hallway", 0.9),)),
        }
    )
    for a, b in (("m", "e"), ("m", "h"), ("s", "h"), ("g", "h")):
        g.add_edge(Edge.make(EdgeKind.CONNECTS, f"room:{a}", f"room:{b}"))
    return build_snapshot(g, (1,))


def test_master_and_guest_bathrooms_are_told_apart_by_what_they_open_onto() -> None:
    snap = _house_with_an_en_suite()
    master = _room(snap, "bathroom", "master bathroom")
    sure = label_sim(0.9)
    assert master["room:e"][0] == sure
    assert master["room:g"][0] == pytest.approx(QUALIFIER_MISS * sure)
    assert "the private one is meant (off a bedroom)" in master["room:g"][1]
    guest = _room(snap, "bathroom", "guest bathroom")
    assert guest["room:g"][0] == sure
    assert guest["room:e"][0] == pytest.approx(QUALIFIER_MISS * sure)
    assert _room(snap, "bathroom", "en suite")["room:e"][0] == sure
    assert _room(snap, "bathroom", "en suite")["room:g"][0] < sure
    # no qualifier: both bathrooms match fully
    plain = _room(snap, "bathroom", "bathroom")
    assert plain["room:e"][0] == plain["room:g"][0] == sure


def test_the_master_bedroom_is_the_one_with_its_own_bathroom() -> None:
    snap = _house_with_an_en_suite()
    master = _room(snap, "bedroom", "master bedroom")
    sure = label_sim(0.9)
    assert master["room:m"][0] == sure and master["room:s"][0] < sure
    spare = _room(snap, "bedroom", "spare bedroom")
    assert spare["room:s"][0] == sure and spare["room:m"][0] < sure


def _sized_bathrooms() -> MapSnapshot:
    """Bathrooms b (2 × 4 m), s (1.5 × 2 m) and w (a toilet, 1 × 1.5 m), by their masks."""
    g = _graph({"b": ("bathroom", (("bathroom", 0.9),)), "s": ("bathroom", (("bathroom", 0.9),)),
                "w": ("toilet", TOILET)})  # fmt: skip
    for key, (width, depth) in {"b": (2.0, 4.0), "s": (1.5, 2.0), "w": (1.0, 1.5)}.items():
        room = g.get(make_id(Layer.ROOM, key))
        assert isinstance(room, RoomNode)
        cells = np.ones((round(depth / 0.1), round(width / 0.1)), dtype=bool)
        room.mask = RoomMask(room.position[0], 0.0, 0.1, cells)
    return build_snapshot(g, (1,))


def test_the_big_and_the_small_bathroom_are_told_apart_by_floor_area() -> None:
    snap = _sized_bathrooms()
    sure = label_sim(0.9)
    big = _room(snap, "bathroom", "large bathroom")
    assert big["room:b"][0] == sure
    assert big["room:s"][0] == pytest.approx(QUALIFIER_MISS * sure)
    assert "the largest one is meant (8.0 m²)" in big["room:s"][1]
    small = _room(snap, "bathroom", "small bathroom")
    assert small["room:s"][0] == sure and small["room:b"][0] < sure
    # the toilet matches as a related type only, so it is not the small bathroom
    assert small["room:w"][0] < sure and "smallest" not in small["room:w"][1]
    assert _room(snap, "bathroom", "main bathroom")["room:s"][0] < sure


def test_the_small_bathroom_is_read_from_the_request() -> None:
    from inherit_sg.retrieval import parse_rules

    parsed = parse_rules("is there a bottle of anything in the small bathroom?")
    room = next(c for c in parsed.constraints if isinstance(c, RoomConstraint))
    assert (room.type, room.name) == ("bathroom", "small bathroom")
    assert room_qualifier(room.name) == "smallest"


def test_room_qualifier_words() -> None:
    assert room_qualifier("master bathroom") == "private"
    assert room_qualifier("the en-suite") == "private"
    assert room_qualifier("Guest Bathroom") == "shared"
    assert room_qualifier("spare room") == "shared"
    assert room_qualifier("bathroom") is None
    assert room_qualifier("mastermind room") is None
    assert room_qualifier("the big bathroom") == "largest"
    assert room_qualifier("main bedroom") == "largest"
    assert room_qualifier("small bathroom") == "smallest"
    assert room_qualifier("front bathroom") == "front"
    assert room_qualifier("the back bedroom") == "back"


def test_with_one_labelled_bathroom_the_big_one_is_compared_with_a_maybe_bathroom() -> None:
    # only b is labelled a bathroom; w (a toilet that may be a bathroom, p 0.35 of 0.6)
    # is compared by size all the same: "the small bathroom" is the toilet room
    g = _graph({"b": ("bathroom", (("bathroom", 0.9),)), "w": ("toilet", TOILET)})
    for key, (width, depth) in {"b": (2.0, 4.0), "w": (1.5, 2.0)}.items():
        room = g.get(make_id(Layer.ROOM, key))
        assert isinstance(room, RoomNode)
        room.mask = RoomMask(
            room.position[0],
            0.0,
            0.1,
            np.ones((round(depth / 0.1), round(width / 0.1)), dtype=bool),
        )
    snap = build_snapshot(g, (1,))
    small = _room(snap, "bathroom", "small bathroom")
    assert small["room:w"][0] > small["room:b"][0]
    assert "the smallest one is meant" in small["room:b"][1]


def test_the_front_bathroom_is_the_one_nearest_the_way_in() -> None:
    snap = _sized_bathrooms()
    sure = label_sim(0.9)
    assert "room:b" in snap.rooms and "room:s" in snap.rooms
    # no door known to lead outside: the qualifier says nothing
    plain = _room(snap, "bathroom", "front bathroom")
    assert plain["room:b"][0] == plain["room:s"][0] == sure
    g = _graph({"b": ("bathroom", (("bathroom", 0.9),)), "s": ("bathroom", (("bathroom", 0.9),))})
    for key in ("b", "s"):
        room = g.get(make_id(Layer.ROOM, key))
        assert isinstance(room, RoomNode)
        room.mask = RoomMask(room.position[0], 0.0, 0.1, np.ones((20, 20), dtype=bool))
    door = ObjectNode(
        make_id(Layer.OBJECT, "front-door"),
        "exterior door",
        (13.0, -0.5, 1.0),
        BBox3D((12.5, -0.6, 0.0), (13.5, -0.4, 2.0)),
        floor_id="floor:0",
    )
    g.add_or_update(door)
    snap = build_snapshot(g, (1,))
    front = _room(snap, "bathroom", "front bathroom")
    assert front["room:s"][0] == sure and front["room:b"][0] == pytest.approx(QUALIFIER_MISS * sure)
    assert "nearest the way in" in front["room:b"][1]
    back = _room(snap, "bathroom", "back bathroom")
    assert back["room:b"][0] == sure and back["room:s"][0] < sure


def test_the_second_bathroom_is_not_the_main_one() -> None:
    from inherit_sg.retrieval import parse_rules
    from inherit_sg.retrieval.room_match import OTHER_MISS

    snap = _sized_bathrooms()
    sure = label_sim(0.9)
    other = _room(snap, "bathroom", "other bathroom")
    assert other["room:s"][0] == sure
    assert other["room:b"][0] == pytest.approx(OTHER_MISS * sure)
    assert "not the main one" in other["room:b"][1]
    for text in ("the mirror in the second bathroom", "the sink in the other bathroom"):
        room = next(c for c in parse_rules(text).constraints if isinstance(c, RoomConstraint))
        assert room.name == "other bathroom" and room_qualifier(room.name) == "other", text
