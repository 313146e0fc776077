"""Count superlatives: "the shelf with the most books", "which room has the fewest
chairs", "which floor has the most bedrooms" rank candidates by how many of the counted
kind each holds (parsed by the rules, ranked on a hand-built snapshot)."""

from __future__ import annotations

from inherit_sg.model import Layer, make_id
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.candidates import Candidates
from inherit_sg.retrieval.graph_checks import GraphChecker, Landmarks
from inherit_sg.retrieval.plan import Compiler, NodeSpec
from inherit_sg.retrieval.ranking import rank_spec
from inherit_sg.retrieval.scoring import Scored, Scorer
from inherit_sg.retrieval.snapshot import MapSnapshot
from tests.unit.retrieval_fixtures import floor_snapshot, hash_similarity


def _ranked(snap: MapSnapshot, text: str) -> list[Scored]:
    """Rank every node of the target's layer for ``text``, as the engine would."""
    plan = Compiler(snap, hash_similarity()).compile(parse_rules(text))
    scorer = Scorer(snap, GraphChecker(snap))

    def generate(spec: NodeSpec, marks: dict[str, Landmarks]) -> Candidates:
        cands = Candidates()
        pool = {"object": snap.objects, "room": snap.rooms, "floor": snap.floors}[spec.layer]
        for nid in pool:
            cands.add(nid, "test")
        return cands

    return rank_spec(plan.target, scorer, generate, [])


def _house() -> MapSnapshot:
    """A kitchen with one chair and a shelf holding three books beside a shelf with one;
    a dining room with three chairs."""
    objects = [
        ("shelf-a", "shelf", 1.0, 1.0, "kitchen"),
        ("book-1", "book", 1.1, 1.0, "kitchen"),
        ("book-2", "book", 0.9, 1.1, "kitchen"),
        ("book-3", "book", 1.0, 0.9, "kitchen"),
        ("shelf-b", "shelf", 4.0, 1.0, "kitchen"),
        ("book-4", "book", 4.1, 1.0, "kitchen"),
        ("chair-k", "chair", 3.0, 3.0, "kitchen"),
        ("chair-1", "chair", 11.0, 1.0, "dining"),
        ("chair-2", "chair", 12.0, 1.0, "dining"),
        ("chair-3", "chair", 13.0, 1.0, "dining"),
    ]
    return floor_snapshot(objects, {"kitchen": ("kitchen", 2.5), "dining": ("dining room", 12.0)})


def test_the_shelf_with_the_most_books_holds_three() -> None:
    ranked = _ranked(_house(), "the shelf with the most books")
    assert ranked[0].id == make_id(Layer.OBJECT, "shelf-a")
    sup = next(t for t in ranked[0].terms.values() if t.kind == "superlative")
    assert sup.why.startswith("most: 3")


def test_the_shelf_with_the_fewest_books_holds_one() -> None:
    ranked = _ranked(_house(), "the shelf with the fewest books")
    assert ranked[0].id == make_id(Layer.OBJECT, "shelf-b")


def test_which_room_has_the_most_chairs_is_a_room() -> None:
    ranked = _ranked(_house(), "which room has the most chairs")
    assert ranked[0].id == make_id(Layer.ROOM, "dining")
    ranked = _ranked(_house(), "which room has the fewest chairs")
    assert ranked[0].id == make_id(Layer.ROOM, "kitchen")
