"""``inherit-sg serve --map DIR``: serve a map (or a folder of maps) over REST.

Host and port default to ``service.host`` / ``service.port`` of the configuration (TOML
file, ``INHERIT_SG_SERVICE__*`` environment variables, ``--set``); ``--host`` and
``--port`` override them. Register on the main app with
``app.command("serve")(serve_cmd.serve)``.
"""

from __future__ import annotations

import ipaddress
from pathlib import Path
from typing import Annotated

import typer

from inherit_sg.cli.output import ConfigFileOption, OverridesOption, handle_errors
from inherit_sg.config import Config
from inherit_sg.errors import InputError

LOOPBACK_NAMES = frozenset({"localhost", "localhost.localdomain", "ip6-localhost"})


def is_loopback(host: str) -> bool:
    """True when ``host`` names a loopback interface only."""
    name = host.strip().strip("[]").lower()
    if name in LOOPBACK_NAMES:
        return True
    try:
        return ipaddress.ip_address(name).is_loopback
    except ValueError:
        return False


def exposure_warning(host: str, config: Config) -> str | None:
    """What is wrong when ``host`` is reachable from other machines and no API key is set
    (anyone could then read the maps, run Cypher and start mapping sessions); None when
    the host is loopback or a key is set."""
    svc = config.service
    if is_loopback(host) or svc.read_keys or svc.write_keys:
        return None
    return (
        f"serving on {host} without API keys — anyone who can reach this port can read the "
        "maps, run Cypher and start mapping sessions; set service.read_keys / "
        "service.write_keys"
    )


def checked_exposure(host: str, config: Config, insecure: bool) -> str | None:
    """:func:`exposure_warning` for binding ``host``; an InputError when it is exposed and
    ``insecure`` was not given (the warning to show at start-up otherwise)."""
    exposed = exposure_warning(host, config)
    if exposed is not None and not insecure:
        raise InputError(f"refusing to start: {exposed} (or pass --insecure)")
    return exposed


def url_host(host: str) -> str:
    """``host`` as written in a URL (an IPv6 address in brackets)."""
    return f"[{host}]" if ":" in host else host


@handle_errors
def serve(
    map_dir: Annotated[
        Path, typer.Option("--map", "-m", help="A map directory, or a folder of maps.")
    ],
    host: Annotated[
        str | None,
        typer.Option(help="Interface to bind (default: service.host, 127.0.0.1)."),
    ] = None,
    port: Annotated[
        int | None,
        typer.Option(min=1, max=65535, help="TCP port (default: service.port, 8765)."),
    ] = None,
    config_file: ConfigFileOption = None,
    overrides: OverridesOption = None,
    insecure: Annotated[
        bool,
        typer.Option(
            "--insecure",
            help="Serve on a non-loopback host without API keys (refused otherwise).",
        ),
    ] = False,
    workers: Annotated[
        int | None,
        typer.Option(
            min=1,
            max=64,
            help="Server processes (default: service.workers, 1). More than one serves "
            "the maps read-only: no live sessions, no conversations.",
        ),
    ] = None,
    ray: Annotated[
        bool,
        typer.Option(
            "--ray",
            help="Serve as a Ray Serve deployment of --replicas read-only replicas "
            "(needs inherit-sg[ray]; see docs/scaling.md).",
        ),
    ] = False,
    ray_address: Annotated[
        str | None,
        typer.Option(help="With --ray: the cluster (default: a local one sized to this machine)."),
    ] = None,
    replicas: Annotated[
        int, typer.Option(min=1, max=256, help="With --ray: replicas of the app.")
    ] = 2,
) -> None:
    """Serve maps at http://HOST:PORT/v1/maps/{name} (name = directory name). On a host
    other machines can reach, API keys are required unless --insecure is given."""
    import uvicorn

    from inherit_sg.api.app import create_app
    from inherit_sg.config import load_config

    cfg = load_config(config_file, overrides or [])
    bind_host = host if host is not None else cfg.service.host
    bind_port = port if port is not None else cfg.service.port
    exposed = checked_exposure(bind_host, cfg, insecure)
    if workers is not None:
        cfg = cfg.model_copy(
            update={"service": cfg.service.model_copy(update={"workers": workers})}
        )
    if ray:
        _serve_on_ray(map_dir, cfg, bind_host, bind_port, replicas, ray_address, exposed)
        return
    processes = cfg.service.workers
    app = create_app(map_dir, cfg)  # checks the maps before any worker starts
    if exposed is not None:
        typer.secho(f"warning: {exposed}", fg=typer.colors.YELLOW, err=True)
    typer.echo(
        f"serving {map_dir} at http://{url_host(bind_host)}:{bind_port}/v1/maps/"
        + (f" ({processes} processes, read-only)" if processes > 1 else "")
    )
    if processes == 1:
        uvicorn.run(app, host=bind_host, port=bind_port, log_level="info")
        return
    import os

    from inherit_sg.api.workers import worker_environment

    os.environ.update(worker_environment(map_dir.absolute(), cfg))
    run_workers(bind_host, bind_port, processes)


def _serve_on_ray(
    map_dir: Path,
    cfg: Config,
    host: str,
    port: int,
    replicas: int,
    address: str | None,
    exposed: str | None,
) -> None:
    """``serve --ray``: the same app as a Ray Serve deployment (inherit_sg.scale.serve)."""
    from inherit_sg.api.state import resolve_maps
    from inherit_sg.scale import require_ray

    names = resolve_maps(map_dir)  # bad paths fail here, before Ray starts
    require_ray()
    from inherit_sg.scale.serve import run_serve

    if exposed is not None:
        typer.secho(f"warning: {exposed}", fg=typer.colors.YELLOW, err=True)

    def ready() -> None:
        typer.echo(
            f"serving {len(names)} map(s) from {map_dir} at http://{url_host(host)}:{port}/v1/maps/ "
            f"({replicas} Ray Serve replicas, read-only)"
        )

    run_serve(map_dir, cfg, host=host, port=port, replicas=replicas, address=address, ready=ready)


def run_workers(host: str, port: int, processes: int) -> None:
    """uvicorn's worker processes on one listening socket, with Nagle's algorithm off on
    it (Linux hands that to every accepted connection): uvicorn's own multi-process
    socket left it on, and a kept-alive client then waited ~45 ms per answer for the
    ACK of its first part (measured: 48 ms per request instead of 5 ms)."""
    import socket

    import uvicorn
    from uvicorn.supervisors import Multiprocess

    config = uvicorn.Config(
        "inherit_sg.api.workers:app_from_environment",
        factory=True,
        workers=processes,
        host=host,
        port=port,
        log_level="info",
    )
    sock = config.bind_socket()
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    Multiprocess(config, sockets=[sock]).run()
