"""Relations, areas, room labels and summaries from object nodes."""

from __future__ import annotations

from inherit_sg.mapping.areas import cluster_objects, label_area, summarise_area
from inherit_sg.mapping.relations import infer_relations
from inherit_sg.mapping.room_semantics import infer_room_type, summarise_room
from inherit_sg.model import BBox3D, ObjectNode


def _o(
    i: int,
    label: str,
    lo: tuple[float, float, float],
    hi: tuple[float, float, float],
    floor: str = "floor:0",
) -> ObjectNode:
    box = BBox3D(lo, hi)
    return ObjectNode(f"obj:{i}", label, tuple(box.center), box, floor_id=floor)


def _rels(
    objs: list[ObjectNode], rooms: dict[str, str | None] | None = None
) -> set[tuple[str, str, str]]:
    room_of = rooms or {o.id: "room:0" for o in objs}
    return {(r.src, r.predicate, r.dst) for r in infer_relations(objs, room_of)}


def test_mug_on_table_and_rug_under_it() -> None:
    table = _o(1, "table", (0, 0, 0), (1, 0.7, 0.75))
    mug = _o(2, "mug", (0.4, 0.3, 0.75), (0.5, 0.4, 0.86))
    rug = _o(3, "rug", (-0.5, -0.5, 0), (1.5, 1.2, 0.02))
    rels = _rels([table, mug, rug])
    assert ("obj:2", "on", "obj:1") in rels
    assert ("obj:1", "on", "obj:3") in rels  # the table stands on the rug
    assert ("obj:2", "above", "obj:3") in rels
    assert ("obj:1", "on", "obj:2") not in rels


def test_next_to_and_near_are_symmetric_and_room_bound() -> None:
    chair = _o(1, "chair", (0, 0, 0), (0.5, 0.5, 0.9))
    desk = _o(2, "desk", (0.8, 0, 0), (2.0, 0.6, 0.75))
    lamp = _o(3, "lamp", (3.0, 0, 0), (3.4, 0.4, 1.6))
    rels = _rels([chair, desk, lamp])
    assert {("obj:1", "next to", "obj:2"), ("obj:2", "next to", "obj:1")} <= rels
    assert ("obj:3", "near", "obj:2") in rels and ("obj:3", "next to", "obj:2") not in rels
    # different, unconnected rooms: nothing (a wall is between them)
    split = _rels([chair, desk], {"obj:1": "room:0", "obj:2": "room:1"})
    assert not split
    # different floors never relate
    assert not _rels([chair, _o(4, "desk", (0.8, 0, 0), (2.0, 0.6, 0.75), floor="floor:1")])


def test_clusters_and_area_labels() -> None:
    objs = [
        _o(1, "bed", (0, 0, 0), (1.6, 2.0, 0.5)),
        _o(2, "nightstand", (1.7, 0, 0), (2.1, 0.4, 0.55)),
        _o(3, "table lamp", (1.8, 0.1, 0.55), (2.0, 0.3, 0.9)),
        _o(4, "desk", (5, 0, 0), (6.3, 0.6, 0.75)),
        _o(5, "chair", (5.3, 0.8, 0), (5.8, 1.3, 0.9)),
    ]
    groups = cluster_objects(objs)
    assert [sorted(o.id for o in g) for g in groups] == [
        ["obj:1", "obj:2", "obj:3"],
        ["obj:4", "obj:5"],
    ]
    assert label_area([o.label for o in groups[0]]) == "sleeping area"
    assert label_area([o.label for o in groups[1]]) == "work area"
    assert label_area(["plant"]) == "plant area"
    assert (
        summarise_area("work area", ["desk", "chair", "chair"])
        == "A work area with 2 chairs and a desk."
    )


def test_room_types_and_summary() -> None:
    assert infer_room_type(["bed", "nightstand"]) == "bedroom"
    assert infer_room_type(["toilet", "sink"]) == "toilet"  # no bath or shower: a toilet room
    assert infer_room_type(["stove", "refrigerator", "table"]) == "kitchen"
    assert infer_room_type(["door", "painting"]) == "hallway"
    assert infer_room_type(["chair"]) == "room"
    text = summarise_room("kitchen", 1, ["A cooking area with a stove."], ["stove", "door"])
    assert text.startswith("A kitchen on the second floor containing stove.")
    assert "cooking area" in text
