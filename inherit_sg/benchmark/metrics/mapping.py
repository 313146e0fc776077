"""Object-level mapping quality against a ground-truth :class:`Scene`.

* precision / recall: a predicted object node matches a true object within
  ``max_distance`` (0.5 m) with a compatible label (same label or a synonym of it);
  one-to-one, nearest first. Recall counts only true objects that were seen (``visible``)
  when that set is given: an object the camera never saw cannot be mapped.
* duplicate rate: predicted nodes that the one-to-one matching against every true
  object leaves over although a true object of a compatible label lies within
  ``max_distance`` (an object mapped twice), over all predicted nodes.
* room and floor assignment accuracy over matched pairs.
* relation precision: predicted RELATION edges between matched objects that hold in the
  ground truth (same predicate semantics, evaluated on true boxes).

Rooms: :func:`room_overlaps` measures how much of every true room each predicted room's
mask covers; :func:`room_correspondence` (most overlap) tells which true room a
predicted room stands for when objects' room assignment is scored; :func:`match_rooms`
gives room precision and recall against every true room by a mutual-majority rule
(see :class:`RoomMatching`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass, field

import numpy as np

from inherit_sg.ingest.synthetic.scene import ObjectGT, Scene
from inherit_sg.ingest.synthetic.truth_predicates import above, near, next_to, on
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS
from inherit_sg.model import Edge, ObjectNode, RoomMask, RoomNode

_SYNONYMS: dict[str, set[str]] = {}
for _kind in OBJECT_KINDS.values():
    names = {_kind.label, *_kind.synonyms}
    for _name in names:
        _SYNONYMS.setdefault(_name, set()).update(names)


def labels_compatible(predicted: str, true: str) -> bool:
    """Same label, or one is a listed synonym of the other."""
    p, t = predicted.lower().strip(), true.lower().strip()
    return p == t or t in _SYNONYMS.get(p, set()) or p in _SYNONYMS.get(t, set())


@dataclass
class MappingQuality:
    """Object-level metrics of one map against its ground truth."""

    predicted: int
    true_objects: int
    matched: int
    precision: float
    recall: float
    duplicate_rate: float
    room_accuracy: float | None = None
    floor_accuracy: float | None = None
    relation_precision: float | None = None
    relations_checked: int = 0
    pairs: dict[str, str] = field(default_factory=dict)  # predicted id -> true id

    def to_dict(self) -> dict[str, object]:
        """JSON-able form without the pair list."""
        out = asdict(self)
        out.pop("pairs")
        return out


def match_objects(
    predicted: Sequence[ObjectNode], truth: Sequence[ObjectGT], max_distance: float = 0.5
) -> dict[str, str]:
    """One-to-one matching, nearest compatible pairs first."""
    if not predicted or not truth:
        return {}
    p = np.array([o.position for o in predicted], dtype=float)
    t = np.array([o.centroid for o in truth], dtype=float)
    dist = np.linalg.norm(p[:, None, :] - t[None, :, :], axis=2)
    pairs = [
        (dist[i, j], i, j)
        for i, j in zip(*np.nonzero(dist <= max_distance), strict=True)
        if labels_compatible(predicted[i].label, truth[j].label)
    ]
    pairs.sort()
    used_p: set[int] = set()
    used_t: set[int] = set()
    out: dict[str, str] = {}
    for _, i, j in pairs:
        if i in used_p or j in used_t:
            continue
        used_p.add(i)
        used_t.add(j)
        out[predicted[i].id] = truth[j].id
    return out


def _duplicates(
    predicted: Sequence[ObjectNode], truth: Sequence[ObjectGT], max_distance: float
) -> int:
    """Predicted nodes that stand for an object another node already stands for: left
    over by the one-to-one matching against every true object, yet within
    ``max_distance`` of a true object of a compatible label. Three bottles side by side
    mapped as three nodes are no duplicates; one bottle mapped twice is one."""
    if not predicted or not truth:
        return 0
    matched = match_objects(predicted, truth, max_distance)
    t = np.array([o.centroid for o in truth], dtype=float)
    dup = 0
    for node in predicted:
        if node.id in matched:
            continue
        d = np.linalg.norm(t - np.asarray(node.position, dtype=float), axis=1)
        dup += any(
            labels_compatible(node.label, truth[j].label)
            for j in np.nonzero(d <= max_distance)[0].tolist()
        )
    return dup


_GT_PREDICATES: dict[str, Callable[[ObjectGT, ObjectGT], bool]] = {
    "on": on,
    "above": above,
    "next to": next_to,
    "near": near,
}


def evaluate_objects(
    predicted: Sequence[ObjectNode],
    scene: Scene,
    *,
    visible: Iterable[str] | None = None,
    room_map: dict[str, str] | None = None,
    floor_level: Callable[[ObjectNode], int | None] | None = None,
    relations: Iterable[Edge] = (),
    max_distance: float = 0.5,
) -> MappingQuality:
    """Compare a map's object nodes with the ground truth.

    ``room_map`` maps predicted room ids to true room ids (from the room-segmentation
    matching); ``floor_level`` gives a predicted node's floor index.
    """
    visible_ids = set(visible) if visible is not None else None
    truth = [o for o in scene.objects if visible_ids is None or o.id in visible_ids]
    pairs = match_objects(predicted, truth, max_distance)
    # predictions that match an unseen-but-real object are not false positives
    extra = {}
    if visible_ids is not None:
        unseen = [o for o in scene.objects if o.id not in visible_ids]
        rest = [p for p in predicted if p.id not in pairs]
        extra = match_objects(rest, unseen, max_distance)
    n_pred, n_true, n_match = len(predicted), len(truth), len(pairs)
    by_true = {o.id: o for o in scene.objects}
    room_acc = floor_acc = None
    if room_map is not None and pairs:
        hits = [
            room_map.get(p.room_id or "") == by_true[pairs[p.id]].room_id
            for p in predicted
            if p.id in pairs
        ]
        room_acc = float(np.mean(hits))
    if floor_level is not None and pairs:
        hits = [floor_level(p) == by_true[pairs[p.id]].floor for p in predicted if p.id in pairs]
        floor_acc = float(np.mean(hits))
    checked = held = 0
    for edge in relations:
        predicate = str(edge.prop("predicate", ""))
        test = _GT_PREDICATES.get(predicate)
        if test is None or edge.src not in pairs or edge.dst not in pairs:
            continue
        checked += 1
        held += bool(test(by_true[pairs[edge.src]], by_true[pairs[edge.dst]]))
    return MappingQuality(
        predicted=n_pred,
        true_objects=n_true,
        matched=n_match,
        precision=(n_match + len(extra)) / n_pred if n_pred else 0.0,
        recall=n_match / n_true if n_true else 0.0,
        duplicate_rate=_duplicates(predicted, scene.objects, max_distance) / n_pred
        if n_pred
        else 0.0,
        room_accuracy=room_acc,
        floor_accuracy=floor_acc,
        relation_precision=held / checked if checked else None,
        relations_checked=checked,
        pairs=pairs,
    )


# ------------------------------------------------------------------ rooms
ROOM_STEP = 0.1  # spacing of the sample points laid over the true room polygons (m)
MAJORITY = 0.5  # share both sides of a room match must exceed


def _polygon_samples(polygon: Sequence[Sequence[float]], step: float) -> np.ndarray:
    """(N, 2) points of a ``step`` grid (cell centres) inside ``polygon`` (even-odd rule)."""
    poly = np.asarray(polygon, dtype=float)[:, :2]
    lo, hi = poly.min(axis=0), poly.max(axis=0)
    xs, ys = np.meshgrid(
        np.arange(lo[0] + step / 2, hi[0], step), np.arange(lo[1] + step / 2, hi[1], step)
    )
    px, py = xs.ravel(), ys.ravel()
    inside = np.zeros(len(px), dtype=bool)
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0), strict=True):
        if y0 == y1:
            continue
        crosses = (y0 > py) != (y1 > py)
        inside ^= crosses & (px < x0 + (py - y0) * (x1 - x0) / (y1 - y0))
    return np.column_stack([px[inside], py[inside]])


def _mask_hits(mask: RoomMask, pts: np.ndarray) -> np.ndarray:
    """Which (N, 2) points fall on covered cells of ``mask``."""
    c = np.floor((pts[:, 0] - mask.origin_x) / mask.resolution).astype(np.int64)
    r = np.floor((pts[:, 1] - mask.origin_y) / mask.resolution).astype(np.int64)
    h, w = mask.cells.shape
    ok = (r >= 0) & (r < h) & (c >= 0) & (c < w)
    hit = np.zeros(len(pts), dtype=bool)
    hit[ok] = mask.cells[r[ok], c[ok]]
    return hit


def _mask_overlap(mask: RoomMask, polygon: Sequence[Sequence[float]]) -> float:
    """Area (m²) of the mask's covered cells whose centres lie inside ``polygon``."""
    from inherit_sg.benchmark.metrics.geometry import rasterize_polygon

    inside = rasterize_polygon(
        polygon, (mask.origin_x, mask.origin_y), mask.resolution, mask.cells.shape
    )
    return float(np.count_nonzero(inside & mask.cells)) * mask.resolution**2


