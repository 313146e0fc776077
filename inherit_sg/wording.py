"""Small English helpers shared by generated texts (summaries, descriptions, requests)."""

from __future__ import annotations


def article(phrase: str) -> str:
    """``a`` or ``an`` for ``phrase`` (by its first letter; ``use…``/``uni…`` take ``a``)."""
    first = phrase.lower()
    if first.startswith(("use", "uni", "uti")):
        return "a"
    return "an" if first[:1] in tuple("aeiou") else "a"


def with_article(phrase: str, *, capital: bool = False) -> str:
    """``phrase`` preceded by its indefinite article (``An`` when ``capital``)."""
    art = article(phrase)
    return f"{art.capitalize() if capital else art} {phrase}"
