"""Typed query results: the JSON of :meth:`QueryResult.to_dict
<inherit_sg.retrieval.result.QueryResult.to_dict>` as pydantic models, so Python users
get types and the REST query route a response schema (``QueryResult.model()``)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field


class ScoreTerm(BaseModel):
    """What one constraint added to a candidate's score."""

    kind: str = Field(description="The constraint's kind: label, relation, room, …")
    weight: float
    polarity: int = Field(description="+1 for a wanted constraint, -1 for a negated one.")
    sim: float = Field(description="How well the candidate meets it, 0 … 1.")
    term: float = Field(description="weight × polarity × sim: its share of the score.")
    why: str = Field(description="A readable reason.")


class NodeRef(BaseModel):
    """A node of the map with where it is."""

    id: str
    label: str
    position: list[float] | None = Field(description="x, y, z in metres (z up).")
    room: str | None = Field(description="The label of the node's room.")
    floor: int | None = Field(description="The level of the node's floor (0 = lowest).")
    room_id: str | None
    floor_id: str | None


class Answer(NodeRef):
    """The node a query answers with."""

    score: float
    verified: bool | None = Field(
        description="True when verification confirmed it, False when every candidate "
        "tried failed (the best-ranked is answered), null when it was not checked."
    )


class Candidate(NodeRef):
    """One ranked candidate with its score terms."""

    score: float
    h_floor: int = Field(description="1, or 0 when the candidate is on a floor ruled out.")
    scores: dict[str, ScoreTerm] = Field(description="Score terms by constraint id.")
    found_by: list[str] = Field(description="Which searches found it (cypher, vector, …).")


class TargetOut(BaseModel):
    """What a request seeks."""

    model_config = ConfigDict(extra="allow")

    layer: str = Field(description="object, area, room or floor.")
    labels: list[str]
    noun: str
    function: str | None


class ConstraintOut(BaseModel):
    """One weighted, polarised constraint of a parsed request; the fields past the
    common ones depend on ``kind`` (a relation's predicate and landmark, a room's type,
    …)."""

    model_config = ConfigDict(extra="allow")

    id: str
    kind: str
    polarity: int
    negated: bool
    weight: float
    text: str


class ParsedRequest(BaseModel):
    """The request as parsed: target, constraints and how it refers to a conversation."""

    model_config = ConfigDict(extra="allow")

    text: str
    target: TargetOut
    constraints: list[ConstraintOut]
    reference: str
    exclude_ids: list[str]
    no_target_reason: str | None
    parser: str = Field(description="rules or llm.")
    notes: list[str]
    viewpoint: dict[str, Any] | None


class QueryResponse(BaseModel):
    """A query's answer, ranked candidates, parsed request, readable trace and timings."""

    query: str
    answer: Answer | None
    candidates: list[Candidate]
    constraints: ParsedRequest
    trace: list[str] = Field(description="What each stage did, in order.")
    timings_ms: dict[str, float] = Field(description="parse, retrieve, verify, total.")
    plan: str | None = Field(None, description="The query plan (when asked for).")
    conversation_id: str | None = Field(None, description="The conversation it belongs to.")
