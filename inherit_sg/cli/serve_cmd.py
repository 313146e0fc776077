"""``inherit-sg serve --map DIR``: serve a map (or a folder of maps) over REST.

Register on the main app with ``app.command("serve")(serve_cmd.serve)``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from inherit_sg.cli.output import handle_errors


@handle_errors
def serve(
    map_dir: Annotated[
        Path, typer.Option("--map", "-m", help="A map directory, or a folder of maps.")
    ],
    host: Annotated[str, typer.Option(help="Interface to bind (loopback by default).")] = (
        "127.0.0.1"
    ),
    port: Annotated[int, typer.Option(min=1, max=65535, help="TCP port.")] = 8765,
) -> None:
    """Serve maps read-only at http://HOST:PORT/v1/maps/{name} (name = directory name)."""
    import uvicorn

    from api.app import create_app

    app = create_app(map_dir)
    typer.echo(f"serving {map_dir} at http://{host}:{port}/v1/maps/")
    uvicorn.run(app, host=host, port=port, log_level="info")
