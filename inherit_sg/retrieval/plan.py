"""Compile a :class:`ParsedQuery` into an inspectable :class:`QueryPlan`.

A plan has one :class:`NodeSpec` per thing to find: the target, and every relation's
landmark (recursively, for chains). Compiling resolves the request against the map:
the floor words become the levels of the hard filter ``H_floor``, label and function
words become the map labels they match (exactly through the lexicon, or by embedding
similarity), room and area phrases become the rooms and areas they name. Each spec then
gets ordered :class:`Step` s — candidate generation by Cypher over the public tables,
vector-index and full-text fallbacks, HAS_* / RELATION traversals, scoring — that
:mod:`inherit_sg.retrieval.candidates` and :mod:`inherit_sg.retrieval.scoring` execute.
``--explain`` prints them.

A request's viewpoint ("facing the windows") is compiled like a relation's landmark:
a spec under the key ``VIEWPOINT`` of the target, resolved before everything else; every
other spec of the plan carries the :class:`Viewpoint` so its scoring can place the
viewer (:mod:`inherit_sg.retrieval.viewer`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from inherit_sg.mapping.relations import NEAR_GAP
from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    Constraint,
    FloorConstraint,
    FunctionConstraint,
    LabelConstraint,
    Landmark,
    PlacementConstraint,
    RelationConstraint,
    RoomConstraint,
    Superlative,
    Target,
    Viewpoint,
)
from inherit_sg.retrieval.directions import VIEW_PREDICATES
from inherit_sg.retrieval.match import Matches, resolve_matches
from inherit_sg.retrieval.query import ParsedQuery, describe, number_constraints
from inherit_sg.retrieval.similarity import PhraseSimilarity
from inherit_sg.retrieval.snapshot import MapSnapshot, canonical_labels
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab.functions import kinds_serving, usual_room
from inherit_sg.vocab.lexicon import lexicon
from inherit_sg.vocab.rooms import room_type

_LIVE = "coalesce(o.status, 'active') <> 'removed'"
CYPHER_OBJECTS_BY_LABEL = f"MATCH (o:Object) WHERE o.label IN $labels AND {_LIVE} RETURN o.id"
CYPHER_OBJECTS_IN_ROOMS = (
    "MATCH (r:Room)-[:HAS_AREA]->(:Area)-[:HAS_OBJECT]->(o:Object) "
    f"WHERE r.id IN $rooms AND {_LIVE} RETURN o.id"
)
CYPHER_OBJECTS_IN_AREAS = (
    f"MATCH (a:Area)-[:HAS_OBJECT]->(o:Object) WHERE a.id IN $areas AND {_LIVE} RETURN o.id"
)
CYPHER_OBJECTS_ON_FLOORS = f"MATCH (o:Object) WHERE o.floor_id IN $floors AND {_LIVE} RETURN o.id"
CYPHER_ALL_OBJECTS = f"MATCH (o:Object) WHERE {_LIVE} RETURN o.id"
CYPHER_RELATED_OBJECTS = (
    "MATCH (l:Object)-[:RELATION]-(o:Object) "
    f"WHERE l.id IN $landmarks AND {_LIVE} RETURN DISTINCT o.id"
)
CYPHER_LAYER = {
    "room": "MATCH (n:Room) RETURN n.id",
    "area": "MATCH (n:Area) RETURN n.id",
    "floor": "MATCH (n:Floor) RETURN n.id",
}
# The score term of a query image (weighted like a relation: strong, but not the name).
IMAGE_TERM = "image"
IMAGE_WEIGHT = 0.8
# The landmark key of a request's viewpoint in the target spec, and of what the speaker
# looks at from there ("standing at the sink looking at the bar").
VIEWPOINT = "viewpoint"
VIEWPOINT_TOWARD = "viewpoint/toward"
VIEWPOINT_KEYS = (VIEWPOINT, VIEWPOINT_TOWARD)
VECTOR_INDEX = {"object": "object_text", "area": "area_text", "room": "room_text"}
FULLTEXT_TABLE = {"object": "Object", "area": "Area", "room": "Room"}


@dataclass(frozen=True)
class Step:
    """One executable, printable step of a plan.

    ``op`` is one of ``pinned``, ``cypher``, ``neighbours`` (the landmark's RELATION
    neighbourhood), ``vector``, ``fulltext`` (candidate generation; ``fallback`` ones
    run only when the steps before found nothing),
    ``floor`` (the hard filter), ``viewer`` (where the viewer stands and looks),
    ``traverse`` (a constraint checked by walking HAS_* edges), ``relation`` (a
    GraphRAG check against a landmark), ``placement`` (a position in the room's floor
    mask), ``score`` and ``superlative``.
    """

    op: str
    spec: str
    text: str
    cypher: str | None = None
    params: dict[str, Any] = field(default_factory=dict)
    index: str | None = None
    query_text: str | None = None
    fallback: bool = False
    constraint: str | None = None

    def render(self) -> str:
        """One or two lines for ``--explain``."""
        head = f"[{self.spec}] {self.op}{' (fallback)' if self.fallback else ''}: {self.text}"
        if self.cypher:
            shown = {
                k: (v if len(str(v)) < 160 else f"{str(v)[:157]}...")
                for k, v in self.params.items()
            }
            head += f"\n      cypher: {self.cypher}  params={shown}"
        if self.index:
            head += f"\n      index: {self.index}  text={self.query_text!r}"
        return head


@dataclass
class NodeSpec:
    """What to find for the target or one landmark, resolved against the map."""

    key: str
    layer: str
    target: Target
    constraints: tuple[Constraint, ...]
    floor: FloorConstraint | None = None
    levels: frozenset[int] | None = None
    matches: dict[str, Matches] = field(default_factory=dict)
    landmarks: dict[str, NodeSpec] = field(default_factory=dict)
    exclude_ids: tuple[str, ...] = ()
    steps: list[Step] = field(default_factory=list)
    image: np.ndarray | None = None  # visual feature of a query image (the target only)
    viewpoint: Viewpoint | None = None  # the request's viewpoint (not on its own spec)

    @property
    def phrase(self) -> str:
        """Words that name the node, for vector and full-text search."""
        words = [*self.target.attributes, self.target.noun or " ".join(self.target.labels)]
        text = " ".join(w for w in words if w).strip()
        return text or (self.target.function or "")

    def scored(self) -> list[Constraint]:
        """Constraints that contribute a term to the score (all but the floor)."""
        return [c for c in self.constraints if not isinstance(c, FloorConstraint)]

    def max_score(self) -> float:
        """The largest score a node can reach: the sum of positive weights."""
        return sum(c.weight for c in self.scored() if not c.negated) or 1.0


@dataclass
class QueryPlan:
    """The compiled request: the target spec with its landmark specs."""

    parsed: ParsedQuery
    target: NodeSpec

    @property
    def steps(self) -> list[Step]:
        """All steps in execution order (landmarks before what depends on them)."""
        out: list[Step] = []

        def visit(spec: NodeSpec) -> None:
            for sub in spec.landmarks.values():
                visit(sub)
            out.extend(spec.steps)

        visit(self.target)
        return out

    def explain(self) -> str:
        """The plan as numbered lines."""
        lines = [f"plan for: {self.parsed.text!r}"]
        lines += [f"  {i:2d}. {s.render()}" for i, s in enumerate(self.steps, start=1)]
        return "\n".join(lines)


def resolve_levels(con: FloorConstraint, levels: list[int]) -> frozenset[int]:
    """The floor levels ``con`` allows on a map with ``levels`` (complement if negated)."""
    if not levels:
        return frozenset()
    if con.level is not None:
        chosen = {con.level}
    elif con.relative == "upstairs":
        chosen = {lv for lv in levels if lv > levels[0]}
    elif con.relative == "top":
        chosen = {levels[-1]}
    else:  # downstairs, bottom
        chosen = {levels[0]}
    return frozenset(set(levels) - chosen if con.negated else chosen & set(levels))


def needs_viewer(spec: NodeSpec) -> bool:
    """Whether scoring ``spec`` places a viewer: ordinals, "the middle one", "closest to
    you", and viewer-relative relations between objects."""
    for con in spec.scored():
        if isinstance(con, Superlative) and (
            con.measure in ("ordinal", "middle")
            or (con.measure in ("closest", "farthest") and con.landmark is None)
        ):
            return True
        if (
            isinstance(con, RelationConstraint)
            and con.predicate in VIEW_PREDICATES
            and spec.layer == "object"
        ):
            return True
    return False


