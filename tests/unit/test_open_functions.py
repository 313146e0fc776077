"""A purpose the function vocabulary does not know ("something to weigh myself on") is
kept in the request's own words and matched to the map labels closest in meaning, with
the real text embedder; the thing a light verb takes in a purpose phrase ("a spot to
make a phone call") is what the request seeks."""

from __future__ import annotations

from inherit_sg.embed import get_text_embedder
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.constraints import FunctionConstraint
from inherit_sg.retrieval.match import OPEN_FUNCTION_MAX, resolve_matches
from inherit_sg.retrieval.similarity import PhraseSimilarity
from tests.unit.retrieval_fixtures import floor_snapshot, hash_similarity

LABELS = ["scale", "blanket", "sofa", "stairs", "painting", "window", "toilet", "sink", "tv"]


def _open_function(text: str) -> FunctionConstraint:
    parsed = parse_rules(text)
    found = [c for c in parsed.constraints if isinstance(c, FunctionConstraint)]
    assert len(found) == 1, parsed
    assert found[0].labels == ()  # not in the vocabulary: no kinds listed
    return found[0]


def _matches(con: FunctionConstraint) -> dict[str, float]:
    snap = floor_snapshot([(f"o{k}", lab, 2.0 * k, 0.0, None) for k, lab in enumerate(LABELS)])
    found = resolve_matches(con, "object", snap, PhraseSimilarity(get_text_embedder()))
    assert found is not None
    return {label: value for label, (value, _) in found.items()}


def test_an_unknown_purpose_is_kept_in_the_requests_words() -> None:
    con = _open_function("Could you find me something to weigh myself on?")
    assert "weigh" in con.function
    assert parse_rules("Could you find me something to weigh myself on?").target.any


def test_an_unknown_purpose_matches_the_closest_labels() -> None:
    weigh = _matches(_open_function("Could you find me something to weigh myself on?"))
    assert max(weigh, key=weigh.__getitem__) == "scale"
    assert weigh["scale"] == OPEN_FUNCTION_MAX
    wrap = _matches(_open_function("I need something to wrap myself in"))
    assert max(wrap, key=wrap.__getitem__) == "blanket"
    # labels far behind the closest one do not count at all
    assert "stairs" not in weigh and "painting" not in wrap


def test_a_purpose_unlike_every_label_matches_nothing() -> None:
    con = FunctionConstraint(function="xqzt", text="xqzt")
    assert _matches(con) == {}


def test_the_thing_a_light_verb_takes_in_a_purpose_phrase_is_sought() -> None:
    parsed = parse_rules("What's a good spot to make a phone call upstairs?")
    assert parsed.target.labels == ("phone",)
    assert parse_rules("somewhere to find the remote").target.labels == ("remote",)


def test_a_statement_naming_no_known_problem_says_what_is_needed() -> None:
    text = "I wonder how much I weigh. Is there something on the second floor that could help?"
    con = _open_function(text)
    assert "weigh" in con.text
    assert max(_matches(con), key=_matches(con).__getitem__) == "scale"
    # a statement about a thing, or a request that names what it wants, is not one
    assert not [
        c
        for c in parse_rules("The chair is brown. Find it.").constraints
        if isinstance(c, FunctionConstraint)
    ]


def test_an_unknown_verb_the_speaker_wants_to_do_is_a_purpose() -> None:
    assert "floss" in _open_function("I want to floss. Show me where.").function
    assert "floss" in _open_function("Where can I floss?").function
    # with a thing the vocabulary knows, the thing is sought
    assert parse_rules("I want to inspect the heater").target.labels == ("heater",)


def _matches_among(con: FunctionConstraint, labels: list[str]) -> dict[str, tuple[float, str]]:
    snap = floor_snapshot([(f"o{k}", lab, 2.0 * k, 0.0, None) for k, lab in enumerate(labels)])
    found = resolve_matches(con, "object", snap, PhraseSimilarity(get_text_embedder()))
    assert found is not None
    return found


def test_an_unknown_purpose_worded_like_a_known_one_reads_as_that_function() -> None:
    labels = ["speaker", "guitar", "book", "phone", "trash can", "blanket"]
    # "make a telephone call" is no phrasing of the vocabulary, but close to "make phone call"
    con = FunctionConstraint(function="make a telephone call", text="make a telephone call")
    found = _matches_among(con, labels)
    assert max(found, key=lambda k: found[k][0]) == "phone"
    assert "read as 'make" in found["phone"][1] and "'make a call'" in found["phone"][1]
    # a single word is not read by its nearest phrasing: "wrap" looks like "wrapper" (a
    # kind of trash) but means something to wrap oneself in
    wrap = _matches_among(_open_function("I need something to wrap myself in"), labels)
    assert max(wrap, key=lambda k: wrap[k][0]) == "blanket"
    assert "trash can" not in wrap


def test_the_vocabularys_phrasings_are_stacked_once_per_list() -> None:
    sim = hash_similarity()
    first = sim.fixed_vectors("phrases", ["make phone call", "listen to music"])
    assert first.shape[0] == 2
    assert sim.fixed_vectors("phrases", ["make phone call", "listen to music"]) is first
    # another list under the same key is stacked anew
    other = sim.fixed_vectors("phrases", ["make phone call"])
    assert other.shape[0] == 1 and other is not first
