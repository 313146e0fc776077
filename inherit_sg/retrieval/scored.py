"""Score terms and scored candidates: what every ranking is made of.

A :class:`Term` is one constraint's contribution ``p · w · Sim`` to a candidate's score;
a :class:`Scored` is a candidate with its terms, its floor filter ``H_floor`` and the
generation steps that found it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass
class Term:
    """One constraint's contribution ``p · w · Sim`` to a candidate's score."""

    cid: str
    kind: str
    weight: float
    polarity: int
    sim: float
    why: str = ""

    @property
    def value(self) -> float:
        """Signed contribution to the score."""
        return self.polarity * self.weight * self.sim

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return {
            "kind": self.kind,
            "weight": round(self.weight, 4),
            "polarity": self.polarity,
            "sim": round(self.sim, 4),
            "term": round(self.value, 4),
            "why": self.why,
        }


@dataclass
class Scored:
    """A candidate with its score terms."""

    id: str
    terms: dict[str, Term] = field(default_factory=dict)
    h_floor: int = 1
    found_by: list[str] = field(default_factory=list)

    @property
    def score(self) -> float:
        """``H_floor · Σ terms``."""
        return self.h_floor * sum(t.value for t in self.terms.values())

    def sim(self, kind: str) -> float:
        """Largest similarity among the positive terms of ``kind`` (0 when none)."""
        return max(
            (t.sim for t in self.terms.values() if t.kind == kind and t.polarity > 0), default=0.0
        )
