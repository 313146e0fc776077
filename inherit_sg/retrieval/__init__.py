"""Retrieval: request parsing into weighted constraints (spaCy with domain rules, or
LLM roles) and conversation history."""

from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    FunctionConstraint,
    LabelConstraint,
    Landmark,
    PlacementConstraint,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
    Viewpoint,
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
    "PlacementConstraint",
    "RelationConstraint",
    "RoomConstraint",
    "RuleParser",
    "Superlative",
    "Target",
    "Viewpoint",
    "describe",
    "parse_rules",
]
