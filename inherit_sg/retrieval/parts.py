"""Parts: "the bin with the yellow lid", "the chair with wheels".

A part phrase is split into colour / material words (the names perception measures:
:data:`~inherit_sg.perception.colour_names.COLOUR_NAMES`,
:data:`~inherit_sg.perception.material.MATERIAL_NAMES`) and the part noun. The object's
description and attribute values are searched for the noun (singular or plural); when
they do not mention it, a colour or material word of the phrase is compared with the
object's measured colour / material: the part may be what gave the object that colour.

- the noun is mentioned: ``PART_MENTIONED``;
- a qualifier agrees with a measured attribute (and none contradicts): ``PART_QUALIFIER``;
- a qualifier contradicts a measured attribute: ``PART_CONTRADICTED``;
- nothing known: no value (``None``) — the scorer's unknown similarity.
"""

from __future__ import annotations

import re
from typing import Any

from inherit_sg.perception.colour_names import COLOUR_NAMES
from inherit_sg.perception.material import MATERIAL_NAMES

PART_MENTIONED = 1.0
PART_QUALIFIER = 0.7
PART_CONTRADICTED = 0.1
_QUALIFIERS: dict[str, tuple[str, str]] = {
    **{c: ("colour", c) for c in COLOUR_NAMES},
    **{m: ("material", m) for m in MATERIAL_NAMES},
    "gray": ("colour", "grey"),
    "wooden": ("material", "wood"),
    "metallic": ("material", "metal"),
}
_WORD = re.compile(r"[a-z]+")
_FILLER = frozenset({"a", "an", "the", "with", "and", "its", "some", "of"})


def _stem(word: str) -> str:
    """Singular form of a regular plural ("wheels" → "wheel", "boxes" → "box")."""
    if len(word) > 4 and word.endswith(("ches", "shes", "xes", "sses")):
        return word[:-2]
    if len(word) > 3 and word.endswith("s") and not word.endswith("ss"):
        return word[:-1]
    return word


def split_part(phrase: str) -> tuple[dict[str, str], list[str]]:
    """Colour / material qualifiers (``{"colour": "yellow"}``) and the noun words of a
    part phrase ("yellow lid" → ``({"colour": "yellow"}, ["lid"])``)."""
    qualifiers: dict[str, str] = {}
    noun: list[str] = []
    for word in _WORD.findall(phrase.lower()):
        found = _QUALIFIERS.get(word)
        if found is not None and found[0] not in qualifiers:
            qualifiers[found[0]] = found[1]
        elif word not in _FILLER:
            noun.append(word)
    return qualifiers, noun


def _texts(description: str, attributes: dict[str, Any]) -> set[str]:
    words: set[str] = set(_WORD.findall(description.lower()))
    for value in attributes.values():
        items = value if isinstance(value, list | tuple | set) else [value]
        for item in items:
            if isinstance(item, str):
                words |= set(_WORD.findall(item.lower()))
    return {_stem(w) for w in words}


def part_sim(phrase: str, description: str, attributes: dict[str, Any]) -> tuple[float | None, str]:
    """Similarity of a node with ``description`` and measured ``attributes`` to having
    the part ``phrase``, with the evidence in words (None: nothing known)."""
    qualifiers, noun = split_part(phrase)
    words = _texts(description, attributes)
    if noun and all(_stem(w) in words for w in noun):
        return PART_MENTIONED, f"description mentions '{' '.join(noun)}'"
    agree: list[str] = []
    for key, wanted in qualifiers.items():
        have = attributes.get(key)
        if not isinstance(have, str) or not have or have.lower() == "unknown":
            continue
        if have.lower() != wanted:
            return PART_CONTRADICTED, f"{key} is {have.lower()}, not {wanted}"
        agree.append(f"{key} is {wanted}")
    part = " ".join(noun) or phrase
    if agree:
        return PART_QUALIFIER, f"{', '.join(agree)}; {part} not described"
    return None, f"{part} not described"
