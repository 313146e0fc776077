"""The query result (DESIGN.md §4), shared by the CLI ``--json`` output and the REST API.

``{"query", "answer": {"id","label","position":[x,y,z],"room","floor","score"} | null,
"candidates": [...], "constraints": {...}, "trace": [...], "timings_ms": {"parse",
"retrieve","verify","total"}}``. ``room`` is the room's label and ``floor`` the floor
level (0 = lowest); ``room_id``, ``floor_id`` and ``verified`` are added alongside.
Each candidate carries its per-constraint terms under ``scores``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from inherit_sg.retrieval.scoring import Scored
from inherit_sg.retrieval.snapshot import MapSnapshot

if TYPE_CHECKING:
    from inherit_sg.retrieval.result_models import QueryResponse


def node_summary(snap: MapSnapshot, node_id: str) -> dict[str, Any]:
    """id, label, position, room (label), floor (level) and their ids for one node."""
    node = snap.node(node_id)
    room_id = snap.room_of.get(node_id)
    floor_id = snap.floor_of.get(node_id)
    room = snap.rooms.get(room_id) if room_id else None
    pos = snap.position(node_id)
    return {
        "id": node_id,
        "label": getattr(node, "label", "") or "",
        "position": [round(float(v), 4) for v in pos] if pos is not None else None,
        "room": room.label if room is not None else None,
        "floor": snap.level_of(node_id),
        "room_id": room_id,
        "floor_id": floor_id,
    }


def candidate_dict(snap: MapSnapshot, cand: Scored) -> dict[str, Any]:
    """One ranked candidate with its score terms."""
    return {
        **node_summary(snap, cand.id),
        "score": round(cand.score, 4),
        "h_floor": cand.h_floor,
        "scores": {cid: t.to_dict() for cid, t in cand.terms.items()},
        "found_by": cand.found_by,
    }


@dataclass
class QueryResult:
    """Answer, ranked candidates, parsed constraints, trace and stage timings."""

    query: str
    answer: dict[str, Any] | None
    candidates: list[dict[str, Any]] = field(default_factory=list)
    constraints: dict[str, Any] = field(default_factory=dict)
    trace: list[str] = field(default_factory=list)
    timings_ms: dict[str, float] = field(default_factory=dict)
    explain: str | None = None

    @property
    def answer_id(self) -> str | None:
        """Id of the answer node, if any."""
        return None if self.answer is None else str(self.answer["id"])

    @property
    def candidate_ids(self) -> list[str]:
        """Ids of the ranked candidates."""
        return [str(c["id"]) for c in self.candidates]

    def to_dict(self) -> dict[str, Any]:
        """The result JSON (the plan, when asked for, under ``plan``)."""
        out: dict[str, Any] = {
            "query": self.query,
            "answer": self.answer,
            "candidates": self.candidates,
            "constraints": self.constraints,
            "trace": self.trace,
            "timings_ms": {k: round(v, 3) for k, v in self.timings_ms.items()},
        }
        if self.explain is not None:
            out["plan"] = self.explain
        return out

    def to_json(self, indent: int | None = None) -> str:
        """:meth:`to_dict` as JSON text."""
        return json.dumps(self.to_dict(), indent=indent)

    def model(self) -> QueryResponse:
        """:meth:`to_dict` as the typed :class:`QueryResponse`."""
        from inherit_sg.retrieval.result_models import QueryResponse

        return QueryResponse.model_validate(self.to_dict())
