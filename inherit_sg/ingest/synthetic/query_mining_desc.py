"""Candidate specs for negation (D) and descriptive (E) requests.

Negations start from an anchor and a look-alike (another object the same noun names)
and negate something true of the look-alike but not of the anchor: its room, floor,
area, colour, material or a relation to a neighbour. Descriptions name the anchor's
colour, material or size, or a superlative it wins by a clear margin.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from typing import Any

from inherit_sg.ingest.synthetic.query_mining import Miner, SceneFacts
from inherit_sg.ingest.synthetic.scene import ObjectGT
from inherit_sg.ingest.synthetic.truth_predicates import SUPERLATIVES, superlative_score
from inherit_sg.ingest.synthetic.truth_spec import (
    AreaConstraint,
    AttributeConstraint,
    ObjectSpec,
    RelationConstraint,
    RoomConstraint,
)

# A superlative is only asked for when the winner beats the runner-up by this fraction.
SUPERLATIVE_MARGIN = 0.15
MAX_ANSWERS = 3


def _scopes(f: SceneFacts, a: ObjectGT, room: bool, floor: bool) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = [{}]
    if room and (rc := f.room(a)) is not None:
        out.append({"room": rc})
    if floor and (fc := f.floor(a)) is not None:
        out.append({"floor": fc})
    return out


def _d_not_room(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        base = f.target(a)
        mine = f.index.room_of(a)
        types = set()
        for o in f.looks_alike(base, a):
            room = f.index.room_of(o)
            if room is not None and (mine is None or room.type != mine.type):
                types.add(room.type)
        for scope in _scopes(f, a, room=False, floor=True):
            for t in sorted(types):
                yield replace(base, room=RoomConstraint(type=t, negated=True), **scope)


def _d_not_floor(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        base = f.target(a)
        others = [o for o in f.looks_alike(base, a) if o.floor != a.floor]
        for scope in _scopes(f, a, room=True, floor=False):
            for o in others[:2]:
                yield replace(base, floor=f.floor(o, negated=True), **scope)


def _d_not_relation(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        base = f.target(a)
        own = {(p, b.label) for p, b in f.facts[a.id]}
        for scope in _scopes(f, a, room=True, floor=True):
            for o in f.looks_alike(base, a)[:4]:
                for p, c in f.facts[o.id][:3]:
                    if (p, c.label) in own or c.id == a.id:
                        continue
                    rel = RelationConstraint(p, f.target(c), negated=True)
                    yield replace(base, relations=[rel], **scope)


def _in_noun(spec: ObjectSpec, attr: AttributeConstraint) -> bool:
    """Whether the attribute's value is a word of the spec's noun ("paper" in "toilet
    paper"): saying it again reads badly and says nothing."""
    return attr.value in spec.noun.split()


def _d_not_attribute(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        base = f.target(a)
        for scope in _scopes(f, a, room=True, floor=True):
            for o in f.looks_alike(base, a)[:4]:
                for key in ("colour", "material"):
                    value = o.attributes.get(key)
                    if key == "colour" and not (f.colour_clear(a) and f.colour_clear(o)):
                        continue
                    if isinstance(value, str) and value != a.attributes.get(key):
                        attr = AttributeConstraint(key, value, negated=True)
                        if _in_noun(base, attr):
                            continue
                        yield replace(base, attributes=[attr], **scope)


def _d_not_area(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        base = replace(f.target(a), room=f.room(a))
        mine = f.index.area_labels.get(a.area_id) if a.area_id is not None else None
        for o in f.looks_alike(base, a):
            label = f.index.area_labels.get(o.area_id) if o.area_id is not None else None
            if o.room_id == a.room_id and label is not None and label != mine:
                yield replace(base, area=AreaConstraint(label, negated=True))


def _narrowest(f: SceneFacts, a: ObjectGT, spec: ObjectSpec) -> ObjectSpec | None:
    """The spec with the broadest scope (none, room, floor, both) that stays small."""
    scopes = _scopes(f, a, room=True, floor=True)
    if len(scopes) == 3:
        scopes.append(scopes[1] | scopes[2])
    for scope in scopes:
        candidate = replace(spec, **scope)
        found = f.index.match(candidate)
        if any(o is a for o in found) and len(found) <= MAX_ANSWERS:
            return candidate
    return None


def _e_attributes(keys: tuple[str, ...]) -> Miner:
    def mine(f: SceneFacts) -> Iterator[ObjectSpec]:
        for a in f.anchors():
            values = [a.attributes.get(k) for k in keys]
            if not all(isinstance(v, str) for v in values):
                continue
            if "colour" in keys and not f.colour_clear(a):
                continue
            attrs = [AttributeConstraint(k, str(v)) for k, v in zip(keys, values, strict=True)]
            target = f.target(a)
            if any(_in_noun(target, x) for x in attrs):
                continue  # "a glass glass"
            spec = _narrowest(f, a, replace(target, attributes=attrs))
            if spec is not None:
                yield spec

    return mine


def _clear_winner(f: SceneFacts, scope_spec: ObjectSpec, superlative: str) -> ObjectGT | None:
    found = f.index.match(scope_spec)
    if len(found) < 2:
        return None
    scores = sorted((superlative_score(o, superlative), i) for i, o in enumerate(found))
    best, second = scores[-1][0], scores[-2][0]
    if best - second < SUPERLATIVE_MARGIN * abs(best):
        return None
    return found[scores[-1][1]]


def _e_superlative(f: SceneFacts) -> Iterator[ObjectSpec]:
    for a in f.anchors():
        base = f.target(a)
        scopes = _scopes(f, a, room=True, floor=True)
        for sup in SUPERLATIVES:
            for scope in scopes:
                spec = replace(base, **scope)
                if _clear_winner(f, spec, sup) is a:
                    yield replace(spec, superlative=sup)
                    break


def desc_miners() -> dict[str, dict[str, Miner]]:
    """Miners of categories D (negation) and E (descriptive)."""
    return {
        "D": {
            "not_room": _d_not_room,
            "not_floor": _d_not_floor,
            "not_relation": _d_not_relation,
            "not_attribute": _d_not_attribute,
            "not_area": _d_not_area,
        },
        "E": {
            "colour": _e_attributes(("colour",)),
            "material": _e_attributes(("material",)),
            "size": _e_attributes(("size",)),
            "colour_material": _e_attributes(("colour", "material")),
            "superlative": _e_superlative,
        },
    }
