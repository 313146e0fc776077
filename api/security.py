"""API keys, CORS and request size limits of the REST service."""

from __future__ import annotations

from fastapi import FastAPI

from inherit_sg.config import Config


def install(app: FastAPI, config: Config) -> None:
    """Add the security middleware configured in ``config.service`` to ``app``."""
