"""Indefinite articles in generated summaries."""

from __future__ import annotations

import pytest

from inherit_sg.mapping.areas import summarise_area
from inherit_sg.wording import article, with_article


@pytest.mark.parametrize(
    ("phrase", "expected"),
    [("entrance area", "an"), ("office", "an"), ("kitchen", "a"), ("utility room", "a")],
)
def test_article(phrase: str, expected: str) -> None:
    assert article(phrase) == expected


def test_capitalised_article() -> None:
    assert with_article("entrance area", capital=True) == "An entrance area"


def test_area_summary_uses_an() -> None:
    assert summarise_area("entrance area", ["door"]).startswith("An entrance area with")
