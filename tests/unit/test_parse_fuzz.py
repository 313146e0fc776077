"""No text crashes the request parser: 10,000 generated strings of every shape (unicode,
empty, whitespace, 10 KB, binary-looking, punctuation, word salad of request words)
either parse into a well-formed result or raise :class:`QueryTextError` naming what is
wrong with the text."""

from __future__ import annotations

import json

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from inherit_sg.errors import QueryTextError
from inherit_sg.retrieval import ParsedQuery
from inherit_sg.retrieval.rules import parse_uncached

# Words that drive the grammar into its branches (frames, viewpoints, negation, ordinals,
# relative clauses, placements, parts) in any order.
_WORDS = (
    "the", "a", "this", "is", "it", "there", "are", "not", "no", "but", "except", "any",
    "one", "ones", "other", "that", "which", "does", "have", "with", "without", "of", "and",
    "or", "to", "from", "facing", "face", "if", "you", "as", "come", "through", "back",
    "left", "right", "middle", "second", "third", "last", "leftmost", "larger", "closest",
    "farthest", "between", "next", "on", "in", "corner", "wall", "against", "center",
    "room", "kitchen", "upstairs", "floor", "2", "chair", "chairs", "bed", "mug", "table",
    "door", "lid", "wheels", "red", "wooden", "big", "select", "walk", "over", "find",
    "where", "can", "i", "sit", "something", "place", "my", "hands", "dirty", ".", ",", "?",
    "!", ";", "'s", "n't", "-", "(", ")", "\"", "…",
)  # fmt: skip


def _word_salad() -> st.SearchStrategy[str]:
    return st.lists(st.sampled_from(_WORDS), min_size=0, max_size=40).map(" ".join)


def _binaryish() -> st.SearchStrategy[str]:
    return st.binary(max_size=200).map(lambda b: b.decode("latin-1"))


def _long() -> st.SearchStrategy[str]:
    return st.tuples(_word_salad(), st.integers(min_value=1, max_value=400)).map(
        lambda t: ((t[0] or "chair ") + " ") * t[1]
    )


TEXTS = st.one_of(
    st.text(max_size=200),
    st.text(alphabet=st.characters(codec="utf-8"), max_size=80),
    _word_salad(),
    _word_salad(),
    _binaryish(),
    _long(),
    st.just(""),
    st.just(" \t\n "),
    st.just("x" * 10_240),
)


def _check(text: str) -> None:
    try:
        parsed = parse_uncached(text)
    except QueryTextError as exc:
        assert str(exc)  # a clear message, not a crash
        return
    assert isinstance(parsed, ParsedQuery)
    data = parsed.to_dict()
    json.dumps(data)  # the result JSON is always serialisable
    assert ParsedQuery.from_dict(data).to_dict() == data
    ids = [c.id for c, _ in parsed.walk()]
    assert len(ids) == len(set(ids))


@settings(
    max_examples=10_000,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(TEXTS)
def test_no_text_crashes_the_parser(text: str) -> None:
    _check(text)
