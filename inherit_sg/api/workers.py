"""The REST app for one of several server processes (``inherit-sg serve --workers N``).

uvicorn starts each worker process by importing an app factory by name, so the maps to
serve and the configuration travel in one environment variable, set by the command
before uvicorn forks (:func:`worker_environment`). Kuzu lets several processes open a
map read-only at once while no writer holds it, so each worker opens the maps itself;
live sessions and conversations are refused with a clear error (see
``service.workers``).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from fastapi import FastAPI

from inherit_sg.api.app import create_app
from inherit_sg.config import Config
from inherit_sg.errors import InputError

SPEC_VARIABLE = "INHERIT_SG_SERVE_SPEC"


def worker_environment(maps: Path, config: Config) -> dict[str, str]:
    """The environment entry that tells each worker what to serve."""
    spec = {"maps": str(maps), "config": config.model_dump(mode="json")}
    return {SPEC_VARIABLE: json.dumps(spec)}


def app_from_environment() -> FastAPI:
    """The app a worker process serves (uvicorn's factory)."""
    raw = os.environ.get(SPEC_VARIABLE)
    if not raw:
        raise InputError(f"{SPEC_VARIABLE} is not set: start workers with inherit-sg serve")
    spec = json.loads(raw)
    return create_app(Path(spec["maps"]), Config.model_validate(spec["config"]))
