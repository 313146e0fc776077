"""Candidate request specs mined from a scene, by category and subcategory.

Each miner walks the scene's objects in a seeded order and proposes specs that describe
the object it stands on ("anchor") in one way: a room, a relation to a neighbour, a
negation that excludes a look-alike, an attribute, a function. The generator evaluates
every proposal and keeps those whose answer sets are small and meaningful.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterator
from dataclasses import replace

from inherit_sg.ingest.synthetic.colour_naming import is_clear
from inherit_sg.ingest.synthetic.query_templates import FUNCTION_WORDING, UNSCOPED_FUNCTIONS
from inherit_sg.ingest.synthetic.query_text import labels_for_noun, noun_words
from inherit_sg.ingest.synthetic.scene import ObjectGT, Scene
from inherit_sg.ingest.synthetic.truth import SceneIndex
from inherit_sg.ingest.synthetic.truth_predicates import (
    BINARY_PREDICATES,
    between,
    scene_floor_levels,
    serves,
)
from inherit_sg.ingest.synthetic.truth_spec import (
    AreaConstraint,
    FloorConstraint,
    ObjectSpec,
    RelationConstraint,
    RoomConstraint,
)
from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

# Relations worth saying; a mug on a table is also above it, so "above" is only said
# when "on" is not (and "under" when "supports" is not).
_FACT_ORDER = ("on", "supports", "above", "under", "next_to", "near")
_IMPLIED_BY = {"above": "on", "under": "supports", "near": "next_to"}


class SceneFacts:
    """The scene's objects, their pairwise relations and seeded word choices."""

    def __init__(self, scene: Scene, index: SceneIndex, rng: random.Random) -> None:
        self.scene = scene
        self.index = index
        self.rng = rng
        self.objects = list(index.objects)
        self.labels = sorted({o.label for o in self.objects})
        self.levels = scene_floor_levels(scene)
        self.multi_floor = len(self.levels) > 1
        self.rooms_of_type: dict[str, int] = {}
        for room in scene.rooms:
            self.rooms_of_type[room.type] = self.rooms_of_type.get(room.type, 0) + 1
        self.facts: dict[str, list[tuple[str, ObjectGT]]] = {o.id: [] for o in self.objects}
        by_floor: dict[int, list[ObjectGT]] = {}
        for o in self.objects:
            by_floor.setdefault(o.floor, []).append(o)
        for group in by_floor.values():
            for a in group:
                for b in group:
                    # "the chair next to the chair" reads badly: relate different kinds only.
                    if a.label != b.label:
                        self._add_facts(a, b)

    def _add_facts(self, a: ObjectGT, b: ObjectGT) -> None:
        held = {p for p in _FACT_ORDER if BINARY_PREDICATES[p](a, b)}
        for p in _FACT_ORDER:
            if p in held and _IMPLIED_BY.get(p) not in held:
                self.facts[a.id].append((p, b))

    def anchors(self) -> list[ObjectGT]:
        """The objects in a fresh seeded order."""
        out = list(self.objects)
        self.rng.shuffle(out)
        return out

    def target(self, obj: ObjectGT) -> ObjectSpec:
        """A bare spec naming ``obj``'s kind with a seeded synonym (all kinds it can name)."""
        noun = self.rng.choice(noun_words(obj.label))
        return ObjectSpec(labels=labels_for_noun(noun, self.labels), noun=noun)

    def room(self, obj: ObjectGT, by_name: bool = False) -> RoomConstraint | None:
        """A room constraint for ``obj``'s room, by type or (when ``by_name``) by name."""
        room = self.index.room_of(obj)
        if room is None:
            return None
        if by_name:
            return RoomConstraint(name=room.name) if room.name else None
        return RoomConstraint(type=room.type)

    def floor(self, obj: ObjectGT, negated: bool = False) -> FloorConstraint | None:
        """A seeded way of naming ``obj``'s floor (number or relative word)."""
        if not self.multi_floor:
            return None
        forms: list[FloorConstraint] = [FloorConstraint(level=obj.floor, negated=negated)]
        if obj.floor == self.levels[0]:
            forms.append(FloorConstraint(relative="downstairs", negated=negated))
        else:
            forms.append(FloorConstraint(relative="upstairs", negated=negated))
            forms.append(FloorConstraint(relative="upstairs", negated=negated))
        if obj.floor == self.levels[-1]:
            forms.append(FloorConstraint(relative="top", negated=negated))
        return self.rng.choice(forms)

    def colour_clear(self, obj: ObjectGT) -> bool:
        """Whether people would name ``obj``'s colour without hesitating: always for a
        palette colour, for a sampled one (``attributes["rgb"]``) when it lies well
        inside its basic colour term (:func:`~inherit_sg.ingest.synthetic.colour_naming.is_clear`)."""
        rgb = obj.attributes.get("rgb")
        return rgb is None or is_clear(tuple(rgb))

    def looks_alike(self, spec: ObjectSpec, obj: ObjectGT) -> list[ObjectGT]:
        """Other objects the spec's noun also names."""
        return [o for o in self.objects if o.label in spec.labels and o.id != obj.id]

    def relation(self, obj: ObjectGT, limit: int = 3) -> list[RelationConstraint]:
        """Up to ``limit`` seeded relations of ``obj`` to neighbours."""
        facts = list(self.facts[obj.id])
        self.rng.shuffle(facts)
        return [RelationConstraint(p, self.target(b)) for p, b in facts[:limit]]


