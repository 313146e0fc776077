"""The read tools: natural-language requests, read-only Cypher, listings, any node's
detail and the graph schema, each one call of :class:`~inherit_sg.facade.MapService` (or
a read over it) on a served map, answered as the JSON REST and ``--json`` give."""

from __future__ import annotations

from typing import Annotated, Any

from mcp.server.mcpserver import Context, MCPServer
from mcp.server.mcpserver.exceptions import ToolError
from mcp_types import ToolAnnotations
from pydantic import Field

from inherit_sg.api.models import (
    MAX_CYPHER_ROWS,
    MAX_CYPHER_TIMEOUT_S,
    CypherResponse,
    ViewerIn,
)
from inherit_sg.api.views import MapEntry, MapList
from inherit_sg.json_values import jsonable
from inherit_sg.mcp_server.access import Access
from inherit_sg.mcp_server.common import MapArg, ServedMaps, reported
from inherit_sg.reads.models import FloorPage, GraphSchema, NodeDetail, ObjectPage, RoomPage
from inherit_sg.reads.nodes import describe_node
from inherit_sg.reads.schema_info import graph_schema

Limit = Annotated[int, Field(ge=1, le=1000, description="Rows per page.")]
Offset = Annotated[int, Field(ge=0, description="Rows to skip (paging).")]
FloorArg = Annotated[str | None, Field(description="Only on this floor id, e.g. 'floor:0'.")]
RoomArg = Annotated[str | None, Field(description="Only in this room id.")]
LabelArg = Annotated[str | None, Field(description="Only with this label (any case).")]
READ_ONLY = ToolAnnotations(read_only_hint=True, open_world_hint=False)