@dataclass
class RoomOverlaps:
    """Areas (m²) shared by predicted rooms and true rooms on the same floor.

    ``overlap[i, j]``: area of true room ``true_ids[j]`` that predicted room
    ``pred_ids[i]``'s mask covers (its cells whose centres lie in the polygon);
    ``pred_area``: each predicted mask's whole area; ``true_area``: each true polygon's
    area and ``mapped`` the part of it that any predicted room of its floor covers (both
    sampled on a :data:`ROOM_STEP` grid; ``mapped`` is at least the largest overlap).
    """

    pred_ids: list[str]
    true_ids: list[str]
    overlap: np.ndarray
    pred_area: np.ndarray
    true_area: np.ndarray
    mapped: np.ndarray


def room_overlaps(
    rooms: Iterable[RoomNode],
    scene: Scene,
    floor_levels: dict[str, int],
    step: float = ROOM_STEP,
) -> RoomOverlaps:
    """Overlap areas of every predicted room (with a mask) against every true room of the
    same floor (a predicted room whose floor is unknown is compared with all floors)."""
    preds = [r for r in rooms if r.mask is not None]
    samples = [_polygon_samples(t.polygon, step) for t in scene.rooms]
    cell = step * step
    overlap = np.zeros((len(preds), len(scene.rooms)))
    union = [np.zeros(len(pts), dtype=bool) for pts in samples]
    for i, pred in enumerate(preds):
        assert pred.mask is not None
        level = floor_levels.get(pred.floor_id or "")
        for j, (true, pts) in enumerate(zip(scene.rooms, samples, strict=True)):
            if level is not None and true.floor != level:
                continue
            union[j] |= _mask_hits(pred.mask, pts)
            overlap[i, j] = _mask_overlap(pred.mask, true.polygon)
    return RoomOverlaps(
        pred_ids=[r.id for r in preds],
        true_ids=[t.id for t in scene.rooms],
        overlap=overlap,
        pred_area=np.array([r.mask.area_m2 for r in preds if r.mask is not None]),
        true_area=np.array([len(pts) * cell for pts in samples]),
        mapped=np.maximum(
            np.array([float(u.sum()) * cell for u in union]),
            overlap.max(axis=0) if len(preds) else 0.0,
        ),
    )


