"""Log a mapping session or a query to Rerun (the ``rerun-sdk`` package, optional extra
``rerun``): camera poses and images while mapping, the scene graph after every global
update (room outlines, object boxes with labels, relations, doors), the BEV pictures at
the end, and a query's candidates, answer and trace.

Entity paths (world is z-up, metres)::

    world/camera                 Transform3D + Pinhole (OpenCV axes) per frame
    world/camera/image/rgb       JPEG-compressed RGB, every ``image_every``-th frame
    world/camera/image/depth     depth in metres, with the RGB
    world/rooms                  room outlines on their floor (LineStrips3D, labelled)
    world/objects                object boxes coloured by room (Boxes3D, labelled)
    world/relations              object relations (LineStrips3D, labelled by predicate)
    world/doors                  room connections through their doors
    world/query/candidates       a query's other candidates (orange boxes)
    world/query/answer           its answer (a red box)
    query/trace                  the request and its trace (Markdown)
    bev/floor_<level>            the BEV picture of each floor

Timelines: ``frame`` (frame index) and ``capture_time`` (seconds of the recording).
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from inherit_sg.errors import InputError, ModelUnavailableError
from inherit_sg.model import Frame, SceneGraph

if TYPE_CHECKING:
    from inherit_sg.reads.models import Scene3D, Scene3DObject

APPLICATION_ID = "inherit-sg"
ANSWER_RGB = (214, 40, 40)
CANDIDATE_RGB = (240, 160, 32)
RELATION_RGB = (85, 96, 112)
DOOR_RGB = (30, 125, 79)
UNASSIGNED_RGB = (154, 165, 177)
INSTALL = "pip install 'inherit-sg[rerun]'  (or: pip install rerun-sdk)"


def _rerun() -> Any:
    try:
        import rerun
    except ImportError as exc:
        raise ModelUnavailableError(f"Rerun logging needs rerun-sdk: {INSTALL} ({exc})") from None
    return rerun


def room_colour(room_id: str | None) -> tuple[int, int, int]:
    """A stable pastel colour per room id (the same in every recording)."""
    if not room_id:
        return UNASSIGNED_RGB
    h = hashlib.blake2b(room_id.encode(), digest_size=3).digest()
    return (96 + h[0] % 144, 96 + h[1] % 144, 96 + h[2] % 144)


def _box_arrays(boxes: Sequence[Scene3DObject]) -> tuple[np.ndarray, np.ndarray]:
    """Centres and half sizes (at least 1 cm) of object boxes, as (n, 3) arrays."""
    lo = np.array([o.bbox_min for o in boxes], dtype=np.float32).reshape(-1, 3)
    hi = np.array([o.bbox_max for o in boxes], dtype=np.float32).reshape(-1, 3)
    return (lo + hi) / 2, np.maximum((hi - lo) / 2, 0.01)


def _is_url(target: str) -> bool:
    return target.startswith(("rerun://", "rerun+http://", "rerun+https://", "http://", "https://"))


class RerunLog:
    """One Rerun recording: saved to an ``.rrd`` file or streamed to a running viewer."""

    def __init__(self, target: str, *, image_every: int = 5, name: str | None = None) -> None:
        """``target``: a path ending in ``.rrd``, or a viewer's gRPC URL (e.g.
        ``rerun+http://127.0.0.1:9876/proxy``, what ``rerun`` prints when started)."""
        if image_every < 1:
            raise InputError(f"image_every must be at least 1, got {image_every}")
        rr = _rerun()
        self._rr = rr
        self.image_every = image_every
        self.rec = rr.RecordingStream(APPLICATION_ID)
        if name:
            self.rec.send_recording_name(name)
        if _is_url(target):
            self.rec.connect_grpc(target)
        else:
            path = Path(target)
            if path.suffix != ".rrd":
                raise InputError(
                    f"Rerun target {target!r}: give a .rrd file or a rerun+http:// URL"
                )
            path.parent.mkdir(parents=True, exist_ok=True)
            self.rec.save(path)
        self.target = target
        self.rec.log("world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)

    # ---------------------------------------------------------------- mapping
    def frame(self, frame: Frame) -> None:
        """The camera's pose and intrinsics; its images every ``image_every`` frames."""
        rr, rec = self._rr, self.rec
        rec.set_time("frame", sequence=frame.index)
        rec.set_time("capture_time", duration=float(frame.timestamp))
        m = np.asarray(frame.pose.matrix16, dtype=np.float64).reshape(4, 4)
        rec.log("world/camera", rr.Transform3D(translation=m[:3, 3], mat3x3=m[:3, :3]))
        k = frame.intrinsics
        rec.log(
            "world/camera/image",
            rr.Pinhole(
                focal_length=[k.fx, k.fy],
                principal_point=[k.cx, k.cy],
                resolution=[k.width, k.height],
                camera_xyz=rr.ViewCoordinates.RDF,
                image_plane_distance=0.4,
            ),
        )
        if frame.index % self.image_every == 0:
            rec.log("world/camera/image/rgb", rr.Image(frame.rgb).compress(jpeg_quality=75))
            rec.log("world/camera/image/depth", rr.DepthImage(frame.depth, meter=1.0))

    def graph(self, graph: SceneGraph) -> None:
        """The scene graph as it stands (called after each global update)."""
        from inherit_sg.reads.scene3d import scene_from_graph

        self.scene(scene_from_graph(graph))

    def bev(self, pictures: list[Path]) -> None:
        """The BEV pictures ``map build`` wrote (``floor_<level>.png``), as static images."""
        for path in pictures:
            self.rec.log(
                f"bev/{path.stem}",
                self._rr.EncodedImage(contents=path.read_bytes(), media_type="image/png"),
                static=True,
            )

    # ---------------------------------------------------------------- the graph
    def scene(self, scene: Scene3D) -> None:
        """Room outlines, object boxes, relations and doors of ``scene``."""
        rr, rec = self._rr, self.rec
        floor_z = {f.id: f.z_min or 0.0 for f in scene.floors}
        strips, labels, colours = [], [], []
        for room in scene.rooms:
            z = floor_z.get(room.floor_id or "", 0.0) + 0.02
            for outline in room.outlines:
                ring = [[x, y, z] for x, y in [*outline, outline[0]]]
                strips.append(ring)
                labels.append(room.label)
                colours.append(room_colour(room.id))
        rec.log("world/rooms", rr.LineStrips3D(strips, labels=labels, colors=colours))
        boxes = scene.objects
        centres, half_sizes = _box_arrays(boxes)
        rec.log(
            "world/objects",
            rr.Boxes3D(
                centers=centres,
                half_sizes=half_sizes,
                labels=[o.label for o in boxes],
                colors=[room_colour(o.room_id) for o in boxes],
                show_labels=False,
            ),
        )
        centre = {o.id: c.tolist() for o, c in zip(boxes, centres, strict=True)}
        rels = [r for r in scene.relations if r.source in centre and r.target in centre]
        rec.log(
            "world/relations",
            rr.LineStrips3D(
                [[centre[r.source], centre[r.target]] for r in rels],
                labels=[r.predicate for r in rels],
                colors=[RELATION_RGB] * len(rels),
                show_labels=False,
            ),
        )
        rooms = {r.id: r for r in scene.rooms}
        doors = []
        for c in scene.connections:
            a, b = rooms.get(c.source), rooms.get(c.target)
            if a is None or b is None or a.position is None or b.position is None:
                continue
            z = floor_z.get(a.floor_id or "", 0.0) + 0.05
            mid = [[c.door[0], c.door[1], z]] if c.door else []
            doors.append(
                [[a.position[0], a.position[1], z], *mid, [b.position[0], b.position[1], z]]
            )
        rec.log("world/doors", rr.LineStrips3D(doors, colors=[DOOR_RGB] * len(doors)))

    # ---------------------------------------------------------------- queries
    def query(self, text: str, result: dict[str, Any], scene: Scene3D) -> None:
        """A query on a map: the map's scene, the candidates, the answer and the trace."""
        rr, rec = self._rr, self.rec
        rec.set_time("query", sequence=0)
        self.scene(scene)
        boxes = {o.id: o for o in scene.objects}
        answer = (result.get("answer") or {}).get("id")
        others = [c["id"] for c in result.get("candidates", []) if c["id"] != answer]
        for path, ids, colour in (
            ("world/query/candidates", [i for i in others if i in boxes], CANDIDATE_RGB),
            ("world/query/answer", [answer] if answer in boxes else [], ANSWER_RGB),
        ):
            centres, half_sizes = _box_arrays([boxes[i] for i in ids])
            rec.log(
                path,
                rr.Boxes3D(
                    centers=centres,
                    half_sizes=half_sizes * 1.05,
                    labels=[f"{boxes[i].label} ({i})" for i in ids],
                    colors=[colour] * len(ids),
                    radii=0.02,
                ),
            )
        lines = [f"**{text}**", "", *[f"- {step}" for step in result.get("trace", [])]]
        rec.log("query/trace", rr.TextDocument("\n".join(lines), media_type=rr.MediaType.MARKDOWN))

    def close(self) -> None:
        """Flush everything to the file or the viewer."""
        self.rec.flush()
        if hasattr(self.rec, "disconnect"):
            self.rec.disconnect()