class ReadTools:
    """The read tools of one MCP server (see :meth:`install`)."""

    def __init__(self, maps: ServedMaps, access: Access) -> None:
        self.maps = maps
        self.access = access

    def install(self, server: MCPServer[Any]) -> None:
        """Register the tools on ``server``."""
        for tool in (
            self.list_maps,
            self.find,
            self.cypher,
            self.list_floors,
            self.list_rooms,
            self.list_objects,
            self.describe_node,
            self.schema,
        ):
            server.add_tool(tool, annotations=READ_ONLY)

    def list_maps(self) -> MapList:
        """The maps this server serves, by name, with 'ok' or why a map did not open.
        Every other tool takes one of these names as its 'map' argument."""
        registry = self.maps.registry
        served = {} if registry is None else registry.maps
        return MapList(maps=[MapEntry(name=name, status=s.status) for name, s in served.items()])

    def find(
        self,
        request: Annotated[
            str,
            Field(
                description="What to find, in plain words: 'the mug on the table next to "
                "the window', 'something to sit on near the TV', 'the other one'."
            ),
        ],
        map: MapArg = None,
        verify: Annotated[
            bool | None, Field(description="Verify on keyframes (config default when null).")
        ] = None,
        top_k: Annotated[
            int | None, Field(ge=1, le=100, description="Candidates to return.")
        ] = None,
        viewer: Annotated[
            ViewerIn | None,
            Field(
                description="The robot's pose {position: [x, y, z], yaw_deg}: 'left', "
                "'right', ordinals and 'closest to you' are seen from it."
            ),
        ] = None,
        conversation_id: Annotated[
            str | None,
            Field(
                max_length=128,
                description="Keep a history under this id so follow-ups ('the other "
                "one', 'not that one') resolve against earlier requests.",
            ),
        ] = None,
    ) -> dict[str, Any]:
        """Answer a natural-language request about the map: the best matching object
        (id, label, position [x, y, z] in metres, room, floor, score), the ranked
        candidates with per-constraint scores, the parsed constraints and a readable trace
        of why each candidate was kept or dropped; the same JSON as `inherit-sg query
        --json` and REST."""
        with reported():
            served = self.maps.get(map)
            registry = self.maps.registry
            conv = (
                registry.conversation(served.name, conversation_id)
                if registry is not None and conversation_id is not None
                else None
            )
            with served.lock:
                result = served.require().query(
                    request,
                    conversation=conv,
                    verify=verify,
                    top_k=top_k,
                    viewer=viewer.pose() if viewer is not None else None,
                )
            out: dict[str, Any] = jsonable(result.to_dict())
            if conversation_id is not None:
                out["conversation_id"] = conversation_id
            return out

    def cypher(
        self,
        ctx: Context,
        query: Annotated[
            str,
            Field(
                min_length=1,
                description="One read-only Cypher statement over the public tables (the "
                "schema tool lists them, with examples).",
            ),
        ],
        map: MapArg = None,
        params: Annotated[
            dict[str, Any] | None, Field(description="Query parameters ($name → value).")
        ] = None,
        max_rows: Annotated[
            int, Field(ge=1, le=MAX_CYPHER_ROWS, description="Stop after this many rows.")
        ] = 1000,
        timeout_s: Annotated[
            float | None,
            Field(
                gt=0,
                le=MAX_CYPHER_TIMEOUT_S,
                description="Time limit in seconds (default: service.cypher_timeout_s).",
            ),
        ] = None,
    ) -> CypherResponse:
        """Run a read-only Cypher statement on the map's graph and return its columns
        and rows ('truncated' when max_rows cut them). Statements that write are refused;
        each one runs in a worker process with a time limit, so even one that crashes the
        database engine only fails itself. Call the schema tool first for the tables."""
        refused = self.access.refusal("cypher", ctx.headers)
        if refused is not None:
            raise ToolError(refused)
        with reported():
            served = self.maps.get(map)
            with served.lock:
                service = served.require()
            # not under the map's lock: the statement runs in the map's Cypher worker
            result = service.cypher(
                query,
                params,
                max_rows=max_rows,
                timeout_s=timeout_s or service.config.service.cypher_timeout_s,
            )
            return CypherResponse(
                columns=result.columns, rows=jsonable(result.rows), truncated=result.truncated
            )

    def list_floors(
        self, map: MapArg = None, label: LabelArg = None, limit: Limit = 100, offset: Offset = 0
    ) -> FloorPage:
        """A page of the map's floors (by id) with their level and room and object counts."""
        with reported(), self.maps.service(map) as svc:
            return svc.floors(label=label, limit=limit, offset=offset)

    def list_rooms(
        self,
        map: MapArg = None,
        floor: FloorArg = None,
        label: LabelArg = None,
        limit: Limit = 100,
        offset: Offset = 0,
    ) -> RoomPage:
        """A page of rooms (by id), optionally on one floor or with one label, each with
        its summary, position, inferred room types, best view and child counts."""
        with reported(), self.maps.service(map) as svc:
            return svc.rooms(floor=floor, label=label, limit=limit, offset=offset)

    def list_objects(
        self,
        map: MapArg = None,
        floor: FloorArg = None,
        room: RoomArg = None,
        label: LabelArg = None,
        limit: Limit = 100,
        offset: Offset = 0,
    ) -> ObjectPage:
        """A page of objects (by id), optionally on one floor, in one room or with one
        label, each with its position, room, floor, description and status."""
        with reported(), self.maps.service(map) as svc:
            return svc.objects(floor=floor, room=room, label=label, limit=limit, offset=offset)

    def describe_node(
        self,
        node_id: Annotated[
            str, Field(description="A floor, room, area or object id, e.g. 'obj:12'.")
        ],
        map: MapArg = None,
    ) -> NodeDetail:
        """Everything about one node of the scene graph: its properties, its path up the
        hierarchy (area → room → floor), its children, its edges (an object's spatial
        relations, a room's doors, a floor's stairs), its best view and the keyframes an
        object was seen in."""
        with reported(), self.maps.service(map) as svc:
            return describe_node(svc, node_id)

    def schema(self, map: MapArg = None) -> GraphSchema:
        """The public graph tables of the map with their properties and types, what they
        hold, example Cypher statements and the rules statements follow: read this
        before writing Cypher."""
        with reported(), self.maps.service(map) as svc:
            return graph_schema(svc)
