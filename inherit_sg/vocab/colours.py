"""Colours (``colours.toml``): the colour names perception measures with their sRGB
prototypes (:mod:`inherit_sg.perception.colour_names`), the request words that name each
colour and the shade words that qualify one."""

from __future__ import annotations

from functools import lru_cache
from typing import Any

from inherit_sg.vocab import VocabularyError, load_table, string_list

_FILE = "colours.toml"
RGB = tuple[int, int, int]


def _table() -> dict[str, Any]:
    table = load_table("colours").get("colours")
    if not isinstance(table, dict) or not table:
        raise VocabularyError(f"{_FILE}: needs at least one [colours.<name>] table")
    for name, entry in table.items():
        if not isinstance(entry, dict):
            raise VocabularyError(f"{_FILE} [colours.{name}] must be a table")
    return table


def _rgb(value: Any) -> RGB | None:
    if not isinstance(value, list) or len(value) != 3:
        return None
    if not all(isinstance(c, int) and not isinstance(c, bool) and 0 <= c <= 255 for c in value):
        return None
    return (value[0], value[1], value[2])


@lru_cache(maxsize=1)
def colour_names() -> tuple[str, ...]:
    """The colour names perception can give, in file order."""
    return tuple(name.strip().lower() for name in _table())


@lru_cache(maxsize=1)
def prototypes() -> dict[str, tuple[RGB, ...]]:
    """Colour name → its sRGB prototypes (0-255), the typical shade first."""
    out: dict[str, tuple[RGB, ...]] = {}
    for name, entry in _table().items():
        where = f"{_FILE} [colours.{name}]"
        value = entry.get("prototypes")
        if not isinstance(value, list) or not value:
            raise VocabularyError(f"{where}: 'prototypes' must be a non-empty list of [r, g, b]")
        shades = []
        for item in value:
            rgb = _rgb(item)
            if rgb is None:
                raise VocabularyError(
                    f"{where}: 'prototypes' entry {item!r} must be [r, g, b] with integers 0-255"
                )
            shades.append(rgb)
        out[name.strip().lower()] = tuple(shades)
    return out


@lru_cache(maxsize=1)
def colour_words() -> dict[str, str]:
    """Every word naming a colour in a request (the names themselves and their words) →
    the colour name; :class:`VocabularyError` when a word would name two colours."""
    out: dict[str, str] = {}
    for name, entry in _table().items():
        canonical = name.strip().lower()
        where = f"{_FILE} [colours.{name}]"
        for word in (canonical, *string_list(entry, "words", where)):
            if out.get(word, canonical) != canonical:
                raise VocabularyError(
                    f"{where}: 'words' entry {word!r} already names {out[word]!r}"
                )
            out[word] = canonical
    return out


@lru_cache(maxsize=1)
def shade_words() -> frozenset[str]:
    """Words that qualify a colour ("light", "dark", …)."""
    return frozenset(string_list(load_table("colours"), "shades", _FILE))


def clear_caches() -> None:
    """Forget the parsed tables (after the file or ``DATA_DIR`` changed; tests)."""
    for fn in (colour_names, prototypes, colour_words, shade_words):
        fn.cache_clear()