Miner = Callable[[SceneFacts], Iterator[ObjectSpec]]


def _a_room(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        if (room := f.room(a)) is not None:
            yield replace(f.target(a), room=room)


def _a_room_name(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        room = f.index.room_of(a)
        if room is None or f.rooms_of_type.get(room.type, 0) < 2:
            continue
        if (by_name := f.room(a, by_name=True)) is not None:
            yield replace(f.target(a), room=by_name)


def _a_room_floor(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        if (room := f.room(a)) is not None and f.multi_floor:
            yield replace(f.target(a), room=room, floor=f.floor(a))


def _a_floor(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        if f.multi_floor:
            yield replace(f.target(a), floor=f.floor(a))


def _b_relation(predicate: str) -> Miner:
    def mine(f: SceneFacts) -> Iterator[ObjectSpec]:
        for a in f.anchors():
            for p, b in f.facts[a.id]:
                if p == predicate:
                    yield replace(f.target(a), relations=[RelationConstraint(p, f.target(b))])

    return mine


def _between_triples(f: SceneFacts, a: ObjectGT) -> Iterator[tuple[ObjectGT, ObjectGT]]:
    same_room = [o for o in f.objects if o.room_id == a.room_id and o.id != a.id]
    for i, b in enumerate(same_room):
        for c in same_room[i + 1 :]:
            if b.label != c.label and between(a, b, c):
                yield b, c


def _b_between(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        if a.room_id is None:
            continue
        for b, c in _between_triples(f, a):
            rel = RelationConstraint("between", f.target(b), f.target(c))
            yield replace(f.target(a), relations=[rel])


def _c_relation(with_room: bool, with_floor: bool) -> Miner:
    def mine(f: SceneFacts) -> Iterator[ObjectSpec]:
        for a in f.anchors():
            room = f.room(a) if with_room else None
            floor = f.floor(a) if with_floor else None
            if (with_room and room is None) or (with_floor and floor is None):
                continue
            for rel in f.relation(a, limit=2):
                yield replace(f.target(a), relations=[rel], room=room, floor=floor)

    return mine


def _c_chain(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        for p, b in f.facts[a.id][:4]:
            if p == "supports":  # "with a tray with a mug on it on it" does not read
                continue
            for q, c in f.facts[b.id][:4]:
                if c.label in (a.label, b.label):
                    continue
                landmark = replace(f.target(b), relations=[RelationConstraint(q, f.target(c))])
                spec = replace(f.target(a), relations=[RelationConstraint(p, landmark)])
                room = f.room(a) if f.rng.random() < 0.7 else None
                floor = f.floor(a) if f.rng.random() < 0.35 else None
                yield replace(spec, room=room, floor=floor)


def _c_area(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        label = f.index.area_labels.get(a.area_id) if a.area_id is not None else None
        if label is None:
            continue
        floor = f.floor(a) if f.rng.random() < 0.5 else None
        yield replace(f.target(a), area=AreaConstraint(label), room=f.room(a), floor=floor)


def _functions(obj: ObjectGT) -> tuple[str, ...]:
    kind = OBJECT_KINDS.get(obj.label)
    return kind.functions if kind is not None else ()


def _f_function(scope: str) -> Miner:
    def mine(f: SceneFacts) -> Iterator[ObjectSpec]:
        for a in f.anchors():
            for fn in _functions(a):
                if fn not in FUNCTION_WORDING or not serves(a, fn):
                    continue
                spec = ObjectSpec(function=fn)
                if scope != "alone" and fn in UNSCOPED_FUNCTIONS:
                    continue
                if scope == "alone":
                    yield spec
                elif scope == "room" and (room := f.room(a)) is not None:
                    yield replace(spec, room=room)
                elif scope == "floor" and (floor := f.floor(a)) is not None:
                    yield replace(spec, floor=floor)
                elif scope == "room_floor" and f.multi_floor and (room := f.room(a)):
                    yield replace(spec, room=room, floor=f.floor(a))
                elif scope == "relation":
                    for rel in f.relation(a, limit=2):
                        if rel.predicate in ("next_to", "near", "on", "under"):
                            yield replace(spec, relations=[rel])

    return mine


def basic_miners() -> dict[str, dict[str, Miner]]:
    """Miners of categories A (room/floor), B (one landmark), C (chains) and F."""
    return {
        "A": {
            "room": _a_room,
            "room_name": _a_room_name,
            "room_floor": _a_room_floor,
            "floor": _a_floor,
        },
        "B": {p: _b_relation(p) for p in _FACT_ORDER} | {"between": _b_between},
        "C": {
            "relation_room": _c_relation(True, False),
            "relation_floor": _c_relation(False, True),
            "relation_room_floor": _c_relation(True, True),
            "chain": _c_chain,
            "area": _c_area,
        },
        "F": {
            "function": _f_function("alone"),
            "function_room": _f_function("room"),
            "function_floor": _f_function("floor"),
            "function_room_floor": _f_function("room_floor"),
            "function_relation": _f_function("relation"),
        },
    }