def implied_constraints(
    key: str, target: Target, cons: tuple[Constraint, ...]
) -> tuple[Constraint, ...]:
    """Label / function constraints the target names but the list lacks (a landmark's
    own noun lives only in its target)."""
    out: list[Constraint] = []
    kinds = {c.kind for c in cons if not c.negated}
    prefix = "" if key == "target" else f"{key}."
    if target.labels and not kinds & {"label", "function"}:
        out.append(
            LabelConstraint(
                id=f"{prefix}label", labels=target.labels, noun=target.noun, text=target.noun
            )
        )
    if target.function and "function" not in kinds and not target.labels:
        serving = kinds_serving(target.function)
        out.append(
            FunctionConstraint(
                id=f"{prefix}function",
                function=target.function,
                labels=tuple(dict.fromkeys(serving)),
                weight=0.9,
                text=target.function,
            )
        )
    return tuple(out)


# Kinds a compound's first word may name without placing the thing by one ("floor lamp",
# "wall clock", "ceiling fan": every room has them).
_EVERYWHERE = frozenset({"wall", "floor", "ceiling", "room", "house"})
# Weight of the nearness a compound implies ("bar stool": a stool by a bar).
COMPOUND_NEAR_WEIGHT = 0.4


def _absent_compounds(
    cons: tuple[Constraint, ...], snap: MapSnapshot
) -> tuple[list[tuple[LabelConstraint, str]], frozenset[str]]:
    """The positive label constraints asking for a compound kind the map has no label
    for ("bar stool", "dining chair"), each with that compound, and the map's labels
    and their kinds."""
    asked = [
        c
        for c in cons
        if isinstance(c, LabelConstraint) and not c.negated and any(" " in w for w in c.labels)
    ]
    if not asked:  # most requests name no compound: no need to look at the map's labels
        return [], frozenset()
    present = _map_labels(snap)
    out: list[tuple[LabelConstraint, str]] = []
    for con in asked:
        if any(label in present for label in con.labels):
            continue
        out.extend((con, label) for label in con.labels if " " in label)
    return out, present


