"""Functional-area rules (``areas.toml``): the labels of the areas the offline labeller
names and the object labels that anchor and support each (see
:func:`inherit_sg.mapping.areas.label_area`).

Rules name object kinds of ``objects.toml``; each kind also stands for its synonyms, so
a map label such as "couch" or "bedside table" meets a rule written with "sofa" or
"nightstand".
"""

from __future__ import annotations

from functools import lru_cache

from inherit_sg.vocab import VocabularyError, load_table, string_list
from inherit_sg.vocab import objects as object_vocab

_FILE = "areas.toml"
_FIELDS = frozenset({"anchors", "support"})


def _with_synonyms(labels: tuple[str, ...]) -> frozenset[str]:
    """``labels`` plus every synonym of the kinds they name."""
    out = set(labels)
    for label in labels:
        kind = object_vocab.canonical_label(label)
        if kind is not None:
            out.add(kind)
            out.update(object_vocab.synonyms(kind))
    return frozenset(out)


@lru_cache(maxsize=1)
def area_rules_as_written() -> dict[str, tuple[tuple[str, ...], tuple[str, ...]]]:
    """Area label → (anchor labels, support labels) exactly as the file lists them, in
    file order."""
    table = load_table("areas").get("areas")
    if not isinstance(table, dict) or not table:
        raise VocabularyError(f'{_FILE}: needs at least one [areas."<label>"] table')
    out: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {}
    for label, entry in table.items():
        where = f'{_FILE} [areas."{label}"]'
        if not isinstance(entry, dict):
            raise VocabularyError(f"{where} must be a table")
        unknown = sorted(set(entry) - _FIELDS)
        if unknown:
            raise VocabularyError(f"{where}: unknown field {unknown[0]!r}")
        anchors = string_list(entry, "anchors", where)
        if not anchors:
            raise VocabularyError(f"{where}: 'anchors' needs at least one label")
        out[label.strip().lower()] = (anchors, string_list(entry, "support", where))
    return out


@lru_cache(maxsize=1)
def area_rules() -> dict[str, tuple[frozenset[str], frozenset[str]]]:
    """Area label → (anchor labels, support labels), each kind with its synonyms, in
    file order (the order breaks ties between equally good rules)."""
    return {
        label: (_with_synonyms(anchors), _with_synonyms(support))
        for label, (anchors, support) in area_rules_as_written().items()
    }


def area_labels() -> tuple[str, ...]:
    """The labels of every rule, in file order."""
    return tuple(area_rules_as_written())


def clear_caches() -> None:
    """Forget the parsed rules (after the file or ``DATA_DIR`` changed; tests)."""
    area_rules_as_written.cache_clear()
    area_rules.cache_clear()
