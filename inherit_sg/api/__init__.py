"""The REST service of INHerit-SG: a FastAPI app (:func:`inherit_sg.api.app.create_app`) that serves
one or more maps under ``/v1/maps/{name}/…`` (read-only; writable while a live mapping
session runs) as a thin face over :class:`inherit_sg.facade.MapService`, plus the web
viewer at ``/``."""

from __future__ import annotations

from inherit_sg.api.app import create_app

__all__ = ["create_app"]
