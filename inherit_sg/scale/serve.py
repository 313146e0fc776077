"""``inherit-sg serve --ray``: the REST app as a Ray Serve deployment with N replicas.

Each replica builds the same FastAPI app as ``serve`` (:func:`inherit_sg.api.app.create_app`)
in its own process and opens the maps read-only, as ``serve --workers N`` does: live
sessions and conversations are refused there, since another replica may answer the next
request. Every answer carries the replica's process id in :data:`REPLICA_HEADER`. The
maps must be readable by every node at the same path (shared storage), and no writer may
hold them while they are served.
"""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path
from typing import Any

from inherit_sg.config import Config
from inherit_sg.scale import require_ray

REPLICA_HEADER = "x-inherit-sg-replica"
APP_NAME = "inherit-sg"


def build_replica_app(maps: str, config: dict[str, Any]) -> Any:
    """The FastAPI app of one replica: ``create_app`` on ``maps`` with ``config`` (a
    :class:`Config` dump), each answer tagged with this process's id."""
    from fastapi import FastAPI, Request, Response

    from inherit_sg.api.app import create_app

    app: FastAPI = create_app(Path(maps), Config.model_validate(config))
    pid = str(os.getpid())

    @app.middleware("http")
    async def tag_replica(request: Request, call_next: Any) -> Response:
        response: Response = await call_next(request)
        response.headers[REPLICA_HEADER] = pid
        return response

    return app


def deployment(maps: Path, config: Config, *, replicas: int, cpus_per_replica: float) -> Any:
    """The bound Ray Serve application: ``replicas`` copies of the REST app on ``maps``."""
    require_ray()
    from ray import serve

    cfg = config.model_copy(
        update={"service": config.service.model_copy(update={"workers": max(2, replicas)})}
    )

    @serve.deployment(
        name="maps",
        num_replicas=replicas,
        ray_actor_options={"num_cpus": cpus_per_replica},
        health_check_period_s=5,
    )
    @serve.ingress()
    class MapsDeployment:
        """The REST app on the served maps; built once per replica."""

        def __init__(self, maps: str, config: dict[str, Any]) -> None:
            self.maps, self.config = maps, config

        def __serve_build_asgi_app__(self) -> Any:
            return build_replica_app(self.maps, self.config)

    app: Any = MapsDeployment  # a serve Deployment: the decorator replaced the class
    return app.bind(str(maps.absolute()), cfg.model_dump(mode="json"))


def _interrupt(signum: int, frame: Any) -> None:
    raise KeyboardInterrupt


def run_serve(
    maps: Path,
    config: Config,
    *,
    host: str,
    port: int,
    replicas: int,
    address: str | None = None,
    cpus_per_replica: float = 1.0,
    ready: Any = None,
) -> None:
    """Serve ``maps`` on Ray Serve at ``http://host:port`` until interrupted: on the
    cluster at ``address``, else on a local cluster sized to this machine. ``ready`` is
    called once the replicas answer."""
    from ray import serve

    from inherit_sg.scale.cluster import ray_session

    signal.signal(signal.SIGTERM, _interrupt)  # a stopped service shuts Serve down too
    with ray_session(address):
        serve.start(http_options={"host": host, "port": port})
        try:
            serve.run(
                deployment(maps, config, replicas=replicas, cpus_per_replica=cpus_per_replica),
                name=APP_NAME,
                route_prefix="/",
            )
            if ready is not None:
                ready()
            while True:
                time.sleep(1.0)
        except KeyboardInterrupt:
            pass
        finally:
            serve.shutdown()
