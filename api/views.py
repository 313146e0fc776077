"""The web viewer (static files at ``/``) and the picture and listing routes it uses."""

from __future__ import annotations

from fastapi import FastAPI


def install(app: FastAPI) -> None:
    """Add the viewer's routes and static files to ``app``."""
