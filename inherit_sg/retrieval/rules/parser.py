"""The offline rule-based request parser: text → :class:`ParsedQuery`.

Pipeline: check the text, tokenise (contractions, punctuation), detect the frame (global
question, refinement), tag words against the lexicon (multi-word nouns, plurals,
synonyms, filler), parse the noun-phrase grammar, and assemble weighted constraints.
Parse results are cached per text (they are immutable).
"""

from __future__ import annotations

from functools import lru_cache

from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.retrieval.rules.assemble import assemble
from inherit_sg.retrieval.rules.clause import ClauseParser
from inherit_sg.retrieval.rules.frames import global_reason, refine_frame
from inherit_sg.retrieval.rules.problems import split_problem
from inherit_sg.retrieval.rules.tagger import tag
from inherit_sg.retrieval.rules.tokens import check_query_text, tokenize


def parse_uncached(text: str) -> ParsedQuery:
    """Parse ``text`` without the result cache (for benchmarks)."""
    text = check_query_text(text)
    problem, words = split_problem(tokenize(text))
    reason = global_reason(words) if words or problem is None else None
    if reason is not None:
        return ParsedQuery(text=text, no_target_reason=reason, notes=("frame: global question",))
    refine, words = refine_frame(words)
    notes = ["frame: refinement of the previous request"] if refine else []
    tokens = tag(words)
    clause = ClauseParser(tokens, notes).parse(refine)
    if problem is not None:
        notes.append(f"function {problem.function!r} implied by the problem {problem.text!r}")
        clause.functions.append(problem)  # an explicit request ("where can I lie down") leads
    return assemble(text, clause, refine, notes, words)


@lru_cache(maxsize=4096)
def _parse_cached(text: str) -> ParsedQuery:
    return parse_uncached(text)


def parse_rules(text: str) -> ParsedQuery:
    """Parse a request with the rule grammar; raises :class:`QueryTextError` on bad text."""
    return _parse_cached(check_query_text(text))


class RuleParser:
    """Object form of :func:`parse_rules` (same interface as the LLM parser)."""

    name = "rules"

    def parse(self, text: str) -> ParsedQuery:
        """Parse ``text`` into constraints."""
        return parse_rules(text)
