"""Offline parser behaviour: text checks, analysis with spaCy (contractions, sentences,
spelling), vocabulary lookups, negation scope, weights, word order, and a missing language
model. Arbitrary input is fuzzed in test_parse_fuzz.py."""

from __future__ import annotations

import pytest

from inherit_sg.errors import QueryTextError
from inherit_sg.retrieval import RuleParser, parse_rules
from inherit_sg.retrieval.labels import request_labels
from inherit_sg.retrieval.rules import MAX_QUERY_CHARS, check_query_text, parse_uncached, tokenize
from inherit_sg.retrieval.rules.spelling import correct_spelling
from inherit_sg.vocab.rooms import room_type


@pytest.mark.parametrize(
    ("bad", "message"),
    [
        ("", "empty"),
        ("   \n\t ", "empty"),
        ("x" * (MAX_QUERY_CHARS + 1), f"{MAX_QUERY_CHARS + 1} characters"),
        (b"the chair", "must be text"),
        (None, "must be text"),
        (42, "must be text"),
        ("the chair\x00", "control character"),
        ("?!? 123 ...", "no words"),
    ],
)
def test_bad_text_raises_query_text_error(bad: object, message: str) -> None:
    with pytest.raises(QueryTextError, match=message):
        check_query_text(bad)
    with pytest.raises(QueryTextError):
        parse_rules(bad)  # type: ignore[arg-type]


def test_long_but_allowed_text_parses() -> None:
    text = ("the red chair " * 80)[:MAX_QUERY_CHARS]
    assert parse_rules(text).target.labels == ("chair",)


def test_tokenize_normalises() -> None:
    assert tokenize("Where's the TV-stand? I can't see it") == [
        "where", "is", "the", "tv", "stand", ",", "i", "can", "not", "see", "it",
    ]  # fmt: skip
    assert tokenize("the productive_work_environment") == [
        "the",
        "productive",
        "work",
        "environment",
    ]
    assert tokenize("It isn’t red!") == ["it", "is", "not", "red"]
    assert tokenize("CoffeeTable3") == ["coffee", "table", "3"]


def test_sentences_and_spelling() -> None:
    assert tokenize("This is a bed.it has a blue blanket") == [
        "this", "is", "a", "bed", ",", "it", "has", "a", "blue", "blanket",
    ]  # fmt: skip
    text, fixes = correct_spelling("fidn teh chager on my desk, thats it")
    assert text == "find the charger on my desk, that's it"
    assert ("chager", "charger") in fixes
    # real words and names stay as written
    assert correct_spelling("the TV by the credenza")[1] == []
    parsed = parse_rules("wheres teh walet")
    assert parsed.target.labels == ("wallet",)
    # three-letter slips: a dropped letter of a thing's name, never of any other word
    assert correct_spelling("the trashcan under the dsk")[0] == "the trashcan under the desk"
    assert correct_spelling("wll sed")[1] == []
    assert any("spelling" in note for note in parsed.notes)


def test_contractions_are_restored_as_whole_words() -> None:
    # any case for longer forms, the longest form first ("its an" before "its a")
    assert correct_spelling("Its an odd one, Dont move it")[0] == "it's an odd one, don't move it"
    # one-letter forms only in lower case, and never inside a word or before an apostrophe
    assert correct_spelling("can u find the U-shaped sofa")[0] == ("can you find the U-shaped sofa")
    assert correct_spelling("the dont's list in the rm")[0] == "the dont's list in the room"


def test_synonyms_plurals_and_open_vocabulary() -> None:
    assert request_labels("couches") == ("sofa",)
    assert request_labels("Fridge") == ("refrigerator",)
    assert request_labels("flux capacitors") == ("flux capacitor",)
    assert room_type("restroom") == "bathroom"
    assert room_type("atrium") is None
    unknown = parse_rules("where is the flux capacitor")
    assert unknown.target.labels == ("flux capacitor",) and unknown.target.noun == "flux capacitor"
    ottomans = parse_rules("the two ottomans by the window")  # spaCy's lemma is "othman"
    assert ottomans.target.labels == ("ottoman",) and ottomans.target.plural


