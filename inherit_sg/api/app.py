"""The FastAPI app: thin routes over :class:`~inherit_sg.facade.MapService`.

``create_app(maps)`` serves one map (a directory, under its basename), every map inside a
root folder, or an explicit ``{name: directory}`` dict at ``/v1/maps/{name}``: read-only,
except while a live mapping session (``POST …/sessions``) holds a map writable.
"""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path
from urllib.parse import quote

from fastapi import FastAPI, Request
from fastapi.responses import JSONResponse

from inherit_sg import __version__
from inherit_sg.api import live, security, views
from inherit_sg.api.errors import install_error_handlers
from inherit_sg.api.models import CypherRequest, CypherResponse, HealthResponse, QueryRequest
from inherit_sg.api.state import Registry, resolve_maps, served_map
from inherit_sg.api.views import FloorQ, LabelQ, Limit, Offset, RoomQ
from inherit_sg.config import Config, load_config
from inherit_sg.errors import InputError
from inherit_sg.json_values import jsonable
from inherit_sg.reads.models import MapStats, ObjectDetail, ObjectPage
from inherit_sg.retrieval.result_models import QueryResponse


def with_image_links(detail: ObjectDetail, map_name: str) -> ObjectDetail:
    """``detail`` with each keyframe's JPEG path under ``/v1/maps/{map_name}``."""
    base = f"/v1/maps/{map_name}/keyframes"
    frames = [
        kf.model_copy(update={"image": f"{base}/{quote(kf.id, safe=':')}.jpg"})
        for kf in detail.keyframes
    ]
    return detail.model_copy(update={"keyframes": frames})


def create_app(maps: dict[str, Path] | Path, config: Config | None = None) -> FastAPI:
    """The REST app serving ``maps``; each map is opened read-only once, at startup
    (reopened writable for a live session), and closed at shutdown."""
    named = resolve_maps(maps)
    cfg = config or load_config()

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        app.state.registry = Registry(named, cfg)
        try:
            yield
        finally:
            app.state.registry.close()

    app = FastAPI(title="INHerit-SG", version=__version__, lifespan=lifespan)
    install_error_handlers(app)
    security.install(app, cfg)

    @app.get("/healthz")
    def healthz() -> HealthResponse:
        """Liveness: the process answers."""
        return HealthResponse(status="ok")

    @app.get("/readyz", response_model=HealthResponse)
    def readyz(request: Request) -> JSONResponse:
        """Readiness: 200 when every served map is open, 503 naming the ones that are not."""
        registry: Registry = request.app.state.registry
        states = {name: s.status for name, s in registry.maps.items()}
        ready = all(v == "ok" for v in states.values())
        body = HealthResponse(status="ok" if ready else "unavailable", maps=states)
        return JSONResponse(body.model_dump(), status_code=200 if ready else 503)

    @app.get("/v1/maps/{map}")
    def map_stats(request: Request, map: str) -> MapStats:
        """Counts per table, sessions and bytes on disk."""
        served = served_map(request, map)
        with served.lock:
            return MapStats.model_validate(served.require().stats())

    @app.post("/v1/maps/{map}/query", response_model_exclude_unset=True)
    def query(request: Request, map: str, body: QueryRequest) -> QueryResponse:
        """Answer a natural-language request (the query result JSON of the CLI)."""
        served = served_map(request, map)
        registry: Registry = request.app.state.registry
        if body.conversation_id is not None and cfg.service.workers > 1:
            raise InputError(
                f"conversation_id needs a server with one process (serve --workers 1): "
                f"this one runs {cfg.service.workers}, and a conversation's history lives "
                "in the process that answered it"
            )
        conv = (
            registry.conversation(map, body.conversation_id)
            if body.conversation_id is not None
            else None
        )
        with served.lock:
            result = served.require().query(
                body.text,
                conversation=conv,
                verify=body.verify,
                top_k=body.top_k,
                viewer=body.viewer.pose() if body.viewer is not None else None,
            )
        out = result.to_dict()
        if body.conversation_id is not None:
            out["conversation_id"] = body.conversation_id
        return QueryResponse.model_validate(out)

    @app.post("/v1/maps/{map}/cypher")
    def cypher(request: Request, map: str, body: CypherRequest) -> CypherResponse:
        """Run a read-only Cypher query; write clauses answer 403."""
        served = served_map(request, map)
        with served.lock:
            service = served.require()
        # not under the map's lock: the statement runs in the map's Cypher worker (a
        # process of its own, stopped at the time limit) and blocks no other request
        result = service.cypher(
            body.query,
            body.params,
            max_rows=body.max_rows,
            timeout_s=body.timeout_s or cfg.service.cypher_timeout_s,
        )
        # BLOB columns (room masks) come back as {"base64": …}, as in `cypher --json`
        return CypherResponse(
            columns=result.columns, rows=jsonable(result.rows), truncated=result.truncated
        )

    @app.get("/v1/maps/{map}/objects")
    def objects(
        request: Request,
        map: str,
        floor: FloorQ = None,
        room: RoomQ = None,
        label: LabelQ = None,
        limit: Limit = 100,
        offset: Offset = 0,
    ) -> ObjectPage:
        """A page of objects, ordered by id."""
        served = served_map(request, map)
        with served.lock:
            return served.require().objects(
                floor=floor, room=room, label=label, limit=limit, offset=offset
            )

    @app.get("/v1/maps/{map}/objects/{object_id}")
    def object_detail(request: Request, map: str, object_id: str) -> ObjectDetail:
        """One object with its relations and hierarchy path; 404 when absent."""
        served = served_map(request, map)
        with served.lock:
            detail = served.require().object(object_id)
        return with_image_links(detail, map)

    app.include_router(live.router)
    views.install(app)
    return app