def compound_nearness(cons: tuple[Constraint, ...], snap: MapSnapshot) -> tuple[Constraint, ...]:
    """A kind asked for by a compound the map does not use ("bar stool", "desk lamp",
    "piano bench") whose first word names a kind the map has: the thing is found by its
    general word (stool) and is likely near that kind (a bar): a weak "near" relation.
    Nothing when the map has the compound's own label or lacks the first word's kind."""
    absent, present = _absent_compounds(cons, snap)
    out: list[Constraint] = []
    done: set[str] = set()
    for con, label in absent:
        if con.id in done:
            continue
        words = label.split()
        mod = object_vocab.canonical_label(words[0])
        if mod is None or mod in _EVERYWHERE or mod not in present or mod == label:
            continue
        done.add(con.id)
        out.append(
            RelationConstraint(
                id=f"{con.id}~{mod}",
                predicate="near",
                landmark=Landmark(target=Target(labels=(mod,), noun=words[0])),
                weight=COMPOUND_NEAR_WEIGHT,
                text=f"a {label} is by a {mod} (the map says only {words[-1]})",
            )
        )
    return tuple(out)


# Weight of the room a compound's first word names ("dining chair": a dining room).
COMPOUND_ROOM_WEIGHT = 0.5


def _room_word(word: str) -> str | None:
    """The room type a compound's first word names: "kitchen", "office", "dining"
    (a dining room), "living" (a living room); not a word of position ("front door",
    "back door", "side table", though "front room" names a room)."""
    if word in lexicon().position_nouns:
        return None
    return room_type(word) or room_type(f"{word} room")


