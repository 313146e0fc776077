"""Multi-role LLM request parser over an OpenAI-compatible endpoint (paper §III-D).

Three chat completions with JSON-schema output, in order: the decomposer (target,
landmarks, spatial requirements), the negation extractor (flags negative constraints,
inverting their polarity) and the weight assigner (importance per constraint, the
intent weighting). Any failure — no endpoint configured, a timeout, an HTTP error,
invalid JSON, an answer that does not fit the schema — falls back to the rule parser,
and the parse's ``notes`` say which role failed and why. Responses are cached by the
client, so a repeated request sends nothing.
"""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.config import LLMConfig
from inherit_sg.errors import EndpointError, InputError
from inherit_sg.llm.client import ChatClient
from inherit_sg.retrieval import llm_roles as roles
from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.retrieval.rules.parser import RuleParser
from inherit_sg.retrieval.rules.tokens import check_query_text


class LLMParser:
    """Parse requests with three LLM roles; fall back to ``fallback`` on any failure."""

    name = "llm"

    def __init__(self, client: ChatClient | None, fallback: RuleParser | None = None) -> None:
        self.client = client
        self.fallback = fallback or RuleParser()

    @classmethod
    def from_config(cls, config: LLMConfig) -> LLMParser:
        """A parser for the ``[llm]`` config section (rules only when no endpoint is set)."""
        return cls(ChatClient.from_config(config) if config.endpoint else None)

    def parse(self, text: str) -> ParsedQuery:
        """Parse ``text``; raises :class:`QueryTextError` only for bad text."""
        text = check_query_text(text)
        if self.client is None:
            return self._fall_back(text, "no LLM endpoint configured (llm.endpoint)")
        role = "decomposer"
        try:
            data = self.client.chat_json(
                roles.messages(roles.DECOMPOSER_PROMPT, text),
                roles.DECOMPOSE_SCHEMA,
                "decomposition",
            )
            query = roles.decomposition_to_query(text, data)
            notes = [f"llm decomposer: {len(list(query.walk()))} constraints"]
            if query.constraints:
                role = "negation extractor"
                listing = roles.listing(query)
                data = self.client.chat_json(
                    roles.messages(roles.NEGATION_PROMPT, listing),
                    roles.NEGATION_SCHEMA,
                    "negations",
                )
                query = roles.apply_negations(query, data)
                notes.append("llm negation extractor: " + _negated(query))
                role = "weight assigner"
                data = self.client.chat_json(
                    roles.messages(roles.WEIGHT_PROMPT, roles.listing(query)),
                    roles.WEIGHT_SCHEMA,
                    "weights",
                )
                query = roles.apply_weights(query, data)
                notes.append("llm weight assigner: weights set")
        except (EndpointError, InputError) as exc:
            return self._fall_back(text, f"{role} failed: {exc.message}")
        return replace(query, notes=(*query.notes, *notes))

    def _fall_back(self, text: str, why: str) -> ParsedQuery:
        parsed = self.fallback.parse(text)
        note = f"llm parser: {why}; fell back to the rule parser"
        return replace(parsed, notes=(note, *parsed.notes))


def _negated(query: ParsedQuery) -> str:
    ids = [c.id for c, _ in query.walk() if c.negated]
    return "negated " + ", ".join(ids) if ids else "nothing negated"
