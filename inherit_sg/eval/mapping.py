"""Object-level mapping quality against a ground-truth :class:`Scene`.

* precision / recall: a predicted object node matches a true object within
  ``max_distance`` (0.5 m) with a compatible label (same label or a synonym of it);
  one-to-one, nearest first. Recall counts only true objects that were seen (``visible``)
  when that set is given: an object the camera never saw cannot be mapped.
* duplicate rate: predicted nodes beyond the first near the same true object, over all
  predicted nodes.
* room and floor assignment accuracy over matched pairs.
* relation precision: predicted RELATION edges between matched objects that hold in the
  ground truth (same predicate semantics, evaluated on true boxes).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass, field

import numpy as np

from ingest.synthetic.scene import ObjectGT, Scene
from ingest.synthetic.truth_predicates import above, near, next_to, on
from ingest.synthetic.vocabulary import OBJECT_KINDS
from inherit_sg.model import Edge, ObjectNode, RoomNode

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
    if not predicted or not truth:
        return 0
    p = np.array([o.position for o in predicted], dtype=float)
    dup = 0
    for obj in truth:
        d = np.linalg.norm(p - np.asarray(obj.centroid), axis=1)
        near_ids = [
            i
            for i in np.nonzero(d <= max_distance)[0].tolist()
            if labels_compatible(predicted[i].label, obj.label)
        ]
        dup += max(0, len(near_ids) - 1)
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


def room_correspondence(
    rooms: Iterable[RoomNode], scene: Scene, floor_levels: dict[str, int], step: float = 0.1
) -> dict[str, str]:
    """Predicted room id -> the true room its mask overlaps most (same floor), by
    sampling each true room polygon on a ``step`` grid."""
    import cv2

    samples: list[tuple[str, int, np.ndarray]] = []
    for room in scene.rooms:
        poly = np.asarray(room.polygon, dtype=float)
        lo, hi = poly.min(axis=0), poly.max(axis=0)
        xs, ys = np.meshgrid(
            np.arange(lo[0] + step / 2, hi[0], step), np.arange(lo[1] + step / 2, hi[1], step)
        )
        pts = np.stack([xs.ravel(), ys.ravel()], axis=1)
        contour = poly.astype(np.float32).reshape(-1, 1, 2)
        inside = np.array(
            [cv2.pointPolygonTest(contour, (float(x), float(y)), False) > 0 for x, y in pts],
            dtype=bool,
        )
        samples.append((room.id, room.floor, pts[inside]))
    out: dict[str, str] = {}
    for pred in rooms:
        if pred.mask is None:
            continue
        level = floor_levels.get(pred.floor_id or "")
        best, best_n = None, 0
        for room_id, floor, pts in samples:
            if level is not None and floor != level:
                continue
            n = sum(pred.mask.contains_xy(float(x), float(y)) for x, y in pts)
            if n > best_n:
                best, best_n = room_id, n
        if best is not None:
            out[pred.id] = best
    return out
