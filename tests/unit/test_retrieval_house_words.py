"""Words people use for rooms and things that a map names otherwise: "the den" (a family
room to some, a TV room to others), "the bar stools" (a map that knows only stools), "the
door to the toilet" (mapped in the hall it opens from), and where a function is usually
done ("wash a few dishes": the kitchen sink, not the one in the toilet)."""

from __future__ import annotations

from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.constraints import RelationConstraint, RoomConstraint
from inherit_sg.retrieval.plan import compound_nearness, compound_rooms, usual_rooms
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.vocab.rooms import also_named, room_type
from tests.unit.retrieval_fixtures import floor_snapshot
from tests.unit.retrieval_rank import rank

# room key → (label, x of its centre)
ROOMS = {
    "living": ("living room", 0.0),
    "tv": ("tv room", 6.0),
    "kitchen": ("kitchen", -6.0),
    "hall": ("hallway", 12.0),
    "wc": ("toilet", 16.0),
}
DOORS = [("living", "tv"), ("living", "kitchen"), ("living", "hall"), ("hall", "wc")]
# (key, label, x, y, room key)
OBJECTS = [
    ("tv_living", "tv", 0.5, 0.0, "living"),
    ("tv_den", "tv", 6.5, 0.0, "tv"),
    ("bar", "bar", -6.0, 2.0, "kitchen"),
    ("stool_bar", "stool", -6.0, 2.6, "kitchen"),
    ("stool_living", "stool", -1.0, 0.0, "living"),
    ("sink_kitchen", "sink", -7.0, 0.0, "kitchen"),
    ("sink_wc", "sink", 16.5, 0.0, "wc"),
    # the toilet's door is mapped in the hall it opens from
    ("door_wc", "door", 14.0, 0.0, "hall"),
    ("door_tv", "door", 3.0, 1.0, "living"),
    ("plant_wc_door", "plant", 14.0, 0.6, "hall"),
    ("plant_tv_door", "plant", 3.0, 1.6, "living"),
]


def _snap() -> MapSnapshot:
    return floor_snapshot(OBJECTS, ROOMS, DOORS)


def test_a_word_that_names_two_room_types() -> None:
    assert room_type("den") == "family room"
    assert also_named("the den") == ("tv room",)
    assert also_named("lounge") == ()
    assert also_named("kitchen") == ()
    ranked, _ = rank(_snap(), parse_rules("Go to the telly in the den."))
    assert ranked[0].id == "obj:tv_den"
    ranked, _ = rank(_snap(), parse_rules("a tv that's not in the den"))
    assert ranked[0].id == "obj:tv_living"


def test_a_compound_the_map_does_not_use_places_the_thing_by_its_first_word() -> None:
    snap = _snap()
    parsed = parse_rules("Show me the bar stools.")
    hints = compound_nearness(parsed.constraints, snap)
    assert len(hints) == 1 and isinstance(hints[0], RelationConstraint)
    assert hints[0].landmark.target.labels == ("bar counter",)
    ranked, _ = rank(snap, parsed)
    assert ranked[0].id == "obj:stool_bar"
    # a map that has the compound's own label needs no hint; nor does a "floor lamp"
    assert not compound_nearness(parse_rules("the stool").constraints, snap)
    assert not compound_nearness(parse_rules("the floor lamp").constraints, snap)


def test_a_function_prefers_the_room_it_is_usually_done_in() -> None:
    snap = _snap()
    parsed = parse_rules("I need to wash a few dishes by hand.")
    (room,) = usual_rooms(parsed.constraints)
    assert isinstance(room, RoomConstraint) and room.type == "kitchen"
    ranked, _ = rank(snap, parsed)
    assert ranked[0].id == "obj:sink_kitchen"
    # a room the request names itself wins
    assert not usual_rooms(parse_rules("wash the dishes in the toilet").constraints)
    ranked, _ = rank(snap, parse_rules("where can I wash my hands in the toilet"))
    assert ranked[0].id == "obj:sink_wc"


def test_the_door_to_a_room_may_be_mapped_in_the_room_it_opens_from() -> None:
    parsed = parse_rules("the plant next to the door to the toilet")
    (rel,) = parsed.of_kind("relation")
    assert isinstance(rel, RelationConstraint)
    (room,) = [c for c in rel.landmark.constraints if isinstance(c, RoomConstraint)]
    assert (room.type, room.opening) == ("toilet", True)
    assert not [c for c in parsed.constraints if isinstance(c, RoomConstraint)]
    ranked, _ = rank(_snap(), parsed)
    assert ranked[0].id == "obj:plant_wc_door"
    ranked, _ = rank(_snap(), parse_rules("the plant next to the door to the tv room"))
    assert ranked[0].id == "obj:plant_tv_door"


def test_the_side_ruled_out_is_kept() -> None:
    from inherit_sg.retrieval.constraints import Superlative

    parsed = parse_rules("Facing the closet doors it is the hamper on the left not the right.")
    sides = [(c.direction, c.negated) for c in parsed.constraints if isinstance(c, Superlative)]
    assert sides == [("left", False), ("right", True)]
    assert parsed.viewpoint is not None and parsed.target.labels == ("basket",)


def test_a_compound_naming_a_room_prefers_its_general_word_in_that_room() -> None:
    """A map whose detector called the dining chairs "sofa chair" (a real Matterport3D
    annotation) and has one plain "chair" in the living room: "the dining chair" is one
    of the chairs in the dining room, and "closest to the bar" ranks among them."""
    rooms = {**ROOMS, "dining": ("dining room", -12.0)}
    doors = [*DOORS, ("kitchen", "dining")]
    objects = [
        *OBJECTS,
        ("chair_living", "chair", -1.0, 1.0, "living"),
        ("sofa_chair_near", "sofa chair", -10.0, 0.0, "dining"),
        ("sofa_chair_far", "sofa chair", -14.0, 0.0, "dining"),
    ]
    snap = floor_snapshot(objects, rooms, doors)
    parsed = parse_rules("the dining chair closest to the bar")
    (room,) = compound_rooms(parsed.constraints, snap)
    assert isinstance(room, RoomConstraint) and room.type == "dining room"
    ranked, _ = rank(snap, parsed)
    assert ranked[0].id == "obj:sofa_chair_near"
    # a room the request names itself wins; a map with the compound's label needs none
    assert not compound_rooms(parse_rules("the dining chair in the kitchen").constraints, snap)
    assert not compound_rooms(parse_rules("the kitchen sink").constraints, _snap())
    # a first word that is itself a kind the map has places by nearness instead
    assert not compound_rooms(parse_rules("the bar stool").constraints, snap)