def compound_rooms(
    cons: tuple[Constraint, ...], snap: MapSnapshot, placed: tuple[Constraint, ...] = ()
) -> tuple[Constraint, ...]:
    """A kind asked for by a compound the map does not use, whose first word names a
    type of room ("dining chair", "kitchen cabinet", "bathroom sink"): the thing is found
    by its general word (chair) or a sibling the detector used instead ("sofa chair"),
    and the one in such a room is more likely it. A room constraint, when the request
    names no room and the compound's first word is no kind the map has (``placed``
    holds the nearness :func:`compound_nearness` gave it)."""
    if any(isinstance(c, RoomConstraint) for c in cons) or placed:
        return ()
    absent, _present = _absent_compounds(cons, snap)
    for con, label in absent:
        rtype = _compound_room(label)
        if rtype is not None:
            why = f"a {label} is usually in a {rtype} (the map says only {label.split()[-1]})"
            return _implied_room(con.id, rtype, COMPOUND_ROOM_WEIGHT, why)
    return ()


def _compound_room(label: str) -> str | None:
    """The room type a compound kind's first word names, when that word is no kind of
    its own ("dining table": a dining room; not "bar stool", "front door")."""
    first = label.split()[0]
    rtype = _room_word(first)
    return None if rtype is None or object_vocab.canonical_label(first) is not None else rtype


def _map_labels(snap: MapSnapshot) -> frozenset[str]:
    """The map's labels and their kinds (made once per snapshot)."""

    def make() -> frozenset[str]:
        present: set[str] = set()
        for raw in snap.raw_labels():
            present.update({raw.strip().lower(), *canonical_labels(raw)})
        return frozenset(present)

    return snap.memo("map_labels", make)


def absent_landmark_rooms(
    cons: tuple[Constraint, ...], snap: MapSnapshot
) -> tuple[Constraint, ...]:
    """A landmark of a compound kind the map does not have, whose first word names a type
    of room ("the light over the dining table" in a map that holds no dining table): what
    is sought by it is likely in such a room, a weak room constraint, when the request
    names no room itself. (The relation alone would measure from whatever the map holds
    most like the landmark, a coffee table in another room.)"""
    if any(isinstance(c, RoomConstraint) for c in cons):
        return ()
    for con in cons:
        if not isinstance(con, RelationConstraint) or con.negated:
            continue
        kinds = [label for label in con.landmark.target.labels if " " in label]
        if not kinds or not _map_labels(snap).isdisjoint(con.landmark.target.labels):
            continue
        for label in kinds:
            rtype = _compound_room(label)
            if rtype is not None:
                why = f"by a {label}, usually in a {rtype} (the map has no {label})"
                return _implied_room(con.id, rtype, COMPOUND_ROOM_WEIGHT, why)
    return ()


def _implied_room(con_id: str, rtype: str, weight: float, why: str) -> tuple[Constraint, ...]:
    """The weak room constraint one constraint implies (id ``<con_id>~room``)."""
    return (RoomConstraint(id=f"{con_id}~room", type=rtype, name=rtype, weight=weight, text=why),)


# Weight of the room a function is usually done in ("wash dishes": a kitchen).
USUAL_ROOM_WEIGHT = 0.3


def usual_rooms(cons: tuple[Constraint, ...]) -> tuple[Constraint, ...]:
    """A weak room constraint for a function that is usually done in one type of room
    ("wash a few dishes": a sink in the kitchen, not the one in the toilet), when the
    request names no room itself."""
    if any(isinstance(c, RoomConstraint) for c in cons):
        return ()
    for con in cons:
        if isinstance(con, FunctionConstraint) and not con.negated:
            rtype = usual_room(con.function)
            if rtype is not None:
                why = f"'{con.function}' is usually done in a {rtype} (functions.toml)"
                return _implied_room(con.id, rtype, USUAL_ROOM_WEIGHT, why)
    return ()


# Weight of where a kind typically stands in its room, when the map names no such kind
# (a hint: it orders the candidates, it decides no comparison).
USUAL_PLACEMENT_WEIGHT = 0.4


