"""What every MCP tool shares: the served maps (the REST service's
:class:`~inherit_sg.api.state.Registry`), the ``map`` argument and the translation of
INHerit-SG errors into tool errors the agent reads."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator
from contextlib import asynccontextmanager, contextmanager
from pathlib import Path
from typing import Annotated

import anyio.to_thread
from mcp.server.mcpserver.exceptions import ResourceError, ResourceNotFoundError, ToolError
from pydantic import Field

from inherit_sg.api.state import Registry, ServedMap
from inherit_sg.config import Config
from inherit_sg.errors import InheritSGError, InputError, MapError, NotFoundError
from inherit_sg.facade import MapService

MapArg = Annotated[
    str | None,
    Field(
        description="Name of the map (see list_maps); may be left out when the server "
        "serves a single map."
    ),
]


class ServedMaps:
    """The maps an MCP server serves, opened read-only while it runs (reopened writable
    for a live mapping session, as REST does)."""

    def __init__(self, maps: dict[str, Path], config: Config) -> None:
        self.paths = maps
        self.config = config
        self.registry: Registry | None = None

    @property
    def names(self) -> list[str]:
        """The served map names."""
        return list(self.paths)

    @asynccontextmanager
    async def opened(self) -> AsyncIterator[Registry]:
        """Open every map for the server's lifetime; close them (finishing a live session
        left open) when it stops."""
        registry = await anyio.to_thread.run_sync(Registry, self.paths, self.config)
        self.registry = registry
        try:
            yield registry
        finally:
            self.registry = None
            await anyio.to_thread.run_sync(registry.close)

    def get(self, name: str | None) -> ServedMap:
        """The map called ``name``; without a name, the only one served."""
        registry = self.registry
        if registry is None:
            raise MapError("the server is not serving (starting or stopping)")
        if name is None:
            if len(registry.maps) == 1:
                return next(iter(registry.maps.values()))
            raise InputError(
                f"this server serves {len(registry.maps)} maps ({', '.join(registry.maps)}): "
                "name one with the 'map' argument"
            )
        return registry.get(name)

    @contextmanager
    def service(self, name: str | None) -> Iterator[MapService]:
        """The open service of the map called ``name`` (see :meth:`get`), held under the
        map's lock for the ``with`` block."""
        served = self.get(name)
        with served.lock:
            yield served.require()


@contextmanager
def reported() -> Iterator[None]:
    """Raise an INHerit-SG error as a :class:`ToolError` (an ``isError`` result whose
    text names the error code and what is wrong)."""
    try:
        yield
    except InheritSGError as exc:
        raise ToolError(f"{exc.code}: {exc.message}") from None


@contextmanager
def resource_errors() -> Iterator[None]:
    """Raise an INHerit-SG error as a resource error: 'not found' and bad input as
    invalid params, anything else as an internal error."""
    try:
        yield
    except (NotFoundError, InputError) as exc:
        raise ResourceNotFoundError(f"{exc.code}: {exc.message}") from None
    except InheritSGError as exc:
        raise ResourceError(f"{exc.code}: {exc.message}") from None
