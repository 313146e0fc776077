"""The web viewer (static files at ``/``) and the picture and listing routes it uses."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from fastapi import FastAPI, Query, Request
from fastapi.responses import FileResponse, Response
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel

from inherit_sg.api.state import Registry, served_map
from inherit_sg.reads.models import AreaPage, FloorPage, Hierarchy, RoomPage, Scene3D

STATIC = Path(__file__).resolve().parent / "static"

Limit = Annotated[int, Query(ge=1, le=1000)]
Offset = Annotated[int, Query(ge=0)]
FloorQ = Annotated[str | None, Query(description="Floor id, e.g. floor:0.")]
RoomQ = Annotated[str | None, Query(description="Room id.")]
LabelQ = Annotated[str | None, Query(description="Label (any case).")]
# the response schema of the picture routes: the image's bytes
BINARY = {"type": "string", "format": "binary"}


class MapEntry(BaseModel):
    """A served map and whether it is open."""

    name: str
    status: str


class MapList(BaseModel):
    """The maps this server serves."""

    maps: list[MapEntry]


def install(app: FastAPI) -> None:
    """Add the viewer's routes and static files to ``app``."""

    @app.get("/", include_in_schema=False)
    def index() -> FileResponse:
        """The viewer page."""
        return FileResponse(STATIC / "index.html", media_type="text/html")

    @app.get("/v1/maps")
    def maps(request: Request) -> MapList:
        """The served maps, by name, with 'ok' or the reason a map did not open."""
        registry: Registry = request.app.state.registry
        return MapList(
            maps=[MapEntry(name=name, status=s.status) for name, s in registry.maps.items()]
        )

    @app.get("/v1/maps/{map}/floors")
    def floors(
        request: Request, map: str, label: LabelQ = None, limit: Limit = 100, offset: Offset = 0
    ) -> FloorPage:
        """A page of floors (by id) with room and object counts."""
        served = served_map(request, map)
        with served.lock:
            return served.require().floors(label=label, limit=limit, offset=offset)

    @app.get("/v1/maps/{map}/rooms")
    def rooms(
        request: Request,
        map: str,
        floor: FloorQ = None,
        label: LabelQ = None,
        limit: Limit = 100,
        offset: Offset = 0,
    ) -> RoomPage:
        """A page of rooms (by id) with summary, floor, best view and child counts."""
        served = served_map(request, map)
        with served.lock:
            return served.require().rooms(floor=floor, label=label, limit=limit, offset=offset)

    @app.get("/v1/maps/{map}/areas")
    def areas(
        request: Request,
        map: str,
        floor: FloorQ = None,
        room: RoomQ = None,
        label: LabelQ = None,
        limit: Limit = 100,
        offset: Offset = 0,
    ) -> AreaPage:
        """A page of functional areas (by id) with summary, room, floor and object count."""
        served = served_map(request, map)
        with served.lock:
            return served.require().areas(
                floor=floor, room=room, label=label, limit=limit, offset=offset
            )

    @app.get("/v1/maps/{map}/hierarchy")
    def hierarchy(request: Request, map: str) -> Hierarchy:
        """Floors → rooms → areas → objects, ids and labels only."""
        served = served_map(request, map)
        with served.lock:
            return served.require().hierarchy()

    @app.get("/v1/maps/{map}/scene3d")
    def scene3d(
        request: Request,
        map: str,
        floor: FloorQ = None,
        near: Annotated[
            bool, Query(description="Also send the 'near' relations (many on a big map).")
        ] = False,
    ) -> Scene3D:
        """Floors, room footprints, object boxes, relations and room connections for the
        viewer's 3D view (one floor, or all floors)."""
        served = served_map(request, map)
        with served.lock:
            return served.require().scene3d(floor_id=floor, near=near)

    @app.get(
        "/v1/maps/{map}/bev.png",
        response_class=Response,
        responses={200: {"content": {"image/png": {"schema": BINARY}}}},
    )
    def bev(
        request: Request,
        map: str,
        floor: Annotated[str, Query(description="Floor id, e.g. floor:0.")],
        source: Annotated[
            Literal["graph", "stored"],
            Query(
                description="'graph': drawn from room masks and objects, with X-BEV-* "
                "transform headers; 'stored': the picture `map build` wrote (no transform)."
            ),
        ] = "graph",
    ) -> Response:
        """The bird's-eye view of one floor as PNG."""
        served = served_map(request, map)
        with served.lock:
            png, tf = served.require().bev_png(floor, stored=source == "stored")
        headers = tf.headers() if tf is not None else None
        return Response(png, media_type="image/png", headers=headers)

    @app.get(
        "/v1/maps/{map}/keyframes/{keyframe_id}.jpg",
        response_class=Response,
        responses={200: {"content": {"image/jpeg": {"schema": BINARY}}}},
    )
    def keyframe(request: Request, map: str, keyframe_id: str) -> Response:
        """One keyframe's JPEG (ids like ``kf:session:1:25``, URL-encoded or not)."""
        served = served_map(request, map)
        with served.lock:
            jpeg = served.require().keyframe_jpeg(keyframe_id)
        return Response(jpeg, media_type="image/jpeg")

    @app.get(
        "/v1/maps/{map}/nodes/{node_id}/view.jpg",
        response_class=Response,
        responses={200: {"content": {"image/jpeg": {"schema": BINARY}}}},
    )
    def best_view(request: Request, map: str, node_id: str) -> Response:
        """The best-view keyframe of an object or room; its id in ``X-Keyframe-Id``."""
        served = served_map(request, map)
        with served.lock:
            service = served.require()
            kf_id = service.best_view(node_id)
            jpeg = service.keyframe_jpeg(kf_id)
        return Response(jpeg, media_type="image/jpeg", headers={"X-Keyframe-Id": kf_id})

    app.mount("/static", StaticFiles(directory=STATIC), name="static")
