"""Token cursor with the pending modifiers the grammar threads through: a negation
waiting for the constraint it scopes, and an emphasis or hedge for the next weight."""

from __future__ import annotations

from typing import Any

from inherit_sg.retrieval.constraints import DEFAULT_WEIGHTS, EMPHASIS_BOOST, HEDGE_FACTOR
from inherit_sg.retrieval.rules.tagger import Tok

# Tokens that can start a noun phrase.
NP_START = (
    "det",
    "num",
    "ord",
    "super",
    "colour",
    "material",
    "adj",
    "noun",
    "unk",
    "room",
    "room_word",
    "area_head",
    "vague",
    "generic",
    "floor_noun",
    "floor",
    "one",
    "anaphor",
    "other",
)
# Tokens that continue a compound noun.
NOUNISH = (
    "noun", "unk", "room", "room_word", "area_head", "vague", "generic", "floor_noun", "material",
)  # fmt: skip


def weighted(kind: str, stress: str | None) -> float:
    """Default weight of ``kind`` raised by an emphasis or lowered by a hedge."""
    base = DEFAULT_WEIGHTS[kind]
    if stress == "emph":
        return min(1.0, round(base + EMPHASIS_BOOST, 3))
    if stress == "hedge":
        return round(base * HEDGE_FACTOR, 3)
    return base


class Cursor:
    """Position in a token list plus pending negation and emphasis."""

    def __init__(self, toks: list[Tok], notes: list[str]) -> None:
        self.toks = toks
        self.i = 0
        self.notes = notes
        self._neg = False
        self._stress: str | None = None
        self.with_depth = 0
        # parsing the object of "in" / "inside" / "from": a word that names both a thing
        # and a room type ("the WC", "the closet") is the room
        self.place_object = False
        self.group: Any = None  # a pending group phrase ("in the row of lockers")
        # the landmark of a leading "counting from the curtains, …" for the next ordinal
        self.count_origin: Any = None

    def peek(self, k: int = 0) -> Tok | None:
        """The token ``k`` places ahead, or None past the end."""
        j = self.i + k
        return self.toks[j] if 0 <= j < len(self.toks) else None

    def text_at(self, k: int = 0) -> str:
        """The words of the token ``k`` places ahead ("" past the end)."""
        tok = self.peek(k)
        return tok.text if tok is not None else ""

    def at(self, *tags: str, k: int = 0) -> bool:
        """Whether the token ``k`` ahead has any of ``tags``."""
        tok = self.peek(k)
        return tok is not None and tok.has(*tags)

    def advance(self) -> Tok:
        """Consume and return the current token."""
        tok = self.toks[self.i]
        self.i += 1
        return tok

    def state(self) -> tuple[int, bool, str | None, int]:
        """Snapshot for backtracking."""
        return self.i, self._neg, self._stress, len(self.notes)

    def restore(self, snap: tuple[int, bool, str | None, int]) -> None:
        """Return to a :meth:`state` snapshot."""
        self.i, self._neg, self._stress, n_notes = snap
        del self.notes[n_notes:]

    def negate(self) -> None:
        """Mark the next constraint as negated (a second negation cancels the first)."""
        self._neg = not self._neg

    def take_neg(self) -> bool:
        """Consume the pending negation."""
        neg, self._neg = self._neg, False
        return neg

    def stress(self, kind: str) -> None:
        """Remember an emphasis (``"emph"``) or hedge (``"hedge"``) for the next weight."""
        self._stress = kind

    def take_stress(self) -> str | None:
        """Consume the pending emphasis or hedge."""
        stress, self._stress = self._stress, None
        return stress

    def weight(self, kind: str) -> float:
        """Weight of a new constraint of ``kind``; consumes the pending emphasis."""
        return weighted(kind, self.take_stress())

    def np_start(self, k: int = 0) -> bool:
        """Whether a noun phrase can start ``k`` tokens ahead."""
        tok = self.peek(k)
        if tok is not None and tok.has("emph", "adv") and not tok.has(*NP_START, "prep"):
            return self.np_start(k + 1)  # "important documents", "very big chair"
        if tok is not None and tok.has("seeker") and self.nounish(k + 1):
            return True  # "group discussions"
        if tok is not None and tok.has("side", "dir", "middle") and self.nounish(k + 1):
            return True  # "leftmost monitor on the desk", "left nightstand" (no "the")
        if tok is None or not tok.has(*NP_START):
            return False
        return not (tok.has("filler") and not tok.has("noun", "room", "unk", "generic"))

    def nounish(self, k: int = 0) -> bool:
        """Whether the token ``k`` ahead can be (part of) a noun."""
        tok = self.peek(k)
        return tok is not None and tok.has(*NOUNISH, "one") and not tok.has("prep", "filler")
