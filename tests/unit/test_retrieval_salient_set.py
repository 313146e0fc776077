"""People compare among the things in front of them: "the stool farthest from the
dishwasher" is one of the kitchen's stools, not the one in the bathroom down the hall,
and "standing at the counter, the stool on the left" orders the stools of the
counter's room."""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.snapshot import MapSnapshot
from tests.unit.retrieval_fixtures import floor_snapshot
from tests.unit.retrieval_rank import rank

# (key, label, room, x, y)
KITCHEN_AND_BATH = [
    ("dw", "dishwasher", "k", 0.0, 0.0),
    ("counter", "counter", "k", 2.0, 1.0),
    ("s1", "stool", "k", 1.0, 2.0),
    ("s2", "stool", "k", 2.0, 2.0),
    ("s3", "stool", "k", 3.0, 2.0),
    ("s4", "stool", "b", 7.0, 0.0),  # a shower stool behind a wall
]


def _snap(objects: list[tuple[str, str, str, float, float]]) -> MapSnapshot:
    """A kitchen and a bathroom on one floor, with ``(key, label, room, x, y)`` objects."""
    rooms = {"k": ("kitchen", 1.5), "b": ("bathroom", 7.0)}
    return floor_snapshot([(k, lab, x, y, room) for k, lab, room, x, y in objects], rooms)


def test_farthest_compares_the_landmarks_room() -> None:
    snap = _snap(KITCHEN_AND_BATH)
    ranked, log = rank(snap, parse_rules("the stool farthest from the dishwasher"))
    assert ranked[0].id == "obj:s3"
    assert any("3 of 4 candidates near the landmark are compared" in line for line in log)
    # with the landmark's room holding one stool only, every stool is compared
    alone = _snap([o for o in KITCHEN_AND_BATH if o[0] not in ("s1", "s2")])
    ranked, _ = rank(alone, parse_rules("the stool farthest from the dishwasher"))
    assert ranked[0].id == "obj:s4"


def test_a_viewpoint_orders_the_candidates_of_its_room() -> None:
    snap = _snap(KITCHEN_AND_BATH)
    parsed = parse_rules("standing at the counter, the stool on the right")
    ranked, log = rank(snap, parsed)
    assert ranked[0].id in {"obj:s1", "obj:s2", "obj:s3"}
    assert any("viewer: from counter" in line for line in log)
    by_id = {c.id: c for c in ranked}
    # the shower stool down the hall is neither in the counter's room nor near it
    assert all(by_id["obj:s4"].score < by_id[k].score for k in ("obj:s1", "obj:s2", "obj:s3"))
    # without the parser's hint that the stool is near the counter, the superlative
    # alone still orders only the stools of the counter's room
    bare = replace(parsed, constraints=tuple(c for c in parsed.constraints if c.kind != "relation"))
    ranked, log = rank(snap, bare)
    assert ranked[0].id in {"obj:s1", "obj:s2", "obj:s3"}
    assert any("in the viewpoint's room are ordered" in line for line in log)
