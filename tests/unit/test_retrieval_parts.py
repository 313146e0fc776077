"""Parts ("the bin with the yellow lid", "the chair with wheels"): mentioned in the
description, implied by a measured colour, contradicted by it, or unknown."""

from __future__ import annotations

import pytest

from inherit_sg.retrieval.constraints import AttributeConstraint
from inherit_sg.retrieval.parts import (
    PART_CONTRADICTED,
    PART_MENTIONED,
    PART_QUALIFIER,
    part_sim,
    split_part,
)
from inherit_sg.retrieval.scoring import UNKNOWN_SIM, attribute_sim
from tests.unit.retrieval_rank import rank, request
from tests.unit.viewer_fixtures import row_snapshot


@pytest.mark.parametrize(
    ("phrase", "qualifiers", "noun"),
    [
        ("yellow lid", {"colour": "yellow"}, ["lid"]),
        ("blue mattress", {"colour": "blue"}, ["mattress"]),
        ("wheels", {}, ["wheels"]),
        ("a gray metal frame", {"colour": "grey", "material": "metal"}, ["frame"]),
        ("seat cushion", {}, ["seat", "cushion"]),
    ],
)
def test_split_part(phrase: str, qualifiers: dict[str, str], noun: list[str]) -> None:
    assert split_part(phrase) == (qualifiers, noun)


@pytest.mark.parametrize(
    ("phrase", "description", "attributes", "expected"),
    [
        ("yellow lid", "a grey bin with a yellow lid", {"colour": "grey"}, PART_MENTIONED),
        ("wheels", "an office chair on five wheels", {}, PART_MENTIONED),
        ("wheel", "an office chair on wheels", {}, PART_MENTIONED),
        ("boxes", "a shelf with a box", {}, PART_MENTIONED),
        ("yellow lid", "a bin", {"colour": "yellow"}, PART_QUALIFIER),
        ("wooden legs", "a table", {"material": "wood"}, PART_QUALIFIER),
        ("wood legs", "a table", {"material": "wood", "colour": "brown"}, PART_QUALIFIER),
        ("yellow lid", "a bin", {"colour": "blue"}, PART_CONTRADICTED),
        ("yellow lid", "a bin", {"colour": "unknown"}, None),
        ("wheels", "a chair", {"colour": "red"}, None),
        ("handle", "a mug", {"parts": ["handle", "rim"]}, PART_MENTIONED),
    ],
)
def test_part_sim(
    phrase: str, description: str, attributes: dict[str, object], expected: float | None
) -> None:
    sim, why = part_sim(phrase, description, attributes)
    assert sim == expected, why


def test_attribute_sim_with_key_part() -> None:
    snap = row_snapshot()
    lid = AttributeConstraint(key="part", value="yellow lid")
    assert attribute_sim(snap, "obj:bin1", lid) == (1.0, "description mentions 'lid'")
    assert attribute_sim(snap, "obj:bin2", lid) == (PART_CONTRADICTED, "colour is blue, not yellow")
    wheels = AttributeConstraint(key="part", value="wheels")
    assert attribute_sim(snap, "obj:ch1", wheels) == (UNKNOWN_SIM, "wheels not described")


def test_scoring_finds_the_bin_with_the_yellow_lid() -> None:
    parsed = request("trash can", AttributeConstraint(key="part", value="yellow lid"))
    ranked, _ = rank(row_snapshot(), parsed)
    assert [c.id for c in ranked[:2]] == ["obj:bin1", "obj:bin2"]
