"""Retrieval accuracy of the engine and of the flat baseline on the same map and the
same requests (paper Table II layout: within 1 m / 0.5 m per category group, overall
and the mean of the groups, plus semantic accuracy)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from inherit_sg.benchmark.metrics.retrieval import Answer, Outcome, evaluate, summarise
from inherit_sg.ingest.synthetic.queries import QueryGT
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.retrieval.baseline import FlatBaseline
from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.retrieval.result import QueryResult


def _as_answer(result: QueryResult) -> Answer:
    answer = result.answer or {}
    return result.answer_id, answer.get("position"), dict(result.timings_ms)


def engine_answers(engine: QueryEngine) -> Callable[[str], Answer]:
    """Answer function of the engine (its configured verification)."""
    return lambda text: _as_answer(engine.query(text))


def flat_answers(engine: QueryEngine) -> Callable[[str], Answer]:
    """Answer function of the flat baseline over the engine's map."""
    flat = FlatBaseline(engine)
    return lambda text: _as_answer(flat.query(text))


def judge(
    answer: Callable[[str], Answer],
    queries: list[QueryGT],
    scene: Scene,
    progress: Callable[[int, int], None] | None = None,
) -> list[Outcome]:
    """Judge every request, reporting (done, total) to ``progress`` every 25 requests."""
    outcomes: list[Outcome] = []
    step = 25
    for start in range(0, len(queries), step):
        outcomes.extend(evaluate(answer, queries[start : start + step], scene))
        if progress is not None:
            progress(len(outcomes), len(queries))
    return outcomes


def warm_up(engine: QueryEngine) -> None:
    """Load the snapshot and the text embedder once, so that no request is timed with
    one-off loading in it."""
    engine.snapshot()
    engine.similarity.vectors(["warm up"])


def compare(
    engine: QueryEngine,
    queries: list[QueryGT],
    scene: Scene,
    progress: Callable[[str, int, int], None] | None = None,
) -> dict[str, list[Outcome]]:
    """Outcomes of ours and of the flat baseline, keyed ``"ours"`` / ``"flat"``
    (``progress`` gets the system name, requests done and the total)."""
    warm_up(engine)
    out: dict[str, list[Outcome]] = {}
    for name, answer in (("ours", engine_answers(engine)), ("flat", flat_answers(engine))):

        def tick(done: int, total: int, name: str = name) -> None:
            if progress is not None:
                progress(name, done, total)

        out[name] = judge(answer, queries, scene, tick)
    return out


def accuracy_table(outcomes: dict[str, list[Outcome]]) -> dict[str, Any]:
    """Summaries (:func:`inherit_sg.benchmark.metrics.retrieval.summarise`) per system."""
    return {system: summarise(outs) for system, outs in outcomes.items()}
