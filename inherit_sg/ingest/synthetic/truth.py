"""Ground truth for requests: which objects of a synthetic :class:`Scene` satisfy a spec.

:func:`evaluate` returns ALL object ids satisfying an :class:`ObjectSpec` (in scene
order), using the deterministic predicates and thresholds documented in
:mod:`inherit_sg.ingest.synthetic.truth_predicates`. Semantics:

- target: label in ``labels`` (any label when empty) and, with ``function``, a kind that
  serves it; structural objects (doors, windows) are targets and landmarks like any other;
- attributes, room, area and floor constraints must hold (fail, when negated); an object
  without a room fails a positive room constraint and passes a negated one;
- a relation holds when some landmark (an object matching the landmark spec, not the
  target itself) is in that relation with the target; a negated relation holds when no
  landmark is; ``between`` needs one landmark of each of its two specs;
- ``exclude_ids`` drops objects named in an earlier turn ("the other one");
- the superlative is applied last, among the objects that passed everything else; ties
  within ``TIE_TOL`` all win.
"""

from __future__ import annotations

from inherit_sg.ingest.synthetic.scene import ObjectGT, RoomGT, Scene
from inherit_sg.ingest.synthetic.truth_predicates import (
    BINARY_PREDICATES,
    between,
    floor_levels,
    has_attribute,
    room_matches,
    serves,
    superlative_score,
)
from inherit_sg.ingest.synthetic.truth_spec import (
    AreaConstraint,
    AttributeConstraint,
    FloorConstraint,
    ObjectSpec,
    RelationConstraint,
    RoomConstraint,
)

__all__ = [
    "AreaConstraint",
    "AttributeConstraint",
    "FloorConstraint",
    "ObjectSpec",
    "RelationConstraint",
    "RoomConstraint",
    "SceneIndex",
    "evaluate",
]

TIE_TOL = 1e-9


class SceneIndex:
    """Lookups and a result cache over one scene; reuse it to evaluate many specs fast.

    The scene must not change while an index over it is in use.
    """

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        self.objects: list[ObjectGT] = list(scene.objects)
        self.by_id: dict[str, ObjectGT] = {o.id: o for o in self.objects}
        self.rooms: dict[str, RoomGT] = {r.id: r for r in scene.rooms}
        self.area_labels: dict[str, str] = {a.id: a.label for a in scene.areas}
        self._cache: dict[str, list[ObjectGT]] = {}

    def room_of(self, obj: ObjectGT) -> RoomGT | None:
        """The room ``obj`` is in, if any."""
        return self.rooms.get(obj.room_id) if obj.room_id is not None else None

    def match(self, spec: ObjectSpec) -> list[ObjectGT]:
        """Objects satisfying ``spec``, in scene order (cached by the spec's meaning)."""
        key = spec.key()
        hit = self._cache.get(key)
        if hit is None:
            hit = self._match(spec)
            self._cache[key] = hit
        return hit

    def _match(self, spec: ObjectSpec) -> list[ObjectGT]:
        floors: set[int] | None = None
        floor_negated = False
        if spec.floor is not None:
            floors = floor_levels(self.scene, spec.floor.level, spec.floor.relative)
            floor_negated = spec.floor.negated
        labels = set(spec.labels)
        excluded = set(spec.exclude_ids)
        found = [
            o
            for o in self.objects
            if (not labels or o.label in labels)
            and o.id not in excluded
            and (spec.function is None or serves(o, spec.function))
            and all(has_attribute(o, a.key, a.value) != a.negated for a in spec.attributes)
            and (floors is None or (o.floor in floors) != floor_negated)
            and self._room_ok(o, spec.room)
            and self._area_ok(o, spec.area)
        ]
        for rel in spec.relations:
            found = [o for o in found if self._relation_holds(o, rel) != rel.negated]
        if spec.superlative is not None and found:
            scores = [superlative_score(o, spec.superlative) for o in found]
            best = max(scores)
            found = [o for o, s in zip(found, scores, strict=True) if s >= best - TIE_TOL]
        return found

    def _room_ok(self, obj: ObjectGT, room: RoomConstraint | None) -> bool:
        if room is None:
            return True
        return room_matches(self.room_of(obj), room.type, room.name) != room.negated

    def _area_ok(self, obj: ObjectGT, area: AreaConstraint | None) -> bool:
        if area is None:
            return True
        label = self.area_labels.get(obj.area_id) if obj.area_id is not None else None
        inside = label is not None and label.lower() == area.label.lower()
        return inside != area.negated

    def _relation_holds(self, obj: ObjectGT, rel: RelationConstraint) -> bool:
        landmarks = [lm for lm in self.match(rel.landmark) if lm.id != obj.id]
        if rel.predicate == "between":
            assert rel.landmark2 is not None
            others = [lm for lm in self.match(rel.landmark2) if lm.id != obj.id]
            return any(between(obj, b, c) for b in landmarks for c in others)
        predicate = BINARY_PREDICATES[rel.predicate]
        return any(predicate(obj, lm) for lm in landmarks)


def evaluate(scene: Scene, spec: ObjectSpec, index: SceneIndex | None = None) -> list[str]:
    """Ids of ALL objects of ``scene`` satisfying ``spec``, in scene order.

    Pass an ``index`` built over the same scene to reuse lookups across many calls.
    """
    idx = index if index is not None and index.scene is scene else SceneIndex(scene)
    return [o.id for o in idx.match(spec)]