def usual_placement(cons: tuple[Constraint, ...], snap: MapSnapshot) -> tuple[Constraint, ...]:
    """A weak placement for a kind asked for that typically stands somewhere in its room
    (``objects.toml`` ``placement``: a kitchen island in the middle), when the map has no
    object of that kind and the request says no placement itself: "the kitchen island"
    is then the counter in the middle of the kitchen, not the one along the wall."""
    if any(isinstance(c, PlacementConstraint) for c in cons):
        return ()
    held = {k for kinds in snap.canon.values() for k in kinds}
    for con in cons:
        if not isinstance(con, LabelConstraint) or con.negated:
            continue
        for label in con.labels[:1]:  # the kind asked for ("light" lists chandeliers too)
            where = object_vocab.typical_placement(label)
            if where and label not in held:
                why = f"a {label} usually stands {_PLACED_AT[where]} (objects.toml)"
                return (
                    PlacementConstraint(
                        id=f"{con.id}~placed", where=where, weight=USUAL_PLACEMENT_WEIGHT,
                        text=why,
                    ),
                )  # fmt: skip
    return ()


_PLACED_AT = {
    "centre": "in the middle of its room",
    "wall": "against a wall",
    "corner": "in a corner",
}


# Weight of the room what is sought takes from the landmark it is on, in or under ("the
# cupboards under the kitchen counter" are in the kitchen).
LANDMARK_ROOM_WEIGHT = 0.5
# Relations that put what is sought in its landmark's room.
_SAME_ROOM_PREDICATES = frozenset({"on", "under", "inside", "above", "supports", "contains"})


def landmark_room(cons: tuple[Constraint, ...]) -> tuple[Constraint, ...]:
    """The weak room constraint what is sought takes from a landmark it is on, in, under
    or above, when the landmark's room is said ("the cupboards under the kitchen counter",
    "the mug on the bedroom table") and the request names no room of its own."""
    if any(isinstance(c, RoomConstraint) for c in cons):
        return ()
    for con in cons:
        if (
            not isinstance(con, RelationConstraint)
            or con.negated
            or con.predicate not in _SAME_ROOM_PREDICATES
        ):
            continue
        for room in con.landmark.constraints:
            if isinstance(room, RoomConstraint) and not room.negated:
                why = f"on, in or under the {con.landmark.target.describe()}: in its room"
                return (replace(room, id=f"{con.id}~room", weight=LANDMARK_ROOM_WEIGHT, text=why),)
    return ()


# Weight of the room a landmark is taken to share with what is sought ("the cushion next
# to the sofa in the family room": that sofa is in the family room too).
SHARED_ROOM_WEIGHT = 0.7


def shared_room(
    key: str, lm: Landmark, parent: tuple[Constraint, ...], con: Constraint | None = None
) -> tuple[Constraint, ...]:
    """The weak room constraint a landmark object takes from the request's own room: a
    thing placed by a landmark, or seen from one, is mostly in the landmark's room. None
    when the landmark names its own room or is no object, when the request's room is
    ruled out or implied rather than said, or when the relation itself is ruled out ("a
    TV stand in the lounge, not the one with a door near it": a door of the hall next
    door counts too)."""
    if lm.target.layer != "object" or any(isinstance(c, RoomConstraint) for c in lm.constraints):
        return ()
    if con is not None and con.negated:
        return ()
    said = [
        c for c in parent if isinstance(c, RoomConstraint) and not c.negated and "~" not in c.id
    ]
    if len(said) != 1 or said[0].opening:
        return ()
    room = said[0]
    why = f"the {lm.target.describe()} is taken to be in the {room.name or room.type} too"
    return (replace(room, id=f"{key}~room", weight=SHARED_ROOM_WEIGHT, text=why),)


def _numbered(lm: Landmark, prefix: str) -> Landmark:
    """``lm`` with ids on its constraints (a viewpoint's landmark has none yet)."""
    if all(c.id for c in lm.constraints):
        return lm
    return Landmark(target=lm.target, constraints=number_constraints(lm.constraints, prefix))


