"""The write tools: live mapping sessions, as REST's ``…/sessions`` routes offer them.

``start_session`` reopens a served map for writing and starts a session (one per map at a
time), ``add_frame`` feeds it one RGB-D frame read from image files on the server's disk,
``session_status`` reports its counters and ``finish_session`` ends it (final update,
everything persisted, the map served read-only again). Offered only when
``service.write_keys`` is set, and only to callers with a write key
(:mod:`~inherit_sg.mcp_server.access`). The work is done by
:class:`~inherit_sg.api.state.ServedMap` and :class:`~inherit_sg.mapping.live.LiveSession`,
the frame decoding by :mod:`inherit_sg.api.live_frames`.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

from mcp.server.mcpserver import Context, MCPServer
from mcp.server.mcpserver.exceptions import ToolError
from mcp_types import ToolAnnotations
from pydantic import Field

from inherit_sg.api.live_frames import (
    decode_depth,
    decode_instances,
    decode_rgb,
    parse_instance_labels,
    parse_intrinsics,
    parse_pose,
)
from inherit_sg.api.live_models import FrameAccepted, SessionCreated
from inherit_sg.errors import FrameError
from inherit_sg.mcp_server.access import Access
from inherit_sg.mcp_server.common import MapArg, ServedMaps, reported
from inherit_sg.mcp_server.tools import READ_ONLY
from inherit_sg.reads.models import LiveStatus, MappingSummary

ADDS = ToolAnnotations(read_only_hint=False, destructive_hint=False, open_world_hint=False)
SessionArg = Annotated[str, Field(description="The session id start_session gave.")]
FileArg = Annotated[str, Field(description="Path of an image file on the server's machine.")]


def read_file(path: str, field: str, max_bytes: int) -> bytes:
    """The bytes of the image file ``path``; FrameError naming ``field`` when it cannot
    be read or is larger than ``max_bytes``."""
    file = Path(path).expanduser()
    try:
        size = file.stat().st_size
        if not file.is_file():
            raise FrameError(f"{field}: {path} is not a file")
        if size > max_bytes:
            raise FrameError(f"{field}: {path} has {size} bytes, more than {max_bytes}")
        return file.read_bytes()
    except OSError as exc:
        raise FrameError(f"{field}: cannot read {path} ({exc.strerror})") from None


class LiveTools:
    """The live mapping tools of one MCP server (see :meth:`install`)."""

    def __init__(self, maps: ServedMaps, access: Access) -> None:
        self.maps = maps
        self.access = access
        self.max_bytes = int(maps.config.service.max_body_mb * 1024 * 1024)

    def install(self, server: MCPServer[Any]) -> None:
        """Register the tools on ``server``."""
        server.add_tool(self.start_session, annotations=ADDS)
        server.add_tool(self.add_frame, annotations=ADDS)
        server.add_tool(self.session_status, annotations=READ_ONLY)
        server.add_tool(self.finish_session, annotations=ADDS)

    def _check(self, tool: str, ctx: Context) -> None:
        refused = self.access.refusal(tool, ctx.headers)
        if refused is not None:
            raise ToolError(refused)

    def start_session(
        self,
        ctx: Context,
        map: MapArg = None,
        name: Annotated[
            str | None,
            Field(min_length=1, max_length=128, description="Session name (default live-N)."),
        ] = None,
        frame_queue: Annotated[
            int, Field(ge=1, le=1024, description="Frames waiting before add_frame refuses.")
        ] = 8,
        flush_every: Annotated[
            int, Field(ge=1, le=10_000, description="Persist (and show to find) every n keyframes.")
        ] = 20,
    ) -> SessionCreated:
        """Start a live mapping session that adds RGB-D frames to the map (one session per
        map at a time); requests keep being answered while it maps."""
        self._check("start_session", ctx)
        with reported():
            served = self.maps.get(map)
            live = served.start_live(name, frame_queue=frame_queue, flush_every=flush_every)
            return SessionCreated(session_id=live.id, name=live.name, map=served.name)

    def add_frame(
        self,
        ctx: Context,
        session_id: SessionArg,
        rgb_path: FileArg,
        depth_path: Annotated[
            str, Field(description="Path of the depth image: uint16 PNG in depth_scale units.")
        ],
        pose: Annotated[
            list[float],
            Field(
                min_length=16,
                max_length=16,
                description="T_world_camera, 16 numbers row-major (OpenCV camera axes, z up "
                "world, metres).",
            ),
        ],
        map: MapArg = None,
        intrinsics: Annotated[
            dict[str, float] | None,
            Field(
                description="{width, height, fx, fy, cx, cy, depth_scale}; required with the "
                "first frame of a session."
            ),
        ] = None,
        timestamp: Annotated[
            float | None, Field(description="Seconds since the session started.")
        ] = None,
        instances_path: Annotated[
            str | None, Field(description="Per-pixel instance ids, uint16 PNG (optional).")
        ] = None,
        instance_labels: Annotated[
            dict[str, str] | None,
            Field(description="{'<instance id>': 'label'} for the instances image."),
        ] = None,
    ) -> FrameAccepted:
        """Feed one RGB-D frame, read from image files on the server's machine, to a live
        session; answers the frame's index and the session's counters. When the session's
        queue is full it answers an error: wait a moment and send the frame again."""
        self._check("add_frame", ctx)
        with reported():
            live = self.maps.get(map).active(session_id)
            if instance_labels is not None and instances_path is None:
                raise FrameError("instance_labels: given without an instances image")
            instances = (
                decode_instances(read_file(instances_path, "instances", self.max_bytes))
                if instances_path is not None
                else None
            )
            receipt = live.submit(
                decode_rgb(read_file(rgb_path, "rgb", self.max_bytes)),
                decode_depth(read_file(depth_path, "depth", self.max_bytes)),
                parse_pose(json.dumps(pose)),
                intrinsics=parse_intrinsics(json.dumps(intrinsics)) if intrinsics else None,
                timestamp=timestamp,
                instances=instances,
                instance_labels=(
                    parse_instance_labels(json.dumps(instance_labels)) if instance_labels else None
                ),
            )
            return FrameAccepted(**receipt.to_dict())

    def session_status(self, session_id: SessionArg, map: MapArg = None) -> LiveStatus:
        """Counters of a running or finished live session: frames received and processed,
        keyframes, objects, warnings and, once finished, the mapping summary."""
        with reported():
            return LiveStatus.model_validate(self.maps.get(map).live_status(session_id))

    def finish_session(
        self, ctx: Context, session_id: SessionArg, map: MapArg = None
    ) -> MappingSummary:
        """Finish a live session: the last frames are mapped, rooms, areas and relations
        updated, everything persisted and the map served read-only again; answers the
        mapping summary (frames, keyframes, objects, rooms, floors, seconds)."""
        self._check("finish_session", ctx)
        with reported():
            return MappingSummary.model_validate(self.maps.get(map).finish_live(session_id))
