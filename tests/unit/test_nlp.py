"""The English pipeline's attribute-ruler index finds exactly what spaCy's matcher finds."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from inherit_sg.nlp import english, known_lemma, lemma_phrase
from inherit_sg.nlp.attribute_index import UnsupportedPattern, build_index, speed_up

DEV = Path(__file__).resolve().parents[1] / "data" / "dev_requests"

# Texts that reach the ruler's rarer patterns: two-token rules, regular expressions,
# dependency tests, spaces and contractions.
UNUSUAL = [
    "y'all gonna love it, c'mon let's go, I gotta see",
    "I ain't got nothin' on the shelf, it aint here",
    "There are  two\n\n spaces,\tand tabs",
    "whether or not it is, do it; did you? he has had it",
    "there's a lamp and there are two chairs, give it to me",
    "",
    "¿qué? 🙂 ###",
]


def _texts() -> list[str]:
    texts = list(UNUSUAL)
    for path in sorted(DEV.glob("*.jsonl")):
        texts += [json.loads(line)["text"] for line in path.read_text().splitlines() if line]
    return texts


def _ruler_inputs(texts: list[str]) -> list:  # type: ignore[type-arg]
    """Documents as they reach the attribute ruler (tagged and parsed, nothing more)."""
    nlp = english()
    with nlp.select_pipes(disable=["attribute_ruler", "lemmatizer"]):
        return [nlp(text) for text in texts]


def test_index_finds_the_matchers_matches() -> None:
    ruler = english().get_pipe("attribute_ruler")
    index = build_index(ruler)  # type: ignore[arg-type]
    texts = _texts()
    assert len(texts) > 1000
    docs = _ruler_inputs(texts)
    for text, doc in zip(texts, docs, strict=True):
        expected = sorted(
            (int(ruler.vocab.strings[key]), key, start, end)
            for key, start, end in ruler.matcher(doc, allow_missing=True, as_spans=False)  # type: ignore[attr-defined]
        )
        assert index.match(doc) == expected, text


def test_loaded_pipeline_uses_the_index_and_keeps_its_annotations() -> None:
    ruler = english().get_pipe("attribute_ruler")
    assert ruler.match.__self__.__class__.__name__ == "AttributeIndex"  # type: ignore[attr-defined]
    doc = english()("y'all gonna find the mug that isn't on the shelf")
    assert [t.lemma_ for t in doc][:3] == ["you", "all", "go"]
    negation = next(t for t in doc if t.lower_ == "n't")
    assert (negation.pos_, negation.lemma_, str(negation.morph)) == ("PART", "not", "Polarity=Neg")
    assert next(t for t in doc if t.lower_ == "is").pos_ == "AUX"


def test_pattern_of_another_form_leaves_the_ruler_alone() -> None:
    from spacy.lang.en import English

    nlp = English()
    ruler = nlp.add_pipe("attribute_ruler")
    ruler.add([[{"LOWER": "very", "OP": "+"}, {"TAG": "JJ"}]], {"LEMMA": "really"})  # type: ignore[attr-defined]
    with pytest.raises(UnsupportedPattern, match="OP"):
        build_index(ruler)  # type: ignore[arg-type]
    assert speed_up(ruler) is False  # type: ignore[arg-type]
    assert "match" not in vars(ruler)


def test_lemma_lists_tell_nouns_from_verbs() -> None:
    assert known_lemma("cartridge", "noun") and not known_lemma("cartridge", "verb")
    assert known_lemma("play", "verb") and known_lemma("play", "noun")
    assert not known_lemma("feeder", "adj")


def test_unknown_plural_after_a_sibilant_loses_es() -> None:
    assert lemma_phrase("kids lunchboxes") == "kids lunchbox"
    assert lemma_phrase("benches") == "bench"
    assert lemma_phrase("atlas") == "atlas"
