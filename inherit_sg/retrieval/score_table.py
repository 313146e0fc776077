"""The score terms of one spec's candidates as columns, and the ranked rows made from them.

A label such as "window" has thousands of candidates on a large map. Scoring them one
:class:`~inherit_sg.retrieval.scoring.Term` object at a time made the Python objects,
not the arithmetic, the cost of a request. A :class:`ScoreTable` holds one
:class:`Column` per constraint (similarities in a float array, reasons in a list), sums
and ranks them with numpy, and hands out :class:`Row` s: ranked candidates whose terms
are built only when read (the answer, the top ``k`` of the result, the trace).

Scores are computed in the order ``Scored.score`` sums them (``H_floor · Σ p·w·Sim``,
term by term), so a row's score is the same float either way.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import overload

import numpy as np

from inherit_sg.retrieval.constraints import Constraint
from inherit_sg.retrieval.scored import Scored, Term

# Kinds whose positive terms say how well a candidate is what was named.
NAMED_KINDS = frozenset({"label", "function"})
# Relations this weak are hints (near where the speaker stands, a hedged "maybe by the
# sink"): they order the candidates but do not split the tier a superlative ranks, so
# "standing at the sink, the stool furthest to the left" counts every stool in view, not
# only the ones the hint happens to find near the sink.
HINT_WEIGHT = 0.4


def is_hint(kind: str, polarity: int, weight: float) -> bool:
    """Whether a term of this kind, polarity and weight is only a hint: a positive
    relation of weight at most :data:`HINT_WEIGHT` (where the speaker stands)."""
    return kind == "relation" and polarity > 0 and weight <= HINT_WEIGHT


@dataclass
class Column:
    """One constraint's term for every candidate of a table (row order)."""

    cid: str
    kind: str
    weight: float
    polarity: int
    sims: np.ndarray
    whys: list[str]

    def values(self) -> np.ndarray:
        """Signed contributions ``p · w · Sim`` (as :attr:`Term.value` computes them)."""
        return self.polarity * self.weight * self.sims

    def is_hint(self) -> bool:
        """Whether this column is only a hint (:func:`is_hint`)."""
        return is_hint(self.kind, self.polarity, self.weight)

    def term(self, row: int) -> Term:
        """The term of one row."""
        return Term(
            self.cid, self.kind, self.weight, self.polarity, float(self.sims[row]), self.whys[row]
        )


class ScoreTable:
    """The candidates of one spec (rows, in generation order) and their score columns."""

    def __init__(self, ids: list[str], found_by: list[list[str]]) -> None:
        self.ids = ids
        self.found_by = found_by
        self.row_of = {node_id: i for i, node_id in enumerate(ids)}
        self.columns: dict[str, Column] = {}
        self.h_floor = np.ones(len(ids), dtype=int)
        # snapshot object row of each candidate (-1: no object), set by the scorer
        self.obj_rows: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.ids)

    def add(
        self, con: Constraint, sims: Iterable[float] | None = None, whys: list[str] | None = None
    ) -> Column:
        """Add (or replace) the column of ``con``; zero similarity and no reason when
        ``sims`` / ``whys`` are not given."""
        return self.add_term(con.id, con.kind, con.weight, con.polarity, sims, whys)

    def add_term(
        self,
        cid: str,
        kind: str,
        weight: float,
        polarity: int,
        sims: Iterable[float] | None = None,
        whys: list[str] | None = None,
    ) -> Column:
        """Add (or replace) a column by its parts."""
        n = len(self.ids)
        values = np.zeros(n) if sims is None else np.fromiter(sims, dtype=float, count=n)
        col = Column(cid, kind, weight, polarity, values, whys if whys is not None else [""] * n)
        self.columns[cid] = col
        return col

    def set(self, cid: str, found: dict[str, tuple[float, str]]) -> None:
        """Set the term ``cid`` of the rows in ``found`` (node id → (sim, why))."""
        col = self.columns[cid]
        for node_id, (sim, why) in found.items():
            row = self.row_of.get(node_id)
            if row is not None:
                col.sims[row] = sim
                col.whys[row] = why

    # ------------------------------------------------------------- sums
    def totals(self, hints: bool = True) -> np.ndarray:
        """``Σ p·w·Sim`` per row, summed term by term in column order; without the
        positive relation terms of weight at most :data:`HINT_WEIGHT` unless ``hints``."""
        total = np.zeros(len(self.ids))
        for col in self.columns.values():
            if hints or not col.is_hint():
                total = total + col.values()
        return total

    def scores(self, hints: bool = True) -> np.ndarray:
        """``H_floor · Σ p·w·Sim`` per row (see :meth:`totals` for ``hints``)."""
        return self.h_floor * self.totals(hints)

    def named_best(self) -> np.ndarray:
        """Best positive label / function similarity per row (0 when none)."""
        best = np.zeros(len(self.ids))
        for col in self.columns.values():
            if col.polarity > 0 and col.kind in NAMED_KINDS:
                best = np.maximum(best, col.sims)
        return best

    def named_sum(self) -> np.ndarray:
        """Sum of the positive label / function similarities per row (term order)."""
        total = np.zeros(len(self.ids))
        for col in self.columns.values():
            if col.polarity > 0 and col.kind in NAMED_KINDS:
                total = total + col.sims
        return total

    # ------------------------------------------------------------- rows
    def terms(self, row: int) -> dict[str, Term]:
        """The terms of one row, in column order."""
        return {cid: col.term(row) for cid, col in self.columns.items()}

    def scored(self, row: int) -> Scored:
        """One row as a plain :class:`Scored` (its terms built now)."""
        return Scored(
            self.ids[row],
            terms=self.terms(row),
            h_floor=int(self.h_floor[row]),
            found_by=self.found_by[row],
        )

    def write_back(self, cid: str, rows: list[int], cands: list[Scored]) -> None:
        """Copy the term ``cid`` of ``cands`` (the :meth:`scored` forms of ``rows``) back
        into its column."""
        col = self.columns[cid]
        for row, cand in zip(rows, cands, strict=True):
            term = cand.terms[cid]
            col.sims[row] = term.sim
            col.whys[row] = term.why

    def ranked(self, order: np.ndarray) -> RankedRows:
        """The rows in ``order`` as a ranking whose candidates are made when read."""
        return RankedRows(self, order)


