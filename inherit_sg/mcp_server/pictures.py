"""Pictures of a map as MCP resources and tools: the bird's-eye view of each floor (PNG,
drawn from the graph) and the best view of an object or room (the keyframe's JPEG).

Resources: ``inherit-sg://{map}/bev/{floor}.png`` and ``inherit-sg://{map}/nodes/{node}/view.jpg``
(templates; the BEV of every floor is also listed). The same pictures come from the
``floor_plan`` and ``best_view`` tools as image content, for clients that do not read
resources.
"""

from __future__ import annotations

from typing import Annotated, Any

from mcp.server.mcpserver import Image, MCPServer
from mcp_types import Resource
from pydantic import Field

from inherit_sg.errors import InheritSGError
from inherit_sg.mcp_server.common import MapArg, ServedMaps, reported, resource_errors
from inherit_sg.mcp_server.tools import READ_ONLY

SCHEME = "inherit-sg"
BEV_URI = SCHEME + "://{map}/bev/{floor}.png"
VIEW_URI = SCHEME + "://{map}/nodes/{node}/view.jpg"


def bev_uri(map_name: str, floor_id: str) -> str:
    """The resource URI of one floor's bird's-eye view."""
    return BEV_URI.format(map=map_name, floor=floor_id)


class Pictures:
    """BEV and best-view pictures of the served maps (see :meth:`install`)."""

    def __init__(self, maps: ServedMaps) -> None:
        self.maps = maps

    def install(self, server: MCPServer[Any]) -> None:
        """Register the resource templates and the picture tools on ``server``."""
        server.resource(
            BEV_URI,
            name="floor BEV",
            description="Bird's-eye view of one floor (PNG): room footprints and object dots.",
            mime_type="image/png",
        )(self.bev_resource)
        server.resource(
            VIEW_URI,
            name="best view",
            description="The keyframe that shows an object or a room best (JPEG).",
            mime_type="image/jpeg",
        )(self.view_resource)
        server.add_tool(self.floor_plan, annotations=READ_ONLY)
        server.add_tool(self.best_view, annotations=READ_ONLY)

    # ------------------------------------------------------------------ pictures
    def _bev(self, map_name: str | None, floor: str) -> tuple[bytes, str]:
        served = self.maps.get(map_name)
        with served.lock:
            png, tf = served.require().bev_png(floor)
        if tf is None:
            return png, f"{floor} of map {served.name}"
        return png, (
            f"{floor} of map {served.name}: {tf.width}x{tf.height} px, {tf.cell:g} m per "
            f"pixel; the top-left corner of the image is world x = {tf.origin_x:g}, "
            f"y = {tf.origin_y:g}; columns grow with +x, rows with -y"
        )

    def _view(self, map_name: str | None, node_id: str) -> tuple[bytes, str]:
        served = self.maps.get(map_name)
        with served.lock:
            service = served.require()
            keyframe = service.best_view(node_id)
            jpeg = service.keyframe_jpeg(keyframe)
        return jpeg, f"best view of {node_id} in map {served.name}: keyframe {keyframe}"

    def bev_resource(self, map: str, floor: str) -> bytes:
        """PNG bytes of one floor's bird's-eye view."""
        with resource_errors():
            return self._bev(map, floor)[0]

    def view_resource(self, map: str, node: str) -> bytes:
        """JPEG bytes of a node's best view."""
        with resource_errors():
            return self._view(map, node)[0]

    def floor_plan(
        self,
        floor: Annotated[str, Field(description="Floor id, e.g. 'floor:0' (see list_floors).")],
        map: MapArg = None,
    ) -> list[Image | str]:
        """The bird's-eye view of one floor as a PNG image (room footprints coloured,
        objects as dots), with the pixel ↔ world transform."""
        with reported():
            png, text = self._bev(map, floor)
        return [text, Image(data=png, format="png")]

    def best_view(
        self,
        node_id: Annotated[str, Field(description="An object or room id.")],
        map: MapArg = None,
    ) -> list[Image | str]:
        """The camera keyframe that shows an object or a room best, as a JPEG image."""
        with reported():
            jpeg, text = self._view(map, node_id)
        return [text, Image(data=jpeg, format="jpeg")]

    # ------------------------------------------------------------------ listing
    def floor_resources(self) -> list[Resource]:
        """A listed resource for the BEV of every floor of every open map."""
        registry = self.maps.registry
        out: list[Resource] = []
        for name, served in ({} if registry is None else registry.maps).items():
            try:
                with served.lock:
                    floors = served.require().floors(limit=1000).floors
            except InheritSGError:
                continue  # a map that did not open lists nothing
            out += [
                Resource(
                    uri=bev_uri(name, f.id),
                    name=f"{name} {f.label or f.id} BEV",
                    description=f"Bird's-eye view of {f.id} of map {name}.",
                    mime_type="image/png",
                )
                for f in floors
            ]
        return out
