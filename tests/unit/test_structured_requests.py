"""Requests written by software (step labels, key/value pairs, calls, JSON, paths,
search-box words) are read as plain phrases; text a person wrote is left as it is."""

from __future__ import annotations

import pytest

from inherit_sg.retrieval.rules import parse_uncached
from inherit_sg.retrieval.rules.structured import plain_request


@pytest.mark.parametrize(
    ("text", "phrase"),
    [
        ("label:ceiling_fan room:master_bedroom", "the ceiling fan in the master bedroom"),
        ("obj=hammer; area=garage; surface=workbench", "the hammer on the workbench in the garage"),
        (
            "find_object(name='laptop', near='desk', room='office')",
            "the laptop near the desk in the office",
        ),
        ('navigate_to("sink", room="kitchen")', "the sink in the kitchen"),
        ('objective: locate(cup) where cup.on == "nightstand"', "the cup on the nightstand"),
        ('query{"noun":"lamp","rel":"next_to","ref":"bed"}', "the lamp next to the bed"),
        ('{"find": "power strip", "under": "desk"}', "the power strip under the desk"),
        ("kitchen/counter/blender", "the blender at the counter in the kitchen"),
        (
            "target: chair; attributes: [leather, black]; room: lobby",
            "the leather  black chair in the lobby",
        ),
        (
            'object="trash bin"; near="printer"; room!="kitchen"',
            "the trash bin near the printer, not in the kitchen",
        ),
        (
            'query="desk lamp", room="study", exclude_color="white"',
            "the desk lamp in the study, not white",
        ),
        ("target=fire_alarm; floor=ground", "the fire alarm on the ground floor"),
        ("object: printer; floor: 2; room: copy room", "the printer in the copy room on floor 2"),
        (
            "item: piano; hint: living room, against the wall",
            "the piano in the living room against the wall",
        ),
        ("Step 4: pick up the stapler", "pick up the stapler"),
        ("Subtask 2/5: go to the fridge", "go to the fridge"),
        (
            "Plan: (1) go to the pantry (2) find the rice cooker",
            "go to the pantry. find the rice cooker",
        ),
        ("fire extinguisher floor 2", "fire extinguisher on floor 2"),
        ("fridge -kitchen", "fridge not kitchen"),
        ("hand towel, powder room", "hand towel in the powder room"),
    ],
)
def test_software_text_is_read_as_a_phrase(text: str, phrase: str) -> None:
    got, note = plain_request(text)
    assert got == phrase
    assert note is not None and "written by software" in note


@pytest.mark.parametrize(
    "text",
    [
        "the mug on the table next to the chair",
        "Note: the lamp by the bed",
        "Kitchen: the mug on the counter",
        "the time is 3:30, where is the clock",
        "go to the whiteboard in conference room B",
        "the t-shirt on the bed",
        "wheres the torch, powers out in the garage",
        "Goal: find the red mug",  # a label, then the sentence itself
    ],
)
def test_human_text_keeps_its_words(text: str) -> None:
    got, _ = plain_request(text)
    assert got.lower().endswith(text.lower().split(": ", 1)[-1])


def test_the_trace_says_how_software_text_was_read() -> None:
    parsed = parse_uncached("req: towel_rack; loc: bathroom; not: guest bath")
    assert parsed.target.labels == ("towel rack",)
    assert any("written by software (key/value pairs)" in note for note in parsed.notes)
    rooms = [(c.type, c.negated) for c in parsed.constraints if c.kind == "room"]  # type: ignore[attr-defined]
    assert ("bathroom", False) in rooms and ("bathroom", True) in rooms


def test_a_call_the_parser_cannot_read_as_a_request_stays_text() -> None:
    # "compute" asks for nothing; its words are parsed as they stand
    got, note = plain_request("compute(area=kitchen)")
    assert note is None and got == "compute(area=kitchen)"
