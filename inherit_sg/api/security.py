"""API keys, CORS and request size limits of the REST service.

Access rule (``config.service``):

* No ``read_keys`` and no ``write_keys``: every route is open (the loopback default).
* Any key configured: every route under ``/v1`` needs ``Authorization: Bearer <key>``;
  a missing or unknown key answers 401 with ``WWW-Authenticate: Bearer``.
  ``/healthz``, ``/readyz``, ``/docs``, ``/openapi.json`` and the viewer's static files
  stay open.
* Reads (``GET``/``HEAD``/``OPTIONS``, and ``POST /v1/maps/{map}/query``) accept a read
  or a write key. Every other ``/v1`` request — Cypher (``POST .../cypher``) and all
  session and frame posts under ``/v1/maps/{map}/sessions`` included — needs a write
  key; a read key answers 403. New non-GET routes are therefore write routes unless
  listed in :data:`READ_POSTS`.

Keys are compared in constant time. Bodies larger than ``service.max_body_mb`` answer
413 (see :mod:`api.security_body`). CORS is off unless ``service.cors_origins`` is set.
"""

from __future__ import annotations

import hmac
import re
from collections.abc import Iterable

from fastapi import FastAPI
from starlette.middleware.cors import CORSMiddleware
from starlette.responses import JSONResponse
from starlette.types import ASGIApp, Receive, Scope, Send

from inherit_sg.api.security_body import BodyLimitMiddleware
from inherit_sg.config import Config
from inherit_sg.errors import ConfigError

PROTECTED_PREFIX = "/v1"
SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})
READ_POSTS = (re.compile(r"^/v1/maps/[^/]+/query/?$"),)
# WebSocket close code "policy violation" (RFC 6455).
WS_POLICY_VIOLATION = 1008


def _encoded(keys: Iterable[str], field: str) -> tuple[bytes, ...]:
    out = []
    for key in keys:
        if not key.strip():
            raise ConfigError(f"service.{field} contains an empty key")
        out.append(key.encode("utf-8"))
    return tuple(out)


class KeyRing:
    """The configured read and write keys; a write key also grants read."""

    def __init__(self, read_keys: Iterable[str], write_keys: Iterable[str]) -> None:
        self.write = _encoded(write_keys, "write_keys")
        self.read = _encoded(read_keys, "read_keys") + self.write

    @property
    def enabled(self) -> bool:
        """True when any key is configured (then ``/v1`` needs one)."""
        return bool(self.read)

    @staticmethod
    def _matches(candidate: bytes, keys: tuple[bytes, ...]) -> bool:
        # Compare against every key, without stopping early, so timing reveals nothing.
        found = False
        for key in keys:
            found |= hmac.compare_digest(candidate, key)
        return found

    def scope_of(self, token: str | None) -> str | None:
        """``"write"``, ``"read"`` or None (missing or unknown) for a bearer token."""
        if not token:
            return None
        candidate = token.encode("utf-8")
        if self._matches(candidate, self.write):
            return "write"
        if self._matches(candidate, self.read):
            return "read"
        return None


def route_path(scope: Scope) -> str:
    """The request path as routing sees it (without ``root_path``, one leading slash)."""
    path: str = scope.get("path", "/")
    root: str = scope.get("root_path", "")
    if root and path.startswith(root):
        path = path[len(root) :]
    return "/" + path.lstrip("/")


def is_protected(path: str) -> bool:
    """True for paths under ``/v1``."""
    return path == PROTECTED_PREFIX or path.startswith(PROTECTED_PREFIX + "/")


def needs_write(method: str, path: str) -> bool:
    """True when ``method path`` needs the write scope (see the module docstring)."""
    if method.upper() in SAFE_METHODS:
        return False
    return not (method.upper() == "POST" and any(p.match(path) for p in READ_POSTS))


def parse_bearer(value: str | None) -> str | None:
    """The token of an ``Authorization`` header value ``Bearer <token>``, or None."""
    scheme, _, token = (value or "").strip().partition(" ")
    if scheme.lower() == "bearer" and token.strip():
        return token.strip()
    return None


def bearer_token(scope: Scope) -> str | None:
    """The token of an ``Authorization: Bearer`` header, or None."""
    for name, value in scope.get("headers", ()):
        if name.lower() == b"authorization":
            return parse_bearer(value.decode("latin-1"))
    return None


class ApiKeyMiddleware:
    """Pure ASGI middleware enforcing the key rule of this module."""

    def __init__(self, app: ASGIApp, keys: KeyRing) -> None:
        self.app = app
        self.keys = keys

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket") or not self.keys.enabled:
            await self.app(scope, receive, send)
            return
        path = route_path(scope)
        if not is_protected(path):
            await self.app(scope, receive, send)
            return
        method = scope.get("method", "GET") if scope["type"] == "http" else "GET"
        granted = self.keys.scope_of(bearer_token(scope))
        if granted is not None and (granted == "write" or not needs_write(method, path)):
            await self.app(scope, receive, send)
            return
        if scope["type"] == "websocket":
            await send({"type": "websocket.close", "code": WS_POLICY_VIOLATION})
            return
        if granted is None:
            body = {
                "error": "unauthorized",
                "message": f"{method} {path}: send a valid API key as 'Authorization: Bearer KEY'",
            }
            header = 'Bearer realm="inherit-sg"'
            status = 401
        else:
            body = {"error": "forbidden", "message": f"{method} {path}: needs a write key"}
            header = 'Bearer realm="inherit-sg", error="insufficient_scope"'
            status = 403
        response = JSONResponse(body, status_code=status, headers={"WWW-Authenticate": header})
        await response(scope, receive, send)


def install(app: FastAPI, config: Config) -> None:
    """Add the security middleware configured in ``config.service`` to ``app``.

    Order, outermost first: CORS (when configured, so preflights and error answers carry
    its headers), API keys, body size limit.
    """
    svc = config.service
    keys = KeyRing(svc.read_keys, svc.write_keys)
    limit = int(svc.max_body_mb * 1024 * 1024)
    # add_middleware wraps: the last added runs first.
    app.add_middleware(BodyLimitMiddleware, max_bytes=limit)
    app.add_middleware(ApiKeyMiddleware, keys=keys)
    if svc.cors_origins:
        app.add_middleware(
            CORSMiddleware,
            allow_origins=list(svc.cors_origins),
            allow_methods=["*"],
            allow_headers=["Authorization", "Content-Type"],
        )
