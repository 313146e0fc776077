"""Human-readable trace lines: which constraints were parsed, which candidates were
found, and why each ranked candidate was kept or dropped."""

from __future__ import annotations

from collections.abc import Sequence

from inherit_sg.retrieval.query import ParsedQuery, describe
from inherit_sg.retrieval.score_table import RankedRows
from inherit_sg.retrieval.scoring import Scored
from inherit_sg.retrieval.snapshot import MapSnapshot

# Ranked candidates explained one by one; the rest are summarised.
EXPLAINED = 5


def describe_query(parsed: ParsedQuery) -> list[str]:
    """Lines for the parse: target, constraints (nested), references and notes."""
    lines = [
        f"parsed by {parsed.parser}: target {parsed.target.describe()!r} "
        f"({parsed.target.layer} layer)"
    ]
    for con, depth in parsed.walk():
        pad = "  " * depth
        lines.append(f"{pad}{con.id}: {describe(con)} (w={con.weight:.2f}, p={con.polarity:+d})")
    if parsed.viewpoint is not None:
        vp = parsed.viewpoint
        lines.append(f"viewpoint: {vp.kind.replace('_', ' ')} {vp.landmark.target.describe()}")
        for con in vp.landmark.constraints:
            lines.append(f"  {con.id}: {describe(con)} (w={con.weight:.2f}, p={con.polarity:+d})")
    if parsed.reference != "none":
        lines.append(f"follow-up: {parsed.reference}")
    if parsed.exclude_ids:
        lines.append(f"excluded by the conversation: {', '.join(parsed.exclude_ids)}")
    lines += [f"note: {n}" for n in parsed.notes]
    return lines


def _terms(cand: Scored) -> str:
    parts = [
        f"{cid} {t.value:+.2f}" + (f" ({t.why})" if t.why else "") for cid, t in cand.terms.items()
    ]
    return "; ".join(parts) or "no scored constraints"


def _why_below(cand: Scored, top: Scored) -> str:
    if not cand.h_floor:
        return "dropped by the floor filter (H_floor = 0)"
    worse = [
        f"{cid} {t.value:+.2f} vs {top.terms[cid].value:+.2f}"
        for cid, t in cand.terms.items()
        if cid in top.terms and t.value < top.terms[cid].value - 1e-9
    ]
    if not worse:
        return "ties with the top candidate" if abs(cand.score - top.score) < 1e-9 else ""
    return "ranks lower: " + ", ".join(worse)


def explain_ranking(snap: MapSnapshot, ranked: Sequence[Scored], k: int) -> list[str]:
    """Lines for the ranking: the top candidates with their terms, why the others rank
    below the first, and a count of the rest."""
    if not ranked:
        return ["no candidates"]
    lines = [f"{len(ranked)} candidates ranked"]
    top = ranked[0]
    for pos, cand in enumerate(ranked[: min(k, EXPLAINED)], start=1):
        label = getattr(snap.node(cand.id), "label", "")
        head = f"#{pos} {cand.id} {label}: S={cand.score:.2f}"
        if pos == 1:
            lines.append(f"{head} kept: {_terms(cand)}")
        else:
            lines.append(f"{head} {_why_below(cand, top)}")
    if isinstance(ranked, RankedRows):
        dropped = ranked.floor_dropped()
    else:
        dropped = sum(1 for c in ranked if not c.h_floor)
    if dropped:
        lines.append(f"{dropped} candidates dropped by the floor filter")
    if len(ranked) > EXPLAINED:
        lines.append(f"... and {len(ranked) - EXPLAINED} lower-ranked candidates")
    return lines
