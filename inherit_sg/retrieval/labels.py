"""Object labels of request words and of map labels, through the object vocabulary.

A request word names the kinds it covers ("couch" → sofa, "seat" → chair, sofa, …); a
word no vocabulary knows names itself, lemmatised ("toolboxes" → "toolbox") — any noun
phrase can be a target or a landmark. A map label is brought to its canonical kind
("bedside table" → nightstand; an annotator's slip mended, "chandellier" → chandelier)
so that both sides meet on one name.
"""

from __future__ import annotations

from functools import lru_cache

from inherit_sg.nlp import lemma_phrase
from inherit_sg.vocab import objects as object_vocab


def _clean(text: str) -> str:
    return " ".join(text.replace("_", " ").replace("-", " ").replace("#", " ").lower().split())


@lru_cache(maxsize=8192)
def request_labels(phrase: str) -> tuple[str, ...]:
    """The kinds a request phrase names, most typical first; an unknown phrase names
    itself, lemmatised."""
    text = _clean(phrase)
    if not text:
        return ()
    return object_vocab.labels_for(text) or (lemma_phrase(text),)


@lru_cache(maxsize=8192)
def map_label_kinds(label: str) -> tuple[str, ...]:
    """Canonical kind of a stored map label (``("sofa",)`` for "couch"); an unknown
    label is its own kind, lemmatised."""
    text = _clean(label)
    if not text:
        return ()
    canon = object_vocab.canonical_label(text) or _misspelt_kind(text)
    return (canon,) if canon else (lemma_phrase(text),)


def _misspelt_kind(text: str) -> str | None:
    """The kind a map label names when an annotator's slip is mended word by word
    ("chandellier", "picutre", "nighstand", "coutertop"); None when nothing changes or
    the mended label names no kind."""
    from inherit_sg.retrieval.rules.spelling import correct_word

    words = text.split()
    mended = [correct_word(w) or w for w in words]
    if mended == words:
        return None
    return object_vocab.canonical_label(" ".join(mended))
