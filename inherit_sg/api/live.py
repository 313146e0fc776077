"""Live mapping over HTTP: sessions that feed posted frames to the dual-stream mapper.

``POST /v1/maps/{map}/sessions`` starts one (one per map at a time; the map is served
writable while it runs and read-only again after it finishes), ``POST …/frames`` posts
one multipart RGB-D frame, ``GET …/sessions/{sid}`` reports its counters and
``POST …/finish`` ends it with the mapping summary. The work is done by
:class:`~inherit_sg.mapping.live.LiveSession`; these routes only decode and route.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Body, File, Form, Request, UploadFile

from inherit_sg.api.live_frames import (
    decode_depth,
    decode_instances,
    decode_rgb,
    parse_instance_labels,
    parse_intrinsics,
    parse_pose,
)
from inherit_sg.api.live_models import FrameAccepted, SessionCreated, SessionRequest
from inherit_sg.api.state import served_map
from inherit_sg.errors import FrameError
from inherit_sg.reads.models import LiveStatus, MappingSummary

router = APIRouter()


@router.post("/v1/maps/{map}/sessions", status_code=201)
def start_session(
    request: Request, map: str, body: Annotated[SessionRequest | None, Body()] = None
) -> SessionCreated:
    """Start a live mapping session (409 while another one runs on this map)."""
    req = body or SessionRequest()
    live = served_map(request, map).start_live(
        req.name, frame_queue=req.frame_queue, flush_every=req.flush_every
    )
    return SessionCreated(session_id=live.id, name=live.name, map=map)


@router.post("/v1/maps/{map}/sessions/{sid}/frames", status_code=202)
def post_frame(
    request: Request,
    map: str,
    sid: str,
    rgb: Annotated[UploadFile, File(description="Colour image, PNG or JPEG.")],
    depth: Annotated[UploadFile, File(description="Depth, uint16 PNG in depth_scale units.")],
    pose: Annotated[str, Form(description="T_world_camera: 16 numbers row-major or 4x4 JSON.")],
    intrinsics: Annotated[
        str | None, Form(description="intrinsics.json object; required on the first frame.")
    ] = None,
    timestamp: Annotated[float | None, Form(description="Seconds since session start.")] = None,
    instances: Annotated[
        UploadFile | None, File(description="Per-pixel instance ids, uint16 PNG.")
    ] = None,
    instance_labels: Annotated[
        str | None, Form(description='JSON {"<instance id>": "label"} for this frame.')
    ] = None,
) -> FrameAccepted:
    """Queue one RGB-D frame (202); 400 for a malformed frame, 429 + Retry-After when
    the intake is full, 503 + Retry-After while the session finishes."""
    live = served_map(request, map).active(sid)
    if instance_labels is not None and instances is None:
        raise FrameError("instance_labels: given without an instances image")
    receipt = live.submit(
        decode_rgb(rgb.file.read()),
        decode_depth(depth.file.read()),
        parse_pose(pose),
        intrinsics=parse_intrinsics(intrinsics) if intrinsics is not None else None,
        timestamp=timestamp,
        instances=decode_instances(instances.file.read()) if instances is not None else None,
        instance_labels=parse_instance_labels(instance_labels) if instance_labels else None,
    )
    return FrameAccepted(**receipt.to_dict())


@router.get("/v1/maps/{map}/sessions/{sid}")
def session_status(request: Request, map: str, sid: str) -> LiveStatus:
    """Counters of a running or finished live session."""
    return LiveStatus.model_validate(served_map(request, map).live_status(sid))


@router.post("/v1/maps/{map}/sessions/{sid}/finish")
def finish_session(request: Request, map: str, sid: str) -> MappingSummary:
    """Finish the session: final update, everything persisted, BEV pictures written under
    ``<map>/bev/``; answers the mapping summary."""
    return MappingSummary.model_validate(served_map(request, map).finish_live(sid))