def test_negation_scopes_exactly_one_constraint() -> None:
    parsed = parse_rules("the red mug not on the table next to the window in the kitchen")
    negated = {c.id: c.negated for c, _ in parsed.walk()}
    assert [c.kind for c in parsed.constraints] == ["label", "attribute", "relation", "room"]
    assert negated == {"c1": False, "c2": False, "c3": True, "c3.1": False, "c4": False}
    double = parse_rules("a chair that is not not red")
    assert [c.negated for c in double.of_kind("attribute")] == [False]


def test_room_and_floor_phrases_attach_to_the_head() -> None:
    parsed = parse_rules("the mug on the table next to the window in the kitchen upstairs")
    table = parsed.of_kind("relation")[0]
    nested_kinds = [c.kind for c, _ in parsed.walk()]
    assert nested_kinds == ["label", "relation", "relation", "room", "floor"]
    assert table.landmark.target.labels == ("table",)  # type: ignore[union-attr]


def test_word_order_does_not_matter() -> None:
    a = parse_rules("the red mug in the kitchen")
    b = parse_rules("in the kitchen, the red mug")
    assert a.target == b.target
    assert [c.to_dict() | {"text": ""} for c in a.constraints] == [
        c.to_dict() | {"text": ""} for c in b.constraints
    ]


def test_politeness_and_filler_are_ignored() -> None:
    plain = parse_rules("the couch in the living room")
    for text in (
        "Could you please take me to the couch in the living room?",
        "hey robot, I'm looking for the couch in the living room, thanks",
        "Can you show me where the couch in the living room is located?",
    ):
        polite = parse_rules(text)
        assert polite.target == plain.target
        assert [c.kind for c in polite.constraints] == [c.kind for c in plain.constraints]


def test_emphasis_and_hedges_change_weights() -> None:
    emph = parse_rules("a chair that must be red")
    hedge = parse_rules("a chair, ideally red")
    assert emph.of_kind("attribute")[0].weight == pytest.approx(0.9)
    assert hedge.of_kind("attribute")[0].weight == pytest.approx(0.3)


def test_global_and_empty_requests_say_why() -> None:
    global_q = parse_rules("What purpose does this space primarily serve?")
    assert global_q.no_target_reason is not None and "global" in global_q.no_target_reason
    nothing = parse_rules("thanks a lot")
    assert nothing.no_target_reason is not None and not nothing.has_target


def test_parser_object_and_cache() -> None:
    parser = RuleParser()
    first = parser.parse("the lamp next to the bed")
    assert parser.parse("the lamp next to the bed") is first
    assert parse_uncached("the lamp next to the bed") == first


def test_missing_language_model_names_the_install_command(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import inherit_sg.nlp as nlp

    monkeypatch.setattr(nlp, "MODEL_PACKAGES", ("no_such_spacy_model",))
    with pytest.raises(nlp.LanguageModelError, match="pip install"):
        nlp._load()


def test_language_pipeline_multiplies_with_numpy() -> None:
    """The loaded pipeline uses numpy's BLAS (faster than blis on request-sized inputs),
    and loading it leaves the process's default operations as they were."""
    from thinc.api import get_current_ops

    import inherit_sg.nlp as nlp

    pipeline = nlp.english()
    for name in ("tok2vec", "tagger", "parser"):
        assert getattr(pipeline.get_pipe(name).model.ops, "use_blis", True) is False
    doc = nlp.analyse("put the mug on the shelf above the desk")
    assert [t.dep_ for t in doc if t.text == "mug"] == ["dobj"]
    assert getattr(get_current_ops(), "use_blis", True) is True


def test_where_the_speaker_stands_is_a_viewpoint() -> None:
    """An opening "from X" with no comma, and a first sentence that places the speaker
    before a question about another thing, both give a viewpoint, not the target."""
    shelf = parse_rules("from the door the third shelf")
    assert shelf.target.labels == ("shelf",)
    assert shelf.viewpoint is not None and shelf.viewpoint.kind == "from"
    assert shelf.viewpoint.landmark.target.labels == ("door",)
    asked = parse_rules(
        "I am sitting on the sofa and the TV is in front of me. Is the lamp behind me?"
    )
    assert asked.target.labels == ("lamp",)
    assert asked.viewpoint is not None and asked.viewpoint.landmark.target.labels == ("sofa",)
