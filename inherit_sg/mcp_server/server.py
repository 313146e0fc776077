"""The MCP server over a set of maps, and its two transports: stdio (the server is a child
process of the agent's client) and streamable HTTP (``/mcp``, with ``/healthz`` open)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from contextlib import AbstractAsyncContextManager
from pathlib import Path
from typing import Any

import anyio
import anyio.to_thread
from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from mcp.server.mcpserver import MCPServer
from mcp_types import Resource
from starlette.requests import Request
from starlette.responses import JSONResponse, Response
from starlette.types import ASGIApp, Receive, Scope, Send

from inherit_sg import __version__
from inherit_sg.api.security import KeyRing, bearer_token, route_path
from inherit_sg.config import Config
from inherit_sg.mcp_server.access import Access
from inherit_sg.mcp_server.common import ServedMaps
from inherit_sg.mcp_server.live_tools import LiveTools
from inherit_sg.mcp_server.pictures import Pictures
from inherit_sg.mcp_server.tools import ReadTools

HTTP_PATH = "/mcp"
HEALTH_PATH = "/healthz"


def instructions(names: list[str]) -> str:
    """What the server tells an agent about itself."""
    shown = ", ".join(names[:20]) + (f" and {len(names) - 20} more" if len(names) > 20 else "")
    return (
        f"INHerit-SG scene graphs of buildings (maps: {shown}): floors → rooms → functional "
        "areas → objects, with doors between rooms and spatial relations between objects; "
        "positions are world coordinates in metres, z up. Use find for requests in plain "
        "words ('the mug on the table next to the window'); list_floors, list_rooms and "
        "list_objects to browse; describe_node for one node; schema, then cypher, for "
        "questions the other tools do not answer; floor_plan and best_view for pictures."
    )


class MapServer(MCPServer[Any]):
    """An :class:`MCPServer` whose resource list also names every floor's BEV picture."""

    def __init__(self, pictures: Pictures, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.pictures = pictures

    async def list_resources(self) -> list[Resource]:
        """The registered resources and the BEV of each floor of each open map."""
        listed = await super().list_resources()
        return listed + await anyio.to_thread.run_sync(self.pictures.floor_resources)


class ToolFilter:
    """Server middleware that leaves out of ``tools/list`` the tools the caller's key
    does not allow (:meth:`Access.allows`)."""

    def __init__(self, access: Access) -> None:
        self.access = access

    async def __call__(
        self, ctx: ServerRequestContext[Any, Any], call_next: CallNext
    ) -> HandlerResult:
        """Filter the tool list of a ``tools/list`` answer; pass everything else on."""
        result = await call_next(ctx)
        if ctx.method == "tools/list" and isinstance(result, dict):
            headers: Mapping[str, str] | None = getattr(ctx.request, "headers", None)
            scope = self.access.scope(headers)
            result["tools"] = [
                t for t in result.get("tools", []) if self.access.allows(str(t.get("name")), scope)
            ]
        return result


def build_server(maps: dict[str, Path], config: Config, access: Access) -> MapServer:
    """The MCP server of ``maps`` (name → directory), opened when it starts serving."""
    served = ServedMaps(maps, config)
    pictures = Pictures(served)

    def lifespan(_: MCPServer[Any]) -> AbstractAsyncContextManager[Any]:
        return served.opened()

    server = MapServer(
        pictures,
        name="inherit-sg",
        title="INHerit-SG maps",
        version=__version__,
        instructions=instructions(served.names),
        lifespan=lifespan,
        log_level="WARNING",
    )
    ReadTools(served, access).install(server)
    pictures.install(server)
    if access.live:
        LiveTools(served, access).install(server)
    server.middleware.append(ToolFilter(access))

    @server.custom_route(HEALTH_PATH, methods=["GET"])
    async def healthz(request: Request) -> Response:
        """Open readiness probe: 200 with every map's status once all are open."""
        registry = served.registry
        states = {} if registry is None else {n: s.status for n, s in registry.maps.items()}
        ready = registry is not None and all(v == "ok" for v in states.values())
        return JSONResponse(
            {"status": "ok" if ready else "unavailable", "maps": states},
            status_code=200 if ready else 503,
        )

    return server


class KeyGate:
    """ASGI middleware: with keys configured, every HTTP request but the health probe
    needs ``Authorization: Bearer <read or write key>`` (401 otherwise); which tools a
    key may call is decided per tool (:class:`Access`)."""

    def __init__(self, app: ASGIApp, keys: KeyRing) -> None:
        self.app = app
        self.keys = keys

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if (
            scope["type"] != "http"
            or not self.keys.enabled
            or route_path(scope) == HEALTH_PATH
            or self.keys.scope_of(bearer_token(scope)) is not None
        ):
            await self.app(scope, receive, send)
            return
        response = JSONResponse(
            {
                "error": "unauthorized",
                "message": "send a valid API key as 'Authorization: Bearer KEY'",
            },
            status_code=401,
            headers={"WWW-Authenticate": 'Bearer realm="inherit-sg"'},
        )
        await response(scope, receive, send)


def http_app(server: MapServer, config: Config, access: Access, host: str) -> ASGIApp:
    """The streamable-HTTP app of ``server`` at :data:`HTTP_PATH`, behind the key gate."""
    app = server.streamable_http_app(
        streamable_http_path=HTTP_PATH,
        host=host,
        max_request_body_size=int(config.service.max_body_mb * 1024 * 1024),
    )
    return KeyGate(app, access.keys)


def run_stdio(server: MapServer) -> None:
    """Serve over this process's stdin and stdout until the client closes them."""
    anyio.run(server.run_stdio_async)


def run_http(
    server: MapServer,
    config: Config,
    access: Access,
    host: str,
    port: int,
    ready: Callable[[], None] | None = None,
) -> None:
    """Serve over streamable HTTP at ``http://host:port/mcp`` until interrupted."""
    import uvicorn

    app = http_app(server, config, access, host)
    if ready is not None:
        ready()
    uvicorn.run(app, host=host, port=port, log_level="info")
