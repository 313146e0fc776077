"""A map label more general than the word asked for ("light" for "ceiling light") is a
weaker match than the word itself, graded by how far up the vocabulary it lies; and
"closest to the front door" measures to the exterior door, not to any door."""

from __future__ import annotations

from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.constraints import LabelConstraint
from inherit_sg.retrieval.match import (
    HYPERNYM,
    HYPERNYM_RESEMBLANCE,
    HYPERNYM_STEP,
    resolve_matches,
)
from inherit_sg.retrieval.snapshot import MapSnapshot
from tests.unit.retrieval_fixtures import floor_snapshot, hash_similarity
from tests.unit.retrieval_rank import rank


def _snap(objects: list[tuple[str, str, float, float]]) -> MapSnapshot:
    """One floor, no rooms; objects ``(key, label, x, y)``."""
    return floor_snapshot([(key, label, x, y, None) for key, label, x, y in objects])


def _labels(snap: MapSnapshot, word: str) -> dict[str, float]:
    con = LabelConstraint(id="c1", labels=(word,), noun=word)
    found = resolve_matches(con, "object", snap, hash_similarity())
    assert found is not None
    return {label: value for label, (value, _) in found.items()}


def test_a_more_general_map_label_matches_less_the_further_up_it_lies() -> None:
    snap = _snap([("a", "light", 0, 0), ("b", "lamp", 3, 0), ("c", "rug", 6, 0)])

    def near(value: float, base: float) -> bool:
        return base <= value <= base + HYPERNYM_RESEMBLANCE

    assert near(_labels(snap, "ceiling light")["light"], HYPERNYM)
    table_lamp = _labels(snap, "table lamp")
    assert near(table_lamp["lamp"], HYPERNYM)
    assert near(table_lamp["light"], HYPERNYM - HYPERNYM_STEP)
    assert table_lamp["lamp"] > table_lamp["light"]
    assert near(_labels(snap, "bath mat")["rug"], HYPERNYM)
    # the word itself still wins, and a general request is not lowered
    assert _labels(snap, "lamp")["lamp"] == 1.0


def test_closest_to_the_front_door_measures_to_the_exterior_door() -> None:
    snap = _snap(
        [
            ("front", "exterior door", 0, 0),
            ("inner", "door", 10, 0),
            ("m1", "mirror", 1.5, 0),
            ("m2", "mirror", 10.5, 0),
        ]
    )
    ranked, _ = rank(snap, parse_rules("the mirror closest to the front door"))
    assert ranked[0].id == "obj:m1"
    # a map that knows no exterior door measures to every door alike
    plain = _snap([("inner", "door", 10, 0), ("m1", "mirror", 1.5, 0), ("m2", "mirror", 10.5, 0)])
    ranked, _ = rank(plain, parse_rules("the mirror closest to the front door"))
    assert ranked[0].id == "obj:m2"


def test_a_synonym_of_a_kind_named_like_a_general_word_means_the_kind_alone() -> None:
    snap = _snap([("d", "decoration", 0, 0), ("p", "painting", 3, 0), ("v", "vase", 6, 0)])

    def asked(noun: str) -> dict[str, float]:
        con = LabelConstraint(id="c1", labels=("decoration",), noun=noun)
        found = resolve_matches(con, "object", snap, hash_similarity())
        assert found is not None
        return {label: value for label, (value, _) in found.items() if value >= 0.85}

    # a knickknack is an ornament (the decoration kind), not a painting or a vase
    assert set(asked("knickknack")) == {"decoration"}
    assert set(asked("ornaments")) == {"decoration"}
    # the general word, and the phrases it shares with its kind, mean every decoration
    assert set(asked("decorations")) == {"decoration", "painting", "vase"}
    assert set(asked("decor")) == {"decoration", "painting", "vase"}


def test_not_the_closest_one_is_any_other() -> None:
    snap = _snap(
        [
            ("w", "window", 0, 0),
            ("m1", "monitor", 1.0, 0),
            ("m2", "monitor", 4.0, 0),
            ("m3", "monitor", 7.0, 0),
        ]
    )
    closest, _ = rank(snap, parse_rules("the monitor closest to the window"))
    assert closest[0].id == "obj:m1"
    other, _ = rank(snap, parse_rules("the monitor which is not closest to the window"))
    assert other[0].id != "obj:m1" and other[-1].id in ("obj:m1", "obj:w")


def test_a_map_label_an_annotator_misspelt_names_its_kind() -> None:
    from inherit_sg.retrieval.labels import map_label_kinds

    assert map_label_kinds("chandellier") == ("chandelier",)
    assert map_label_kinds("nighstand") == ("nightstand",)
    assert map_label_kinds("coutertop") == ("counter",)
    # a real word stands as written; a word nothing mends names itself
    assert map_label_kinds("tablet") == ("tablet",)
    assert map_label_kinds("unkown") == ("unkown",)
