"""Request and response models of the live mapping routes."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class SessionRequest(BaseModel):
    """``POST /v1/maps/{map}/sessions``: start a live mapping session."""

    model_config = ConfigDict(extra="forbid")

    name: str | None = Field(
        None, min_length=1, max_length=128, description="Session name (default live-N)."
    )
    frame_queue: int = Field(
        8, ge=1, le=1024, description="Frames waiting for the geometric stream before 429."
    )
    flush_every: int = Field(
        20, ge=1, le=10_000, description="Persist (and expose to queries) every n keyframes."
    )


class SessionCreated(BaseModel):
    """A started live session."""

    session_id: str
    name: str
    map: str


class FrameAccepted(BaseModel):
    """A frame taken into the session: its index and the session's counters."""

    frame: int
    keyframes: int
    dropped: int
    objects: int
    queued: int