def room_correspondence(
    rooms: Iterable[RoomNode], scene: Scene, floor_levels: dict[str, int], step: float = ROOM_STEP
) -> dict[str, str]:
    """Predicted room id -> the true room (same floor) its mask overlaps most, for every
    predicted room that overlaps any: the room an object of that predicted room is
    compared with when room assignment is scored. Several predicted rooms may map to one
    true room; for precision and recall use :func:`match_rooms`."""
    ov = room_overlaps(rooms, scene, floor_levels, step)
    out: dict[str, str] = {}
    for i, pred_id in enumerate(ov.pred_ids):
        if ov.overlap.shape[1] and ov.overlap[i].max() > 0:
            out[pred_id] = ov.true_ids[int(np.argmax(ov.overlap[i]))]
    return out


@dataclass
class RoomMatching:
    """Room precision and recall of a map against every true room (region).

    Overlap rule (mutual majority): predicted room P and true room T match when more than
    :data:`MAJORITY` of P's mask lies in T (P is not mostly some other room, or several
    rooms merged) and P covers more than :data:`MAJORITY` of the part of T that any
    predicted room covers (T is not split between predicted rooms). Each side has at most
    one such partner, so the matching is one-to-one. Precision = matched / predicted
    rooms; recall = matched / true rooms, every true room counted (``recall_seen`` leaves
    out true rooms no predicted room touches; they are listed in ``unseen``).
    """

    precision: float
    recall: float
    recall_seen: float
    predicted: int
    true_rooms: int
    matched: int
    pairs: dict[str, str] = field(default_factory=dict)  # predicted id -> true id
    unseen: list[str] = field(default_factory=list)
    overlaps: RoomOverlaps | None = None

    def to_dict(self) -> dict[str, object]:
        """JSON-able figures (pairs included, overlap matrix left out)."""
        out = asdict(self)
        out.pop("overlaps")
        return out


def match_rooms(
    rooms: Iterable[RoomNode],
    scene: Scene,
    floor_levels: dict[str, int],
    step: float = ROOM_STEP,
    majority: float = MAJORITY,
) -> RoomMatching:
    """Match predicted rooms with the scene's true rooms by the rule of :class:`RoomMatching`."""
    ov = room_overlaps(rooms, scene, floor_levels, step)
    pairs: dict[str, str] = {}
    for i, pred_id in enumerate(ov.pred_ids):
        for j, true_id in enumerate(ov.true_ids):
            a = ov.overlap[i, j]
            if a > 0 and a > majority * ov.pred_area[i] and a > majority * ov.mapped[j]:
                pairs[pred_id] = true_id
    n_pred, n_true = len(ov.pred_ids), len(ov.true_ids)
    unseen = [t for t, m in zip(ov.true_ids, ov.mapped, strict=True) if m <= 0]
    seen = n_true - len(unseen)
    return RoomMatching(
        precision=len(pairs) / n_pred if n_pred else 0.0,
        recall=len(pairs) / n_true if n_true else 0.0,
        recall_seen=len(pairs) / seen if seen else 0.0,
        predicted=n_pred,
        true_rooms=n_true,
        matched=len(pairs),
        pairs=pairs,
        unseen=unseen,
        overlaps=ov,
    )
