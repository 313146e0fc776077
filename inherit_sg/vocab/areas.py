"""Functional-area rules (``areas.toml``): the labels of the areas the offline labeller
names and the object labels that anchor and support each (see
:func:`inherit_sg.mapping.areas.label_area`)."""

from __future__ import annotations

from functools import lru_cache

from inherit_sg.vocab import VocabularyError, load_table, string_list

_FILE = "areas.toml"


@lru_cache(maxsize=1)
def area_rules() -> dict[str, tuple[frozenset[str], frozenset[str]]]:
    """Area label → (anchor labels, support labels), in file order (the order breaks
    ties between equally good rules)."""
    table = load_table("areas").get("areas")
    if not isinstance(table, dict) or not table:
        raise VocabularyError(f'{_FILE}: needs at least one [areas."<label>"] table')
    out: dict[str, tuple[frozenset[str], frozenset[str]]] = {}
    for label, entry in table.items():
        where = f'{_FILE} [areas."{label}"]'
        if not isinstance(entry, dict):
            raise VocabularyError(f"{where} must be a table")
        anchors = string_list(entry, "anchors", where)
        if not anchors:
            raise VocabularyError(f"{where}: 'anchors' needs at least one label")
        support = string_list(entry, "support", where)
        out[label.strip().lower()] = (frozenset(anchors), frozenset(support))
    return out


def area_labels() -> tuple[str, ...]:
    """The labels of every rule, in file order."""
    return tuple(area_rules())


def clear_caches() -> None:
    """Forget the parsed rules (after the file or ``DATA_DIR`` changed; tests)."""
    area_rules.cache_clear()
