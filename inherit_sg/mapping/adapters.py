"""Factory for the model-backed roles of the semantic stream: the LLM area labeller,
the VLM relation verifier and the VLM soft-trigger supervisor when ``llm.endpoint`` is
set, the offline defaults otherwise (DESIGN §5)."""

from __future__ import annotations

from collections.abc import Callable

from inherit_sg.config import Config
from inherit_sg.llm import ChatClient
from inherit_sg.mapping.area_labeller import AreaLabeller, LlmAreaLabeller, RuleAreaLabeller
from inherit_sg.mapping.relation_verifier import (
    GeometricVerifier,
    RelationVerifier,
    VlmRelationVerifier,
)
from inherit_sg.mapping.supervisor import HeuristicSupervisor, Supervisor
from inherit_sg.mapping.vlm_supervisor import VlmSupervisor


def create_area_labeller(config: Config) -> AreaLabeller:
    """LLM labeller (rules as fallback) with an endpoint, the rules without."""
    if not config.llm.endpoint:
        return RuleAreaLabeller()
    return LlmAreaLabeller(ChatClient.from_config(config.llm))


def create_relation_verifier(config: Config) -> RelationVerifier:
    """VLM verifier with an endpoint, the geometric mode without."""
    if not config.llm.endpoint:
        return GeometricVerifier()
    return VlmRelationVerifier(ChatClient.from_config(config.llm))


def create_supervisor(config: Config, bev_png: Callable[[], bytes]) -> Supervisor:
    """VLM supervisor reading ``bev_png()`` with an endpoint, the heuristic without."""
    if not config.llm.endpoint:
        return HeuristicSupervisor()
    return VlmSupervisor(ChatClient.from_config(config.llm), bev_png)
