"""``inherit-sg mcp --map DIR|ROOT``: serve maps to LLM agents over the Model Context
Protocol (stdio by default, or streamable HTTP with ``--transport http``).

The server is :mod:`inherit_sg.mcp_server`, which needs the ``mcp`` extra; the SDK is
imported only here, when the command runs. Register on the main app with
``app.command("mcp")(mcp_cmd.mcp)``.
"""

from __future__ import annotations

import os
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from inherit_sg.cli.output import ConfigFileOption, OverridesOption, handle_errors
from inherit_sg.cli.serve_cmd import checked_exposure, url_host
from inherit_sg.errors import InputError

INSTALL_HINT = "pip install 'inherit-sg[mcp]'"
DEFAULT_PORT = 8766


class Transport(StrEnum):
    """How the MCP client talks to the server."""

    stdio = "stdio"
    http = "http"


def require_mcp() -> None:
    """InputError naming the install command when the MCP SDK is missing."""
    try:
        import mcp.server.mcpserver  # noqa: F401
    except ImportError:
        raise InputError(
            f"the mcp command needs the MCP Python SDK, which is not installed: {INSTALL_HINT}"
        ) from None


@handle_errors
def mcp(
    map_dir: Annotated[
        Path, typer.Option("--map", "-m", help="A map directory, or a folder of maps.")
    ],
    transport: Annotated[
        Transport,
        typer.Option(help="stdio (the client starts this command) or http (streamable HTTP)."),
    ] = Transport.stdio,
    host: Annotated[
        str | None,
        typer.Option(help="http: interface to bind (default: service.host, 127.0.0.1)."),
    ] = None,
    port: Annotated[
        int, typer.Option(min=1, max=65535, help="http: TCP port; the endpoint is /mcp.")
    ] = DEFAULT_PORT,
    config_file: ConfigFileOption = None,
    overrides: OverridesOption = None,
    insecure: Annotated[
        bool,
        typer.Option(
            "--insecure",
            help="http: serve on a non-loopback host without API keys (refused otherwise).",
        ),
    ] = False,
) -> None:
    """Serve maps as MCP tools and resources for LLM agents: find (natural-language
    requests), cypher (read-only), list_floors / list_rooms / list_objects, describe_node,
    schema, floor_plan and best_view pictures, and live mapping sessions with a write key
    (service.write_keys; over stdio the key is read from INHERIT_SG_MCP_KEY)."""
    from inherit_sg.api.state import resolve_maps
    from inherit_sg.config import load_config

    require_mcp()
    from inherit_sg.mcp_server.access import KEY_ENV, Access
    from inherit_sg.mcp_server.server import HTTP_PATH, build_server, run_http, run_stdio

    cfg = load_config(config_file, overrides or [])
    named = resolve_maps(map_dir)  # a bad path fails here, before anything starts
    if transport is Transport.stdio:
        access = Access(cfg, stdio_key=os.environ.get(KEY_ENV) or None)
        access.check_stdio()
        run_stdio(build_server(named, cfg, access))
        return
    bind_host = host if host is not None else cfg.service.host
    exposed = checked_exposure(bind_host, cfg, insecure)
    access = Access(cfg)

    def ready() -> None:
        if exposed is not None:
            typer.secho(f"warning: {exposed}", fg=typer.colors.YELLOW, err=True)
        typer.echo(
            f"serving {len(named)} map(s) over MCP at http://{url_host(bind_host)}:{port}{HTTP_PATH}"
        )

    run_http(build_server(named, cfg, access), cfg, access, bind_host, port, ready=ready)
