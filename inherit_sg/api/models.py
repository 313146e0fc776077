"""Request and response models of the REST service."""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field

from inherit_sg.retrieval.viewer import MAX_COORDINATE, ViewerPose

MAX_CYPHER_ROWS = 10_000
MAX_CYPHER_TIMEOUT_S = 300

Coordinate = Annotated[float, Field(allow_inf_nan=False, ge=-MAX_COORDINATE, le=MAX_COORDINATE)]


class ViewerIn(BaseModel):
    """The robot's pose when the request is made, in the map's world frame."""

    model_config = ConfigDict(extra="forbid")

    position: list[Coordinate] = Field(
        min_length=3, max_length=3, description="[x, y, z] in metres (world frame, z up)."
    )
    yaw_deg: float = Field(
        allow_inf_nan=False,
        description="Heading in degrees, counter-clockwise from +x (0 = looking along +x).",
    )

    def pose(self) -> ViewerPose:
        """As the engine's :class:`ViewerPose`."""
        x, y, z = self.position
        return ViewerPose((x, y, z), self.yaw_deg)


class QueryRequest(BaseModel):
    """``POST /v1/maps/{map}/query``: a natural-language request."""

    model_config = ConfigDict(extra="forbid")

    text: str = Field(description="The request, e.g. 'the mug on the kitchen table'.")
    conversation_id: str | None = Field(
        None,
        max_length=128,
        description="Keeps the history server-side so follow-ups ('the other one') resolve.",
    )
    verify: bool | None = Field(None, description="Run the verifier (config default when null).")
    top_k: int | None = Field(None, ge=1, le=100, description="Candidates to return.")
    viewer: ViewerIn | None = Field(
        None,
        description=(
            "The robot's pose, {position: [x, y, z], yaw_deg}: 'left', 'right', 'in front "
            "of', ordinals ('the second chair from the left') and 'closest to you' are "
            "seen from it unless the request names a viewpoint ('facing the window'). "
            "Without it the viewer is the keyframe that saw most of the candidates."
        ),
    )


class CypherRequest(BaseModel):
    """``POST /v1/maps/{map}/cypher``: a read-only Cypher query."""

    model_config = ConfigDict(extra="forbid")

    query: str = Field(min_length=1, description="A read-only Cypher statement.")
    params: dict[str, Any] = Field(default_factory=dict, description="Query parameters.")
    max_rows: int = Field(1000, ge=1, le=MAX_CYPHER_ROWS, description="Stop after this many rows.")
    timeout_s: float | None = Field(
        None,
        gt=0,
        le=MAX_CYPHER_TIMEOUT_S,
        description="Time limit in seconds (default: service.cypher_timeout_s); 408 past it.",
    )


class CypherResponse(BaseModel):
    """Rows of a Cypher query; ``truncated`` when ``max_rows`` cut the result."""

    columns: list[str]
    rows: list[list[Any]]
    truncated: bool


class HealthResponse(BaseModel):
    """Liveness / readiness answer."""

    status: str
    maps: dict[str, str] = Field(default_factory=dict)
