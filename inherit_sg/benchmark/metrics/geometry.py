"""Geometric-stream quality against a ground-truth :class:`Scene`.

Rooms (as in HOV-SG / Hydra evaluations): predicted and true 2D room masks are compared
on the predicted floor's BEV grid; a predicted room matches a true room when their IoU
is at least 0.5 (one-to-one, highest IoU first). Precision = matched / predicted rooms,
recall = matched / true rooms that were observed.

True masks are the scene's room polygons rasterised on that grid (cell centres inside
the polygon). ``mode="observed"`` (the default) intersects them with the cells the
camera observed (free or occupied): a map cannot know space it never saw, and using
observed cells of any kind (not only free ones) keeps walls and furniture in the true
mask, so a method cannot shrink the target to its own free-space estimate.
``mode="full"`` uses the whole polygon. True rooms with less than ``min_seen_m2`` of
observed area are left out of recall (reported as ``unseen``).

Floors: the number of predicted floors against the true number, and the share of frames
assigned to the right floor. A predicted floor corresponds to the true floor with the
nearest surface height. Frames on stairs are not scored: a frame is scored when its
camera height above the floor below it is within 0.3 m of the walk's typical eye height.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from inherit_sg.ingest.synthetic.scene import FloorGT, RoomGT, Scene
from inherit_sg.model import RoomMask

if TYPE_CHECKING:
    from inherit_sg.geometry.stream import GeometricStream

IOU_THRESHOLD = 0.5


def rasterize_polygon(
    polygon: Sequence[Sequence[float]],
    origin: tuple[float, float],
    resolution: float,
    shape: tuple[int, int],
) -> np.ndarray:
    """Cells whose centres lie inside ``polygon`` (even-odd rule)."""
    h, w = shape
    xs = origin[0] + (np.arange(w) + 0.5) * resolution
    ys = origin[1] + (np.arange(h) + 0.5) * resolution
    px, py = np.meshgrid(xs, ys)
    inside = np.zeros(shape, dtype=bool)
    pts = [(float(p[0]), float(p[1])) for p in polygon]
    for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1], strict=True):
        if y0 == y1:
            continue
        crosses = (y0 > py) != (y1 > py)
        x_at = x0 + (py - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (px < x_at)
    return inside


def paste(mask: RoomMask, origin: tuple[float, float], shape: tuple[int, int]) -> np.ndarray:
    """A room mask placed on a grid with the same resolution and the given origin."""
    out = np.zeros(shape, dtype=bool)
    c0 = round((mask.origin_x - origin[0]) / mask.resolution)
    r0 = round((mask.origin_y - origin[1]) / mask.resolution)
    h, w = mask.cells.shape
    rs, cs = max(0, r0), max(0, c0)
    re, ce = min(shape[0], r0 + h), min(shape[1], c0 + w)
    if rs < re and cs < ce:
        out[rs:re, cs:ce] = mask.cells[rs - r0 : re - r0, cs - c0 : ce - c0]
    return out


@dataclass
class RoomMetrics:
    """Room segmentation quality at one IoU threshold."""

    precision: float
    recall: float
    predicted: int
    true: int
    matched: int
    unseen: int = 0
    mean_iou: float = 0.0
    matches: list[tuple[str, str, float]] = field(default_factory=list)  # pred, true, IoU

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return asdict(self)


def match_masks(
    pred: dict[str, np.ndarray], true: dict[str, np.ndarray], threshold: float = IOU_THRESHOLD
) -> list[tuple[str, str, float]]:
    """One-to-one matches ``(pred, true, IoU)`` with IoU ≥ ``threshold``, best first."""
    pairs = []
    for pk, pm in pred.items():
        for tk, tm in true.items():
            inter = int(np.logical_and(pm, tm).sum())
            if inter == 0:
                continue
            iou = inter / float(np.logical_or(pm, tm).sum())
            if iou >= threshold:
                pairs.append((iou, pk, tk))
    used_p: set[str] = set()
    used_t: set[str] = set()
    out = []
    for iou, pk, tk in sorted(pairs, key=lambda t: (-t[0], t[1], t[2])):
        if pk in used_p or tk in used_t:
            continue
        used_p.add(pk)
        used_t.add(tk)
        out.append((pk, tk, iou))
    return out


def room_metrics(
    pred: dict[str, np.ndarray],
    true_rooms: Sequence[RoomGT],
    origin: tuple[float, float],
    resolution: float,
    observed: np.ndarray,
    mode: str = "observed",
    min_seen_m2: float = 1.0,
    threshold: float = IOU_THRESHOLD,
) -> RoomMetrics:
    """Metrics of predicted masks (on the grid of ``observed``) against true rooms."""
    if mode not in ("observed", "full"):
        raise ValueError(f"unknown room evaluation mode {mode!r} (observed|full)")
    shape = observed.shape
    true: dict[str, np.ndarray] = {}
    unseen = 0
    for room in true_rooms:
        poly = rasterize_polygon(room.polygon, origin, resolution, shape)
        seen = poly & observed
        if seen.sum() * resolution**2 < min_seen_m2:
            unseen += 1
            continue
        true[room.id] = seen if mode == "observed" else poly
    matches = match_masks(pred, true, threshold)
    n = len(matches)
    return RoomMetrics(
        precision=n / len(pred) if pred else 0.0,
        recall=n / len(true) if true else 0.0,
        predicted=len(pred),
        true=len(true),
        matched=n,
        unseen=unseen,
        mean_iou=float(np.mean([m[2] for m in matches])) if matches else 0.0,
        matches=matches,
    )


def combine(parts: Sequence[RoomMetrics]) -> RoomMetrics:
    """Pool per-floor metrics into one."""
    pred = sum(p.predicted for p in parts)
    true = sum(p.true for p in parts)
    matched = sum(p.matched for p in parts)
    matches = [m for p in parts for m in p.matches]
    return RoomMetrics(
        precision=matched / pred if pred else 0.0,
        recall=matched / true if true else 0.0,
        predicted=pred,
        true=true,
        matched=matched,
        unseen=sum(p.unseen for p in parts),
        mean_iou=float(np.mean([m[2] for m in matches])) if matches else 0.0,
        matches=matches,
    )


@dataclass
class FloorMetrics:
    """Floor count and per-frame floor assignment."""

    predicted_floors: int
    true_floors: int
    count_exact: bool
    frame_accuracy: float
    scored_frames: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return asdict(self)


def true_frame_floors(camera_z: Sequence[float], floors: Sequence[FloorGT]) -> list[int | None]:
    """True floor index per frame, None for frames between floors (stairs)."""
    zs = np.array(sorted(f.z for f in floors))
    cam = np.asarray(camera_z, dtype=np.float64)
    below = np.clip(np.searchsorted(zs, cam, side="right") - 1, 0, len(zs) - 1)
    above_floor = cam - zs[below]
    eye = float(np.median(above_floor))
    ok = np.abs(above_floor - eye) <= 0.3
    return [int(b) if k else None for b, k in zip(below, ok, strict=True)]


def floor_metrics(
    frame_floor_z: Sequence[float | None],
    camera_z: Sequence[float],
    predicted_floors: int,
    floors: Sequence[FloorGT],
) -> FloorMetrics:
    """``frame_floor_z``: surface height of the predicted floor of every frame."""
    truth = true_frame_floors(camera_z, floors)
    zs = np.array(sorted(f.z for f in floors))
    hits = scored = 0
    for pz, t in zip(frame_floor_z, truth, strict=True):
        if t is None:
            continue
        scored += 1
        if pz is not None and int(np.argmin(np.abs(zs - pz))) == t:
            hits += 1
    return FloorMetrics(
        predicted_floors=predicted_floors,
        true_floors=len(floors),
        count_exact=predicted_floors == len(floors),
        frame_accuracy=hits / scored if scored else 0.0,
        scored_frames=scored,
    )


def nearest_floor(floors: Sequence[FloorGT], z: float) -> FloorGT:
    """The true floor whose surface is nearest to height ``z``."""
    return min(floors, key=lambda f: abs(f.z - z))


def scene_rooms_on(scene: Scene, floor_index: int) -> list[RoomGT]:
    """True rooms of one storey."""
    return [r for r in scene.rooms if r.floor == floor_index]


@dataclass
class GeometryReport:
    """Room and floor quality of one run."""

    rooms: RoomMetrics
    floors: FloorMetrics

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form (without the per-room match list)."""
        rooms = self.rooms.to_dict()
        rooms.pop("matches")
        return {"rooms": rooms, "floors": self.floors.to_dict()}


