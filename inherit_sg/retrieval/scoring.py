"""Intent-weighted scoring (paper §III-D): ``S(n) = H_floor · Σ_i p_i · w_i · Sim(n, c_i)``.

Every term is kept per candidate (:class:`Term`), so results and traces say why a node
ranks where it does. ``Sim`` per constraint kind:

- label / function: the map-label matches resolved by the plan (lexicon or embedding),
  or the vector / full-text evidence of the candidate step;
- attribute: the node's measured attributes (colour, material), size words relative to
  the median of the node's kind in the map (:mod:`inherit_sg.retrieval.sizes`), else
  its description; height words rank the candidates by box height;
- room / area: the candidate's room / area (found by walking HAS_* edges) against the
  rooms / areas the constraint matched;
- part (an attribute with key ``part``): :mod:`inherit_sg.retrieval.parts`;
- relation: the GraphRAG check of :mod:`inherit_sg.retrieval.graph_checks`, weighted by
  how well the landmark met its own constraints; ``left_of`` / ``right_of`` /
  ``in_front_of`` / ``behind`` are decided geometrically as the viewer sees them
  (:mod:`inherit_sg.retrieval.directions`, the viewer from
  :mod:`inherit_sg.retrieval.viewer`);
- placement: against a wall, in a corner, in the centre, measured on the room's floor
  mask (:mod:`inherit_sg.retrieval.placement`);
- superlative: rank within the best-scoring tier (largest by box volume with flat sides
  floored, tallest by box height; boxes seen in one view are left out when others can
  be compared; closest / farthest to the landmark, or to the viewer without one);
  ordinals and "the middle one" order the tier as the viewer sees it: left to right,
  by depth (front / back) or by distance from the viewer (no direction); the chosen
  one gets 1, the others ``ORDINAL_FALLOFF / (1 + |rank - k|)``;
- floor: the hard filter ``H_floor`` (all floors when nothing passes: global fallback).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from inherit_sg.model import ObjectNode, RoomNode
from inherit_sg.perception.colour_names import name_similarity
from inherit_sg.perception.describer import size_class
from inherit_sg.retrieval.candidates import Candidates
from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    Constraint,
    FunctionConstraint,
    LabelConstraint,
    PlacementConstraint,
    RelationConstraint,
    Superlative,
)
from inherit_sg.retrieval.directions import VIEW_PREDICATES, directional_all
from inherit_sg.retrieval.graph_checks import GraphChecker, Landmarks
from inherit_sg.retrieval.match import LABEL_SEMANTIC_MAX
from inherit_sg.retrieval.ordinals import place
from inherit_sg.retrieval.parts import part_sim
from inherit_sg.retrieval.placement import PlacementMeter
from inherit_sg.retrieval.plan import IMAGE_TERM, IMAGE_WEIGHT, VIEWPOINT, NodeSpec
from inherit_sg.retrieval.sizes import (
    linear_size,
    measured_in_views,
    robust_volume,
    size_word,
    size_word_sim,
)
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.retrieval.viewer import KeyframeViews, View, ViewerPose, ViewFinder

# Distance to a landmark, as "closest" measures it (ordinals counted from a landmark).
_AS_CLOSEST = Superlative(measure="closest")
# A label / function similarity at least this strong means "is what was named" (exact,
# a kind of it, a likely function kind), not merely "resembles it".
STRONG_MATCH = 0.5
# A label / function similarity at least this strong means the candidate surely is the
# kind asked for; when one on the allowed floors is, things that are not the kind at all
# (below STRONG_MATCH) rank after every candidate that is, whatever negations cost.
SURE_KIND = 0.9
# Candidates scoring within this of the best form the tier a superlative ranks.
SUPERLATIVE_TIER = 0.05
# "Closest to the front door" measures to the landmarks that match best: a landmark
# whose match is more than this below the best one's is left out (a plain door when
# the map knows the exterior door).
LANDMARK_TIER = 0.15
# People count and compare among the things in front of them: with a viewpoint set
# ("standing at the counter facing the bar, the stool on the left") only candidates in
# its landmark's room or within VIEW_REACH metres of it are ordered (when any is), and "the stool
# farthest from the dishwasher" compares the candidates in the landmark's room (within
# LANDMARK_REACH of it when it has none), when at least two are there.
VIEW_REACH = 2.0
LANDMARK_REACH = 5.0
# Superlatives measured on an object's box (compared only between well-observed boxes).
BOX_MEASURES = frozenset({"largest", "smallest", "tallest", "shortest", "widest", "narrowest"})
# Measures ranked from the top down ("the largest"); the others from the bottom up.
MAX_MEASURES = frozenset({"largest", "tallest", "highest", "widest", "farthest"})
# Ordinals and "the middle one": the chosen candidate scores 1, the others this much
# over (1 + their rank distance); of an even tier's two central ones, the one farther
# from the viewer scores MIDDLE_RUNNER_UP.
ORDINAL_FALLOFF = 0.5
MIDDLE_RUNNER_UP = 0.9
_WORD = re.compile(r"[a-z]+")


@dataclass
class Term:
    """One constraint's contribution ``p · w · Sim`` to a candidate's score."""

    cid: str
    kind: str
    weight: float
    polarity: int
    sim: float
    why: str = ""

    @property
    def value(self) -> float:
        """Signed contribution to the score."""
        return self.polarity * self.weight * self.sim

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return {
            "kind": self.kind,
            "weight": round(self.weight, 4),
            "polarity": self.polarity,
            "sim": round(self.sim, 4),
            "term": round(self.value, 4),
            "why": self.why,
        }


@dataclass
class Scored:
    """A candidate with its score terms."""

    id: str
    terms: dict[str, Term] = field(default_factory=dict)
    h_floor: int = 1
    found_by: list[str] = field(default_factory=list)

    @property
    def score(self) -> float:
        """``H_floor · Σ terms``."""
        return self.h_floor * sum(t.value for t in self.terms.values())

    def sim(self, kind: str) -> float:
        """Largest similarity among the positive terms of ``kind`` (0 when none)."""
        return max(
            (t.sim for t in self.terms.values() if t.kind == kind and t.polarity > 0), default=0.0
        )


def _named_sim(cand: Scored) -> float:
    """How well the candidate is what was named (best positive label / function sim)."""
    return max(
        (t.sim for t in cand.terms.values() if t.polarity > 0 and t.kind in ("label", "function")),
        default=0.0,
    )


def _rank_key(cand: Scored, seen: int = 0) -> tuple[float, float, int, str]:
    """Best score first; among equals, the better label / function match, then the one
    the map observed more often (``seen``: a surer detection, the main part of a thing
    mapped in pieces), then by id."""
    total, named = 0.0, 0.0
    for t in cand.terms.values():
        total += t.polarity * t.weight * t.sim
        if t.polarity > 0 and t.kind in ("label", "function"):
            named += t.sim
    return (-cand.h_floor * total, -named, -seen, cand.id)


def _kind_first(
    out: list[Scored], snap: MapSnapshot
) -> Callable[[Scored], tuple[int, float, float, int, str]]:
    """The sort key of a ranking: what is not the kind asked for ranks after what surely
    is ("not the toilet in the WC, the other toilet" answers a toilet, not a stool, even
    when every toilet is penalised), then by :func:`_rank_key`."""
    sure = any(c.h_floor and _named_sim(c) >= SURE_KIND for c in out)

    def key(cand: Scored) -> tuple[int, float, float, int, str]:
        other_kind = sure and bool(cand.h_floor) and _named_sim(cand) < STRONG_MATCH
        node = snap.node(cand.id)
        seen = node.observation_count if isinstance(node, ObjectNode) else 0
        return (int(other_kind), *_rank_key(cand, seen))

    return key


def _words(text: str) -> set[str]:
    return set(_WORD.findall(text.lower()))


# Attributes the mapping measures on objects when the pixels allow it; an object without
# a value scores this much (a measured mismatch scores 0).
OBSERVABLE = frozenset({"colour", "material"})
UNKNOWN_SIM = 0.35


def attribute_sim(snap: MapSnapshot, node_id: str, con: AttributeConstraint) -> tuple[float, str]:
    """Sim of one attribute constraint from measured attributes, else the description."""
    node = snap.node(node_id)
    value = con.value.lower()
    text = ""
    if con.key == "part":
        attrs = node.attributes if isinstance(node, ObjectNode) else {}
        desc = node.description if isinstance(node, ObjectNode) else getattr(node, "summary", "")
        sim, why = part_sim(value, desc, attrs)
        return (UNKNOWN_SIM if sim is None else sim), why
    if isinstance(node, ObjectNode):
        have = node.attributes.get(con.key)
        if isinstance(have, str) and have and have.lower() != "unknown":
            seen = have.lower()
            if con.key == "colour" and seen != value:
                # neighbouring names share part of the credit: colour naming is a guess
                near = name_similarity(seen, value)
                return near, f"colour is {seen}" + (f", close to {value}" if near else "")
            return (1.0 if seen == value else 0.0), f"{con.key} is {seen}"
        if con.key == "size" and (ref := snap.kind_sizes.get(node.label.lower())):
            # size words are relative to the kind: compare with the map's others
            ratio = linear_size(node) / ref
            why = f"{size_word(ratio)} for a {node.label.lower()} ({ratio:.2f} × the median)"
            return size_word_sim(ratio, value), why
        text = node.description
    elif node is not None:
        text = getattr(node, "summary", "")
    if value in _words(text):
        return 1.0, f"description mentions '{value}'"
    if con.key == "size" and isinstance(node, ObjectNode):
        have = size_class(tuple(float(v) for v in node.bbox.size))  # type: ignore[arg-type]
        return (1.0 if have == value else 0.0), f"box size is {have}"
    if con.key in OBSERVABLE and isinstance(node, ObjectNode):
        # not measured is not a mismatch: rank it between a match and a contradiction
        return UNKNOWN_SIM, f"{con.key} not observed"
    return 0.0, f"no {con.key} '{value}' known"


class _Viewing:
    """The views of one scoring of a spec, with a trace line per use."""

    def __init__(self, finder: ViewFinder, spec_key: str, notes: list[str]) -> None:
        self.finder = finder
        self.spec_key = spec_key
        self.notes = notes
        self._said: set[tuple[str, str]] = set()

    def view(self, group: list[str], cid: str) -> View | None:
        """The view for ranking ``group`` for constraint ``cid`` (traced once)."""
        found = self.finder.view(group)
        if found is not None and (found.why, cid) not in self._said:
            self._said.add((found.why, cid))
            self.notes.append(f"viewer: {found.why} (for {self.spec_key} {cid})")
        return found


class Scorer:
    """Scores candidates of a spec against a snapshot.

    ``robot`` is the viewer's pose sent with the request, ``keyframes`` the SEEN_IN
    index and keyframe poses of the snapshot (the viewer "as the robot saw them"), and
    ``placement`` the snapshot's room fields; each is optional (a scorer without
    ``keyframes`` skips that source; ``placement`` is made on first use)."""

    def __init__(
        self,
        snap: MapSnapshot,
        checker: GraphChecker,
        *,
        robot: ViewerPose | None = None,
        keyframes: KeyframeViews | None = None,
        placement: PlacementMeter | None = None,
    ) -> None:
        self.snap = snap
        self.checker = checker
        self.robot = robot
        self.keyframes = keyframes
        self._placement = placement

    @property
    def placement(self) -> PlacementMeter:
        """The placement meter (made on first use when none was given)."""
        if self._placement is None:
            self._placement = PlacementMeter(self.snap)
        return self._placement

    def score(
        self, spec: NodeSpec, cands: Candidates, landmarks: dict[str, Landmarks]
    ) -> tuple[list[Scored], list[str]]:
        """Ranked candidates of ``spec`` and notes for the trace."""
        notes: list[str] = []
        finder = ViewFinder(
            self.snap,
            viewpoint=spec.viewpoint,
            viewpoint_marks=landmarks.get(VIEWPOINT, ()) if spec.viewpoint is not None else (),
            robot=self.robot,
            keyframes=self.keyframes,
        )
        viewing = _Viewing(finder, spec.key, notes)
        out = [Scored(i, found_by=how) for i, how in cands.found_by.items()]
        scored = [c for c in spec.scored() if not isinstance(c, Superlative)]
        for cand in out:
            for con in scored:
                if isinstance(con, RelationConstraint):
                    sim, why = 0.0, ""
                else:
                    sim, why = self._sim(spec, con, cand.id, cands)
                cand.terms[con.id] = Term(con.id, con.kind, con.weight, con.polarity, sim, why)
            if spec.image is not None:
                sim = cands.visual_sim.get(cand.id, 0.0)
                why = f"appearance similarity {sim:.2f}"
                cand.terms[IMAGE_TERM] = Term(IMAGE_TERM, "visual", IMAGE_WEIGHT, 1, sim, why)
        spatial = self._relations(spec, out, landmarks, viewing)
        for cand in out:
            for cid, found in spatial.items():
                term = cand.terms[cid]
                term.sim, term.why = found.get(cand.id, (0.0, ""))
        self._heights(spec, out)
        self._floor(spec, out, notes)
        for sup in spec.scored():
            if isinstance(sup, Superlative):
                self._superlative(sup, out, landmarks.get(sup.id, ()), notes, viewing)
        out.sort(key=_kind_first(out, self.snap))
        return out, notes

    def _leading(self, spec: NodeSpec, out: list[Scored]) -> list[str]:
        """The candidates that lead on everything but relations (on the allowed floors
        when any is there): the group a viewer-relative relation is seen for."""
        live = out
        if spec.levels is not None:
            live = [c for c in out if self.snap.level_of(c.id) in spec.levels] or out
        partial = {c.id: sum(t.value for t in c.terms.values()) for c in live}
        if not partial:
            return []
        best = max(partial.values())
        return [i for i, v in partial.items() if v >= best - SUPERLATIVE_TIER]

    # ------------------------------------------------------------- per kind
    def _sim(
        self,
        spec: NodeSpec,
        con: Constraint,
        node_id: str,
        cands: Candidates,
    ) -> tuple[float, str]:
        snap = self.snap
        if isinstance(con, LabelConstraint | FunctionConstraint):
            node = snap.node(node_id)
            key = node.label if isinstance(node, ObjectNode) else node_id
            sim, why = spec.matches.get(con.id, {}).get(key, (0.0, ""))
            text = cands.text_sim.get(node_id, 0.0) * LABEL_SEMANTIC_MAX
            if text > sim and not con.negated:
                return text, "found by text search"
            return sim, why or f"label '{getattr(node, 'label', '')}' does not match"
        if con.kind in ("room", "area"):
            place = (snap.room_of if con.kind == "room" else snap.area_of).get(node_id)
            if place is None:
                return 0.0, f"not in any {con.kind}"
            hit = spec.matches.get(con.id, {}).get(place)
            if hit is not None:
                return hit
            node = snap.rooms.get(place) or snap.areas.get(place)
            return 0.0, f"in {place} ({node.label if node is not None else '?'})"
        if isinstance(con, AttributeConstraint):
            return attribute_sim(snap, node_id, con)
        if isinstance(con, PlacementConstraint):
            measured, why = self.placement.sim(node_id, con.where)
            return (UNKNOWN_SIM if measured is None else measured), why
        return 0.0, f"{con.kind} is not scored"

    def _relations(
        self,
        spec: NodeSpec,
        out: list[Scored],
        landmarks: dict[str, Landmarks],
        viewing: _Viewing,
    ) -> dict[str, dict[str, tuple[float, str]]]:
        """GraphRAG checks of every relation constraint for all candidates at once;
        viewer-relative predicates are decided geometrically when a viewer can be
        formed (else approximated by 'near', as the checker does)."""
        ids = [c.id for c in out]
        found: dict[str, dict[str, tuple[float, str]]] = {}
        for con in spec.scored():
            if not isinstance(con, RelationConstraint):
                continue
            first = landmarks.get(con.id, ())
            if con.predicate == "between":
                second = landmarks.get(f"{con.id}/2", ())
                found[con.id] = self.checker.between_all(ids, first, second)
                continue
            view = None
            if con.predicate in VIEW_PREDICATES and spec.layer == "object":
                view = viewing.view(self._leading(spec, out), con.id)
            if view is not None:
                found[con.id] = directional_all(self.snap, view, ids, con.predicate, first)
            else:
                held = self.checker.relation_all(ids, con.predicate, first)
                # partial credit for being close counts only the best landmarks: near
                # the front door, not near any door that might be it
                top = set(best_landmarks(first))
                marks = [(lid, q) for lid, q in first if lid in top]
                near = self.checker.proximity_all([i for i in ids if i not in held], marks)
                found[con.id] = {**near, **held}
        return found

    def _heights(self, spec: NodeSpec, out: list[Scored]) -> None:
        """Height words without a stated height: rank candidates by box height."""
        if not any(isinstance(c, AttributeConstraint) and c.key == "height" for c in spec.scored()):
            return
        heights = {c.id: self._height(c.id) for c in out}
        known = [h for h in heights.values() if h is not None]
        if not known:
            return
        lo, hi = min(known), max(known)
        for con in spec.scored():
            if not (isinstance(con, AttributeConstraint) and con.key == "height"):
                continue
            for cand in out:
                term, h = cand.terms[con.id], heights[cand.id]
                if term.sim > 0.0 or h is None:
                    continue
                rel = 1.0 if hi - lo < 1e-6 else (h - lo) / (hi - lo)
                term.sim = rel if con.value == "tall" else 1.0 - rel
                term.why = f"box height {h:.2f} m among {lo:.2f}–{hi:.2f} m"

    def _height(self, node_id: str) -> float | None:
        node = self.snap.node(node_id)
        return float(node.bbox.size[2]) if isinstance(node, ObjectNode) else None

    def _floor(self, spec: NodeSpec, out: list[Scored], notes: list[str]) -> None:
        """Apply H_floor. When no candidate on the allowed floors matches (is what was
        named — a strong label or function match — or, for unnamed targets, scores
        above zero) but candidates elsewhere do, the filter is lifted: the global
        fallback."""
        if spec.levels is None:
            return
        for cand in out:
            cand.h_floor = int(self.snap.level_of(cand.id) in spec.levels)
        named = any(c.kind in ("label", "function") and not c.negated for c in spec.scored())

        def matches(c: Scored) -> bool:
            return _named_sim(c) >= STRONG_MATCH if named else c.score > 0.0

        if any(matches(c) for c in out if c.h_floor) or not any(matches(c) for c in out):
            return
        for cand in out:
            cand.h_floor = 1
        notes.append(
            f"{spec.key}: nothing matching on levels {sorted(spec.levels)}; "
            "floor filter lifted (global fallback)"
        )

    # ---------------------------------------------------------- superlative
    def _measure(
        self,
        con: Superlative,
        node_id: str,
        landmarks: Landmarks,
        viewer: tuple[float, float] | None = None,
    ) -> float | None:
        node = self.snap.node(node_id)
        if con.measure in ("largest", "smallest"):
            if isinstance(node, ObjectNode):
                return robust_volume(node.bbox.size)
            if isinstance(node, RoomNode) and node.mask is not None:
                return node.mask.area_m2
            return None
        if con.measure in ("tallest", "shortest"):
            return self._height(node_id)
        if con.measure in ("highest", "lowest"):
            # how high it sits above its storey's floor ("the picture hung highest")
            here = self.snap.position(node_id)
            base = self.snap.floor_height(node_id)
            return here[2] - base if here is not None else None
        if con.measure in ("widest", "narrowest"):
            return float(max(node.bbox.size[:2])) if isinstance(node, ObjectNode) else None
        if con.measure in ("closest", "farthest") and landmarks:
            here = self.snap.position(node_id)
            dists = [
                math.dist(here, there)
                for lid in best_landmarks(landmarks)
                if lid != node_id and here is not None and (there := self.snap.position(lid))
            ]
            return min(dists) if dists else None
        if con.measure in ("closest", "farthest") and viewer is not None:
            here = self.snap.position(node_id)
            return math.dist(here[:2], viewer) if here is not None else None
        return None

    def _measured_boxes(self, con: Superlative, tier: list[Scored]) -> list[Scored]:
        """The tier without objects whose box comes from a single view (often a sliver
        of a larger object), unless nothing better measured is left to compare."""
        kept: list[Scored] = []
        single: list[Scored] = []
        for cand in tier:
            node = self.snap.node(cand.id)
            measured = not isinstance(node, ObjectNode) or measured_in_views(node)
            (kept if measured else single).append(cand)
        if not kept:
            return tier
        for cand in single:
            cand.terms[con.id].why = f"{con.measure}: box seen in one view only, not compared"
        return kept

    def _superlative(
        self,
        con: Superlative,
        out: list[Scored],
        landmarks: Landmarks,
        notes: list[str],
        viewing: _Viewing,
    ) -> None:
        for cand in out:
            cand.terms[con.id] = Term(con.id, con.kind, con.weight, con.polarity, 0.0, "")
        live = [c for c in out if c.h_floor]
        if not live:
            return
        best = max(c.score for c in live)
        tier = [c for c in live if c.score >= best - SUPERLATIVE_TIER]
        if con.measure in ("ordinal", "middle"):
            self._by_position(
                con, self._near_viewpoint(con, tier, notes, viewing), landmarks, notes, viewing
            )
            return
        if con.measure == "farthest" and landmarks:
            tier = self._near_landmarks(con, tier, landmarks, notes)
        if con.measure in BOX_MEASURES:
            tier = self._measured_boxes(con, tier)
        viewer = None
        if con.measure in ("closest", "farthest") and con.landmark is None:
            view = viewing.view([c.id for c in tier], con.id)
            viewer = view.position if view is not None else None
        values = {c.id: self._measure(con, c.id, landmarks, viewer) for c in tier}
        known = {k: v for k, v in values.items() if v is not None}
        if not known:
            notes.append(f"{con.id}: cannot rank by '{con.measure}' here (no measure known)")
            return
        want_max = con.measure in MAX_MEASURES
        top = max(known.values()) if want_max else min(known.values())
        for cand in tier:
            v = known.get(cand.id)
            if v is None:
                continue
            ratio = (v / top if top > 0 else 1.0) if want_max else (top / v if v > 0 else 1.0)
            cand.terms[con.id].sim = float(min(1.0, ratio)) if v != top else 1.0
            cand.terms[con.id].why = f"{con.measure}: {v:.3g} (best {top:.3g})"

    def _near_viewpoint(
        self, con: Superlative, tier: list[Scored], notes: list[str], viewing: _Viewing
    ) -> list[Scored]:
        """With a viewpoint set, the candidates in the room of the landmark the viewer
        stands at or faces, or within :data:`VIEW_REACH` of it (all of them without one,
        or when none is there)."""
        if viewing.finder.viewpoint is None or len(tier) < 2:
            return tier
        view = viewing.view([c.id for c in tier], con.id)
        anchor = view.anchor if view is not None else None
        spot = self.snap.position(anchor) if anchor else None
        if anchor is None or spot is None:
            return tier
        room = self.snap.room_of.get(anchor)
        near = [
            c
            for c in tier
            if (room is not None and self.snap.room_of.get(c.id) == room)
            or (
                (here := self.snap.position(c.id)) is not None
                and math.dist(here[:2], spot[:2]) <= VIEW_REACH
            )
        ]
        return _compared(
            con, tier, near, 1, notes,
            left_out="out of the viewpoint's room: not ordered",
            note=f"the {len(near)} of {len(tier)} candidates in the viewpoint's room are ordered",
        )  # fmt: skip

    def _near_landmarks(
        self, con: Superlative, tier: list[Scored], landmarks: Landmarks, notes: list[str]
    ) -> list[Scored]:
        """The candidates in the room of a best-matching landmark (within
        :data:`LANDMARK_REACH` of one when the landmarks have no room); all of them when
        fewer than two are."""
        marks = best_landmarks(landmarks)
        rooms = {self.snap.room_of.get(lid) for lid in marks} - {None}
        spots = [p for lid in marks if (p := self.snap.position(lid)) is not None]

        def near(cid: str) -> bool:
            if rooms:
                return self.snap.room_of.get(cid) in rooms
            here = self.snap.position(cid)
            return here is not None and any(
                math.dist(here[:2], p[:2]) <= LANDMARK_REACH for p in spots
            )

        kept = [c for c in tier if near(c.id)]
        return _compared(
            con, tier, kept, 2, notes,
            left_out="far from the landmark: not compared",
            note=f"{len(kept)} of {len(tier)} candidates near the landmark are compared",
        )  # fmt: skip

    def _by_position(
        self,
        con: Superlative,
        tier: list[Scored],
        landmarks: Landmarks,
        notes: list[str],
        viewing: _Viewing,
    ) -> None:
        """Ordinals and "the middle one": order the tier as the viewer sees it."""
        placed = [(c, p) for c in tier if (p := self.snap.position(c.id)) is not None]
        view = viewing.view([c.id for c, _ in placed], con.id) if placed else None
        if view is None:
            notes.append(f"{con.id}: cannot order the candidates (no position known)")
            return
        ids = [c.id for c, _ in placed]
        xy = np.array([p[:2] for _, p in placed], dtype=float).reshape(-1, 2)
        landmark_dist = None
        if con.landmark is not None and con.direction is None:
            if not landmarks:
                notes.append(f"{con.id}: no landmark to count from; counting from the viewer")
            else:
                landmark_dist = np.array(
                    [self._measure(_AS_CLOSEST, i, landmarks) or math.inf for i in ids]
                )
        ranked = place(
            con,
            ids,
            xy,
            view,
            landmark_dist=landmark_dist,
            falloff=ORDINAL_FALLOFF,
            runner_up=MIDDLE_RUNNER_UP,
        )
        if ranked.note:
            notes.append(ranked.note)
        for (cand, _), sim, why in zip(placed, ranked.sims, ranked.whys, strict=True):
            cand.terms[con.id].sim = sim
            cand.terms[con.id].why = why


def best_landmarks(landmarks: Landmarks) -> list[str]:
    """The landmark ids whose quality is within :data:`LANDMARK_TIER` of the best."""
    top = max((q for _, q in landmarks), default=0.0) - LANDMARK_TIER
    return [lid for lid, q in landmarks if q >= top]


def _compared(
    con: Superlative,
    tier: list[Scored],
    kept: list[Scored],
    fewest: int,
    notes: list[str],
    *,
    left_out: str,
    note: str,
) -> list[Scored]:
    """``kept`` as the candidates a superlative compares, when at least ``fewest`` of
    ``tier`` are in it and some are not (the others' terms say ``left_out``, the trace
    ``note``); else the whole tier."""
    if len(kept) < fewest or len(kept) == len(tier):
        return tier
    for cand in tier:
        if cand not in kept:
            cand.terms[con.id].why = left_out
    notes.append(f"{con.id}: {note}")
    return kept


def landmark_quality(spec: NodeSpec, ranked: list[Scored], limit: int = 50) -> Landmarks:
    """Landmark candidates with quality ``S(n) / max S`` in (0, 1], best first."""
    top = spec.max_score()
    out = [(c.id, min(1.0, c.score / top)) for c in ranked if c.h_floor and c.score > 0.0]
    return out[:limit]
