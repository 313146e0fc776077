"""A faster way to find the matches of spaCy's attribute ruler.

The packaged English pipeline ends with an ``attribute_ruler`` of 179 token patterns
(fine tag → coarse part of speech, morphology and lemma exceptions such as "gonna" or
"ain't"). spaCy finds their matches with its general token ``Matcher``, which took
0.27 ms a request (7,078 request texts, this project's 2-core machine). Every one of these
patterns is a fixed sequence of one or two tokens with no operators, and which of them can
start at a token depends only on the token's lower-case form, tag, dependency label and
whether it is a space. Remembering that per token kind finds the same matches in 0.019 ms.

:func:`speed_up` builds the index from the ruler's own patterns when the model loads and
swaps it in for the ruler's ``match`` step. The ruler still applies its attributes itself,
in its own order, so the resulting documents are identical (``tests/unit/test_nlp.py``
compares the matches on the development set). A pattern of a form the index does not
handle (an operator, another key or value form) leaves the ruler untouched.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from spacy.pipeline import AttributeRuler
    from spacy.tokens import Doc, Token

TokenTest = Callable[["Token"], bool]
# A match as the ruler's ``match`` step returns it: rule number, matcher key, start, end.
Match = tuple[int, int, int, int]

# Token kinds remembered before the memory starts afresh.
_MAX_REMEMBERED = 50_000

# Token attributes a pattern may test, and how each is read from a token.
_READERS: dict[str, Callable[[Token], Any]] = {
    "LOWER": lambda t: t.lower_,
    "TAG": lambda t: t.tag_,
    "DEP": lambda t: t.dep_,
    "IS_SPACE": lambda t: t.is_space,
}


class UnsupportedPattern(ValueError):
    """A ruler pattern uses a form the index does not handle."""


def _value_test(read: Callable[[Token], Any], spec: Any) -> TokenTest:
    """A test that one attribute equals ``spec``, or satisfies its ``IN`` / ``NOT_IN`` /
    ``REGEX`` form, as spaCy's matcher reads it."""
    if isinstance(spec, str | bool):
        return lambda t: bool(read(t) == spec)
    if isinstance(spec, dict) and len(spec) == 1:
        ((op, arg),) = spec.items()
        if op == "IN" and isinstance(arg, list):
            members = frozenset(arg)
            return lambda t: read(t) in members
        if op == "NOT_IN" and isinstance(arg, list):
            outsiders = frozenset(arg)
            return lambda t: read(t) not in outsiders
        if op == "REGEX" and isinstance(arg, str):
            pattern = re.compile(arg)
            return lambda t: pattern.search(read(t)) is not None
    raise UnsupportedPattern(f"value {spec!r}")


def _token_test(spec: dict[str, Any]) -> TokenTest:
    """One pattern token as a test on a token."""
    if not spec:
        raise UnsupportedPattern("empty token pattern")
    tests = []
    for key, value in spec.items():
        if key not in _READERS:
            raise UnsupportedPattern(f"key {key!r}")
        tests.append(_value_test(_READERS[key], value))
    return lambda t: all(test(t) for test in tests)


def _exact_values(spec: dict[str, Any], key: str) -> frozenset[str] | None:
    """The values ``key`` must take in a pattern token when the token names them (a string
    or an ``IN`` list); None when it does not pin ``key`` down."""
    value = spec.get(key)
    if isinstance(value, str):
        return frozenset((value,))
    if isinstance(value, dict) and set(value) == {"IN"}:
        return frozenset(value["IN"])
    return None


@dataclass(frozen=True)
class _Alternative:
    """One token sequence of a rule."""

    rule: int
    key: int
    tests: tuple[TokenTest, ...]


@dataclass
class AttributeIndex:
    """The ruler's patterns, filed by the lower-case form or tag their first token
    requires, with the first-token matches of every token kind seen so far
    remembered: which rules can start at a token depends only on its lower-case form, tag,
    dependency label and whether it is a space, and requests repeat these a lot."""

    by_lower: dict[str, list[_Alternative]] = field(default_factory=dict)
    by_tag: dict[str, list[_Alternative]] = field(default_factory=dict)
    anywhere: list[_Alternative] = field(default_factory=list)
    _starts: dict[tuple[str, str, str, bool], tuple[_Alternative, ...]] = field(
        default_factory=dict
    )

    def add(self, alternative: _Alternative, first: dict[str, Any]) -> None:
        """File ``alternative`` under the lower-case forms its first token requires, else
        under the tags it requires, else with those that may start anywhere."""
        lowers = _exact_values(first, "LOWER")
        tags = _exact_values(first, "TAG")
        if lowers is not None:
            for value in lowers:
                self.by_lower.setdefault(value, []).append(alternative)
        elif tags is not None:
            for value in tags:
                self.by_tag.setdefault(value, []).append(alternative)
        else:
            self.anywhere.append(alternative)

    def _starting_at(self, token: Token) -> tuple[_Alternative, ...]:
        """The alternatives whose first token matches ``token``."""
        kind = (token.lower_, token.tag_, token.dep_, token.is_space)
        found = self._starts.get(kind)
        if found is None:
            if len(self._starts) >= _MAX_REMEMBERED:
                self._starts.clear()
            candidates = (
                self.by_lower.get(token.lower_, [])
                + self.by_tag.get(token.tag_, [])
                + self.anywhere
            )
            found = tuple(alt for alt in candidates if alt.tests[0](token))
            self._starts[kind] = found
        return found

    def match(self, doc: Doc) -> list[Match]:
        """Every rule match in ``doc``, sorted as the ruler applies them."""
        found: set[Match] = set()
        n = len(doc)
        for start, token in enumerate(doc):
            for alt in self._starting_at(token):
                end = start + len(alt.tests)
                if end == start + 1 or (
                    end <= n and all(test(doc[start + i]) for i, test in enumerate(alt.tests) if i)
                ):
                    found.add((alt.rule, alt.key, start, end))
        return sorted(found)


def _sequences(patterns: object) -> list[list[dict[str, Any]]]:
    """A rule's patterns as token sequences; raises :class:`UnsupportedPattern` for any
    other form."""
    if not isinstance(patterns, list) or not all(
        isinstance(seq, list) and seq and all(isinstance(tok, dict) for tok in seq)
        for seq in patterns
    ):
        raise UnsupportedPattern(f"patterns {patterns!r}")
    return [[{str(k): v for k, v in tok.items()} for tok in seq] for seq in patterns]


def build_index(ruler: AttributeRuler) -> AttributeIndex:
    """The index of ``ruler``'s patterns; raises :class:`UnsupportedPattern` for a
    pattern it cannot hold."""
    index = AttributeIndex()
    strings = ruler.vocab.strings
    for rule, entry in enumerate(ruler.patterns):
        key = strings.add(str(rule))
        for sequence in _sequences(entry["patterns"]):
            tests = tuple(_token_test(token) for token in sequence)
            index.add(_Alternative(rule, key, tests), sequence[0])
    return index


def speed_up(ruler: AttributeRuler) -> bool:
    """Swap the index in for ``ruler``'s matcher; False (ruler unchanged) when one of
    its patterns is of a form the index does not handle."""
    try:
        index = build_index(ruler)
    except UnsupportedPattern:
        return False
    ruler.match = index.match  # type: ignore[method-assign]
    return True
