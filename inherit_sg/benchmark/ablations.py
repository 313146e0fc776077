"""Ablations of the query pipeline (paper §IV-D): the same requests on the same map with
one part switched off through the config, each with accuracy per category group and the
mean latency per request."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from inherit_sg.benchmark.accuracy import engine_answers, judge, warm_up
from inherit_sg.benchmark.latency import mean_total_ms
from inherit_sg.benchmark.metrics.retrieval import summarise
from inherit_sg.config import Config
from inherit_sg.ingest.synthetic.queries import QueryGT
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.store import MapStore


@dataclass(frozen=True)
class Ablation:
    """One variant: a name, the config field it sets, and the value."""

    name: str
    section: str
    field: str
    value: Any
    needs_llm: bool = False

    @property
    def override(self) -> str:
        """The ``--set`` form of the change."""
        return f"{self.section}.{self.field}={self.value}"


ABLATIONS: tuple[Ablation, ...] = (
    Ablation("without areas", "retrieval", "use_areas", False),
    Ablation("without segmenter in verification", "retrieval", "verify_segmenter", False),
    Ablation("without verification", "retrieval", "verify", False),
    Ablation("LLM parser instead of rules", "retrieval", "parser", "llm", needs_llm=True),
)


FULL = "full pipeline"

# the parser ablation when the configured parser is already the LLM one
RULES_INSTEAD_OF_LLM = Ablation(
    "rules parser instead of LLM", "retrieval", "parser", "rules", needs_llm=True
)


def with_change(config: Config, ablation: Ablation) -> Config:
    """A copy of ``config`` with the ablation's field set (validated)."""
    section = getattr(config, ablation.section)
    data = section.model_dump() | {ablation.field: ablation.value}
    return config.model_copy(update={ablation.section: type(section).model_validate(data)})


def _measure(
    store: MapStore, config: Config, queries: list[QueryGT], scene: Scene
) -> dict[str, Any]:
    engine = QueryEngine(store, config)
    warm_up(engine)
    outcomes = judge(engine_answers(engine), queries, scene)
    return {"accuracy": summarise(outcomes), "mean_latency_ms": mean_total_ms(outcomes)}


def run_ablations(
    store: MapStore,
    config: Config,
    queries: list[QueryGT],
    scene: Scene,
    progress: Callable[[str], None] | None = None,
) -> dict[str, dict[str, Any]]:
    """Accuracy per group and mean latency of the full pipeline (``"full pipeline"``, run
    again so that every variant finds the same phrases cached) and of every ablation;
    variants that need an LLM endpoint are recorded as skipped when ``llm.endpoint`` is
    not configured."""
    if progress is not None:
        progress(FULL)
    out: dict[str, dict[str, Any]] = {
        FULL: {"override": None, **_measure(store, config, queries, scene)}
    }
    for ablation in ABLATIONS:
        if ablation.needs_llm and config.retrieval.parser == "llm":
            ablation = RULES_INSTEAD_OF_LLM
        if ablation.needs_llm and not config.llm.endpoint:
            out[ablation.name] = {
                "override": ablation.override,
                "skipped": "llm.endpoint is not configured",
            }
            continue
        if progress is not None:
            progress(ablation.name)
        changed = with_change(config, ablation)
        out[ablation.name] = {
            "override": ablation.override,
            **_measure(store, changed, queries, scene),
        }
    return out