def evaluate_stream(
    stream: GeometricStream,
    scene: Scene,
    camera_z: Sequence[float],
    refined: bool = True,
    mode: str = "observed",
) -> GeometryReport:
    """Evaluate a geometric stream that consumed a whole walk of ``scene``.

    ``camera_z`` is the camera height of every frame the stream processed.
    """
    parts = []
    covered: set[int] = set()
    for fid, fmap in stream.maps.items():
        if fmap.grid.empty:
            continue
        true_floor = nearest_floor(scene.floors, stream.tracker.floors[fid].floor_z)
        covered.add(true_floor.index)
        g = fmap.grid
        origin = (g.origin_x, g.origin_y)
        pred = {str(k): paste(m, origin, g.shape) for k, m in fmap.masks(refined).items()}
        parts.append(
            room_metrics(
                pred,
                scene_rooms_on(scene, true_floor.index),
                origin,
                g.resolution,
                g.known_mask(),
                mode,
            )
        )
    for f in scene.floors:
        missing = len(scene_rooms_on(scene, f.index))
        if f.index not in covered and missing:
            parts.append(RoomMetrics(0.0, 0.0, 0, missing, 0))
    frame_z = [stream.tracker.floors[fid].floor_z for fid in stream.stats.frame_floors]
    floors = floor_metrics(frame_z, camera_z, len(stream.tracker.floors), scene.floors)
    return GeometryReport(rooms=combine(parts), floors=floors)