class Compiler:
    """Turns parsed requests into plans for one map snapshot."""

    def __init__(self, snap: MapSnapshot, sim: PhraseSimilarity) -> None:
        self.snap = snap
        self.sim = sim

    def compile(self, parsed: ParsedQuery, image: np.ndarray | None = None) -> QueryPlan:
        """The plan of ``parsed`` (which must have a target); ``image`` is the visual
        feature of a picture that came with the request (objects only)."""
        vp = parsed.viewpoint
        spec = self._spec(
            "target", parsed.target, parsed.constraints, parsed.exclude_ids, viewpoint=vp
        )
        if vp is not None:
            room = spec.constraints
            stand = _numbered(vp.landmark, "v")
            seen = {VIEWPOINT: self._landmark(VIEWPOINT, stand, room=room)}
            if vp.toward is not None:
                toward = _numbered(vp.toward, "t")
                seen[VIEWPOINT_TOWARD] = self._landmark(VIEWPOINT_TOWARD, toward, room=room)
            spec.landmarks = {**seen, **spec.landmarks}
        if image is not None and spec.layer == "object":
            spec.image = image
            at = next(i for i, s in enumerate(spec.steps) if s.fallback or s.op != "cypher")
            spec.steps.insert(
                at,
                Step(
                    "visual",
                    spec.key,
                    "objects that look most like the query image",
                    index="object_visual",
                    query_text="<query image>",
                ),
            )
            spec.steps.insert(
                len(spec.steps) - 1,
                Step(
                    "traverse",
                    spec.key,
                    f"{IMAGE_TERM}: appearance, cosine of the image's and "
                    "the candidate's visual features",
                    constraint=IMAGE_TERM,
                ),
            )
        return QueryPlan(parsed=parsed, target=spec)

    def _landmark(
        self,
        key: str,
        lm: Landmark,
        viewpoint: Viewpoint | None = None,
        *,
        room: tuple[Constraint, ...] = (),
        con: Constraint | None = None,
    ) -> NodeSpec:
        """The spec of one landmark; ``room`` holds the constraints of what it places
        (whose room it shares, :func:`shared_room`), ``con`` the relation placing it."""
        cons = (*lm.constraints, *shared_room(key, lm, room, con))
        return self._spec(key, lm.target, cons, (), viewpoint=viewpoint)

    def _spec(
        self,
        key: str,
        target: Target,
        cons: tuple[Constraint, ...],
        exclude: tuple[str, ...],
        *,
        viewpoint: Viewpoint | None = None,
    ) -> NodeSpec:
        cons = (*implied_constraints(key, target, cons), *cons)
        near = compound_nearness(cons, self.snap)
        cons = (*cons, *near, *compound_rooms(cons, self.snap, near))
        cons = (*cons, *landmark_room(cons))
        cons = (*cons, *absent_landmark_rooms(cons, self.snap))
        cons = (*cons, *usual_rooms(cons), *usual_placement(cons, self.snap))
        floor = next((c for c in cons if isinstance(c, FloorConstraint)), None)
        spec = NodeSpec(key, target.layer, target, cons, floor, exclude_ids=exclude)
        spec.viewpoint = viewpoint
        if floor is not None:
            spec.levels = resolve_levels(floor, self.snap.levels)
        vp = viewpoint
        for con in cons:
            if isinstance(con, RelationConstraint):
                spec.landmarks[con.id] = self._landmark(
                    f"{con.id}.landmark", con.landmark, vp, room=cons, con=con
                )
                if con.landmark2 is not None:
                    spec.landmarks[f"{con.id}/2"] = self._landmark(
                        f"{con.id}.landmark2", con.landmark2, vp, room=cons, con=con
                    )
            elif isinstance(con, Superlative) and con.landmark is not None:
                # "the bathroom sink closest to the front door": measured across rooms
                spec.landmarks[con.id] = self._landmark(f"{con.id}.landmark", con.landmark, vp)
            found = resolve_matches(con, spec.layer, self.snap, self.sim)
            if found is not None:
                spec.matches[con.id] = found
        spec.steps = self._steps(spec)
        return spec

    # ------------------------------------------------------------------ steps
    def _steps(self, spec: NodeSpec) -> list[Step]:
        steps = self._generation(spec)
        if spec.floor is not None:
            levels = sorted(spec.levels or ())
            steps.append(
                Step(
                    "floor",
                    spec.key,
                    f"H_floor: keep nodes on levels {levels} "
                    f"({describe(spec.floor)}); all floors if none is left",
                    constraint=spec.floor.id,
                )
            )
        if needs_viewer(spec) or (spec.viewpoint is not None and spec.key == "target"):
            steps.append(self._viewer_step(spec))
        for con in spec.scored():
            steps.append(self._constraint_step(spec, con))
        steps.append(
            Step(
                "score",
                spec.key,
                "S(n) = H_floor · Σ p_i · w_i · Sim(n, c_i) over "
                + ", ".join(f"{c.id}({c.kind})" for c in spec.scored()),
            )
        )
        return steps

    def _generation(self, spec: NodeSpec) -> list[Step]:
        key, target = spec.key, spec.target
        if target.node_ids:
            ids = list(target.node_ids)
            return [Step("pinned", key, f"the node(s) named by the conversation: {ids}")]
        if spec.layer != "object":
            labels = self._label_values(spec)
            text = f"every {spec.layer}" + (f", scored against {labels}" if labels else "")
            steps = [Step("cypher", key, text, CYPHER_LAYER[spec.layer])]
            return [*steps, *self._text_steps(spec)]
        labels = self._label_values(spec)
        if labels:
            steps = [
                Step(
                    "cypher",
                    key,
                    f"objects labelled {labels}",
                    CYPHER_OBJECTS_BY_LABEL,
                    {"labels": labels},
                )
            ]
            return [*steps, *self._text_steps(spec)]
        if target.labels or target.function:  # named, but no map label matches the name
            return self._text_steps(spec)
        return [self._scope_step(spec), *self._text_steps(spec)]

    def _label_values(self, spec: NodeSpec) -> list[str]:
        """Map labels (objects) or node ids (rooms, areas) matching the positive label
        and function constraints."""
        keys: set[str] = set()
        for con in spec.constraints:
            if isinstance(con, LabelConstraint | FunctionConstraint) and not con.negated:
                keys |= set(spec.matches.get(con.id, {}))
        return sorted(keys)

    def _text_steps(self, spec: NodeSpec) -> list[Step]:
        phrase = spec.phrase
        if not phrase or spec.layer == "floor":
            return []
        return [
            Step(
                "vector",
                spec.key,
                f"nearest {spec.layer} texts to the phrase",
                index=VECTOR_INDEX[spec.layer],
                query_text=phrase,
                fallback=True,
            ),
            Step(
                "fulltext",
                spec.key,
                f"full-text match on {FULLTEXT_TABLE[spec.layer]}",
                index=FULLTEXT_TABLE[spec.layer],
                query_text=phrase,
                fallback=True,
            ),
        ]

    def _scope_step(self, spec: NodeSpec) -> Step:
        for con in spec.constraints:  # "something on the table": the landmark's neighbours
            if isinstance(con, RelationConstraint) and not con.negated and spec.layer == "object":
                return Step(
                    "neighbours",
                    spec.key,
                    f"objects joined by RELATION edges to (or within {NEAR_GAP} m of) the "
                    f"candidates of {spec.landmarks[con.id].key}",
                    CYPHER_RELATED_OBJECTS,
                    {"landmarks": f"<candidates of {spec.landmarks[con.id].key}>"},
                    constraint=con.id,
                )
        place = self._place_scope(spec)
        if place is not None:
            return place
        if spec.levels:
            floors = sorted(f for f, n in self.snap.floors.items() if n.level in spec.levels)
            return Step(
                "cypher",
                spec.key,
                f"objects on floors {floors}",
                CYPHER_OBJECTS_ON_FLOORS,
                {"floors": floors},
            )
        return Step("cypher", spec.key, "every object", CYPHER_ALL_OBJECTS)

    @staticmethod
    def _place_scope(spec: NodeSpec) -> Step | None:
        """The step selecting the objects of the rooms or areas the request names."""
        for con in spec.constraints:
            if con.negated:
                continue
            if isinstance(con, RoomConstraint) and spec.matches.get(con.id):
                rooms = sorted(spec.matches[con.id])
                return Step(
                    "cypher",
                    spec.key,
                    f"objects in rooms {rooms} (HAS_AREA/HAS_OBJECT)",
                    CYPHER_OBJECTS_IN_ROOMS,
                    {"rooms": rooms},
                )
            if isinstance(con, AreaConstraint) and spec.matches.get(con.id):
                areas = sorted(spec.matches[con.id])
                return Step(
                    "cypher",
                    spec.key,
                    f"objects in areas {areas} (HAS_OBJECT)",
                    CYPHER_OBJECTS_IN_AREAS,
                    {"areas": areas},
                )
        return None

    def _viewer_step(self, spec: NodeSpec) -> Step:
        fallback = (
            "the robot's pose when the request gives one, else the camera of the keyframe "
            "that saw most of the candidates, else the room's centre looking at them"
        )
        vp = spec.viewpoint
        if vp is None:
            return Step("viewer", spec.key, fallback)
        name = vp.landmark.target.describe()
        how = {
            "facing": f"stand behind the candidates and look towards the best {name}",
            "from": f"stand at the best {name} and look towards the candidates",
            "back_to": f"stand at the candidates with your back to the best {name}",
            "seated": f"sit on the best {name} and look the way it faces (into its room)",
        }[vp.kind]
        if vp.toward is not None and vp.kind in ("from", "seated"):
            seen = vp.toward.target.describe()
            how = (
                f"{'sit on' if vp.kind == 'seated' else 'stand at'} the best {name} and look "
                f"at the best {seen} (candidates of {VIEWPOINT_TOWARD}), else {how}"
            )
        return Step(
            "viewer",
            spec.key,
            f"{vp.kind.replace('_', ' ')} {name} (candidates of {VIEWPOINT}): "
            f"{how}; if no {name} is found, {fallback}",
        )

    def _constraint_step(self, spec: NodeSpec, con: Constraint) -> Step:
        what = describe(con)
        if isinstance(con, RelationConstraint):
            landmarks = [k for k in (con.id, f"{con.id}/2") if k in spec.landmarks]
            names = " and ".join(spec.landmarks[k].key for k in landmarks)
            if con.predicate in VIEW_PREDICATES and spec.layer == "object":
                how = (
                    f"compare box centres with the candidates of {names} as the viewer sees "
                    "them ('near' at half strength when no viewer can be formed)"
                )
            else:
                how = f"walk RELATION edges to candidates of {names} (box geometry where no edge)"
            return Step("relation", spec.key, f"{con.id} {what}: {how}", constraint=con.id)
        if isinstance(con, Superlative):
            how = "rank the best-scoring tier"
            if con.measure in ("ordinal", "middle"):
                how += " by position as the viewer sees it"
            elif con.measure in ("closest", "farthest") and con.landmark is None:
                how += " by distance from the viewer"
            return Step("superlative", spec.key, f"{con.id} {what}: {how}", constraint=con.id)
        if isinstance(con, PlacementConstraint):
            return Step(
                "placement",
                spec.key,
                f"{con.id} {what}: measure the footprint on its room's floor mask "
                "(distance to the walls / to the centre)",
                constraint=con.id,
            )
        found = spec.matches.get(con.id)
        detail = ""
        if found:
            best = sorted(found.items(), key=lambda kv: -kv[1][0])[:6]
            detail = "; matches " + ", ".join(f"{k} ({s:.2f})" for k, (s, _) in best)
        if isinstance(con, RoomConstraint | AreaConstraint):
            return Step(
                "traverse",
                spec.key,
                f"{con.id} {what}: walk HAS_OBJECT/HAS_AREA up to "
                f"the candidate's {con.kind}{detail}",
                constraint=con.id,
            )
        return Step(
            "traverse",
            spec.key,
            f"{con.id} {what}: compare with node properties{detail}",
            constraint=con.id,
        )