class RankedRows(Sequence[Scored]):
    """A ranking of a table's rows: a read-only sequence of :class:`Row` s, each made on
    first access and kept (a request reads the top few of thousands)."""

    def __init__(self, table: ScoreTable, order: np.ndarray) -> None:
        self._table = table
        self._order = order
        self._scores = table.scores()
        self._made: dict[int, Row] = {}

    def __len__(self) -> int:
        return len(self._order)

    def _at(self, pos: int) -> Row:
        row = self._made.get(pos)
        if row is None:
            i = int(self._order[pos])
            row = self._made[pos] = Row(self._table, i, float(self._scores[i]))
        return row

    @overload
    def __getitem__(self, pos: int) -> Scored: ...

    @overload
    def __getitem__(self, pos: slice) -> list[Scored]: ...

    def __getitem__(self, pos: int | slice) -> Scored | list[Scored]:
        if isinstance(pos, slice):
            return [self._at(i) for i in range(*pos.indices(len(self)))]
        if pos < 0:
            pos += len(self)
        if not 0 <= pos < len(self):
            raise IndexError("ranking index out of range")
        return self._at(pos)

    def __iter__(self) -> Iterator[Scored]:
        return (self._at(i) for i in range(len(self)))

    def floor_dropped(self) -> int:
        """How many candidates the floor filter dropped (``H_floor = 0``)."""
        return int(np.count_nonzero(self._table.h_floor == 0))

    def positive(self, limit: int) -> list[Scored]:
        """The first ``limit`` candidates with ``H_floor`` 1 and a score above 0, in
        ranking order (looked up in the table, without making the others)."""
        live = (self._table.h_floor[self._order] != 0) & (self._scores[self._order] > 0.0)
        return [self._at(int(pos)) for pos in np.flatnonzero(live)[:limit]]


class Row(Scored):
    """A ranked candidate of a :class:`ScoreTable`: its terms are built on first read
    (after which they behave as a plain :class:`Scored` 's, mutable and summed)."""

    def __init__(self, table: ScoreTable, row: int, score: float) -> None:
        self._table = table
        self._row = row
        self._score = score
        self._terms: dict[str, Term] | None = None
        self.id = table.ids[row]
        self.h_floor = int(table.h_floor[row])
        self.found_by = table.found_by[row]

    @property
    def terms(self) -> dict[str, Term]:
        """The candidate's terms (built from the table on first read)."""
        if self._terms is None:
            self._terms = self._table.terms(self._row)
        return self._terms

    @terms.setter
    def terms(self, value: dict[str, Term]) -> None:
        self._terms = value

    @property
    def score(self) -> float:
        """``H_floor · Σ terms`` (from the table until the terms are read)."""
        if self._terms is None:
            return self._score
        return self.h_floor * sum(t.value for t in self._terms.values())
