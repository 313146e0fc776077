"""The flat baseline (ConceptGraphs / Embodied-RAG style): rank every object by the
embedding similarity of the WHOLE request to its text (label + description), with no
parsing, hierarchy, relations or verification. Benchmarks run it beside the engine."""

from __future__ import annotations

import time

from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.retrieval.result import QueryResult, node_summary
from inherit_sg.retrieval.rules.tokens import check_query_text


class FlatBaseline:
    """Nearest object texts to the request text, via the map's ``object_text`` index."""

    name = "flat"

    def __init__(self, engine: QueryEngine) -> None:
        self.engine = engine

    def query(self, text: str, top_k: int = 10) -> QueryResult:
        """The objects nearest to ``text``, best first (the first is the answer)."""
        start = time.perf_counter()
        text = check_query_text(text)
        snap, _ = self.engine.snapshot()
        vec = self.engine.similarity.vectors([text])[0]
        t1 = time.perf_counter()
        hits = [
            (i, d)
            for i, d in self.engine.store.vector_search("object_text", vec, top_k)
            if i in snap.objects
        ]
        cands = [
            {**node_summary(snap, i), "score": round(1.0 - d, 4), "scores": {}} for i, d in hits
        ]
        answer = dict(cands[0]) if cands else None
        if answer is not None:
            answer.pop("scores")
        trace = [f"flat baseline: nearest object texts to the whole request ({len(cands)} hits)"]
        end = time.perf_counter()
        return QueryResult(
            query=text,
            answer=answer,
            candidates=cands,
            constraints={},
            trace=trace,
            timings_ms={
                "parse": 0.0,
                "retrieve": (end - start) * 1000.0,
                "verify": 0.0,
                "total": (end - start) * 1000.0,
                "embed": (t1 - start) * 1000.0,
            },
        )
