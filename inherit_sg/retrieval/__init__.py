"""Retrieval: request parsing into weighted constraints (rule grammar or LLM roles) and
conversation history."""

from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    FunctionConstraint,
    LabelConstraint,
    Landmark,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
)
from inherit_sg.retrieval.query import ParsedQuery, describe
from inherit_sg.retrieval.rules import RuleParser, parse_rules

__all__ = [
    "AreaConstraint",
    "AttributeConstraint",
    "Constraint",
    "FloorConstraint",
    "FunctionConstraint",
    "LabelConstraint",
    "Landmark",
    "ParsedQuery",
    "RelationConstraint",
    "RoomConstraint",
    "RuleParser",
    "Superlative",
    "Target",
    "describe",
    "parse_rules",
]
