"""Live mapping over HTTP: sessions that feed posted frames to the dual-stream mapper."""

from __future__ import annotations

from fastapi import APIRouter

router = APIRouter()
