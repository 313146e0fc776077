"""The one place where errors become HTTP answers.

Every :class:`~inherit_sg.errors.InheritSGError` carries its own ``http_status`` and
``to_dict()`` body; request validation errors (400) and routing errors (404, 405) answer
in the same ``{"error", "message"}`` JSON shape, and so does any unexpected error (500,
logged with its traceback).
"""

from __future__ import annotations

import logging

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException

from inherit_sg.errors import BackPressureError, InheritSGError

log = logging.getLogger(__name__)


def error_response(exc: InheritSGError) -> JSONResponse:
    """The JSON answer for one library error (status from the error class)."""
    headers: dict[str, str] = {}
    if isinstance(exc, BackPressureError):
        headers["Retry-After"] = str(max(1, round(exc.retry_after_s)))
    return JSONResponse(exc.to_dict(), status_code=exc.http_status, headers=headers)


async def _library_error(request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, InheritSGError)
    return error_response(exc)


async def _validation_error(request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, RequestValidationError)
    parts = []
    for err in exc.errors():
        where = ".".join(str(p) for p in err.get("loc", ()))
        parts.append(f"{where}: {err.get('msg', 'invalid')}")
    body = {"error": "bad_input", "message": "; ".join(parts) or "invalid request"}
    return JSONResponse(body, status_code=400)


async def _http_error(request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, HTTPException)
    code = "not_found" if exc.status_code == 404 else "http_error"
    body = {"error": code, "message": f"{request.method} {request.url.path}: {exc.detail}"}
    return JSONResponse(body, status_code=exc.status_code, headers=exc.headers)


async def _unexpected_error(request: Request, exc: Exception) -> JSONResponse:
    # a bug, not bad input: log it with its traceback, answer in the usual shape
    log.error("%s %s failed", request.method, request.url.path, exc_info=exc)
    body = {
        "error": "internal_error",
        "message": f"{request.method} {request.url.path}: {type(exc).__name__} (see server log)",
    }
    return JSONResponse(body, status_code=500)


def install_error_handlers(app: FastAPI) -> None:
    """Register the handlers that turn errors into JSON bodies on ``app``."""
    app.add_exception_handler(InheritSGError, _library_error)
    app.add_exception_handler(RequestValidationError, _validation_error)
    app.add_exception_handler(HTTPException, _http_error)
    app.add_exception_handler(Exception, _unexpected_error)
