"""Offline rule-based request parser: tokenizer, lexical tagger and noun-phrase grammar."""

from inherit_sg.retrieval.rules.parser import RuleParser, parse_rules, parse_uncached
from inherit_sg.retrieval.rules.tokens import MAX_QUERY_CHARS, check_query_text, tokenize

__all__ = [
    "MAX_QUERY_CHARS",
    "RuleParser",
    "check_query_text",
    "parse_rules",
    "parse_uncached",
    "tokenize",
]
