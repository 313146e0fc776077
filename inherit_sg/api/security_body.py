"""Request body size limit as pure ASGI middleware.

A declared ``Content-Length`` above the limit answers 413 before any byte is read; a
streamed (chunked) body is counted as it arrives and answers 413 as soon as it passes the
limit — the route then sees a disconnect and whatever it sends is dropped.
"""

from __future__ import annotations

from starlette.responses import JSONResponse
from starlette.types import ASGIApp, Message, Receive, Scope, Send


def _too_large(scope: Scope, max_bytes: int) -> JSONResponse:
    where = f"{scope.get('method', '')} {scope.get('path', '')}".strip()
    body = {
        "error": "payload_too_large",
        "message": f"{where}: request body exceeds {max_bytes} bytes (service.max_body_mb)",
    }
    return JSONResponse(body, status_code=413, headers={"Connection": "close"})


def _declared_length(scope: Scope) -> int | None:
    """The ``Content-Length`` header as an int; -1 when present but malformed."""
    for name, value in scope.get("headers", ()):
        if name.lower() == b"content-length":
            text = value.decode("latin-1").strip()
            return int(text) if text.isdigit() else -1
    return None


class BodyLimitMiddleware:
    """Reject request bodies larger than ``max_bytes`` with a 413 JSON answer."""

    def __init__(self, app: ASGIApp, max_bytes: int) -> None:
        self.app = app
        self.max_bytes = max_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = _declared_length(scope)
        if declared == -1:
            bad = JSONResponse(
                {"error": "bad_input", "message": "Content-Length header is not a number"},
                status_code=400,
            )
            await bad(scope, receive, send)
            return
        if declared is not None and declared > self.max_bytes:
            await _too_large(scope, self.max_bytes)(scope, receive, send)
            return

        received = 0
        answered = False  # our 413 went out; drop what the route sends after it
        cut = False  # the route is told the client went away
        started = False

        async def guarded_send(message: Message) -> None:
            nonlocal started
            if answered:
                return
            if message["type"] == "http.response.start":
                started = True
            await send(message)

        async def counted_receive() -> Message:
            nonlocal received, answered, cut
            if cut:
                return {"type": "http.disconnect"}
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > self.max_bytes:
                    if not started:
                        await _too_large(scope, self.max_bytes)(scope, receive, send)
                        answered = True
                    cut = True
                    return {"type": "http.disconnect"}
            return message

        try:
            await self.app(scope, counted_receive, guarded_send)
        except Exception:
            # The route fails on the disconnect it was handed; the client has its 413.
            if not answered:
                raise
