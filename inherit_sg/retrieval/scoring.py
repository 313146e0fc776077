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

import itertools
import math
import re
from collections.abc import Callable, Iterable, Sequence

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
    RoomConstraint,
    Superlative,
)
from inherit_sg.retrieval.directions import VIEW_PREDICATES, directional_all
from inherit_sg.retrieval.graph_checks import GraphChecker, Landmarks
from inherit_sg.retrieval.match import LABEL_SEMANTIC_MAX
from inherit_sg.retrieval.ordinals import place
from inherit_sg.retrieval.parts import part_sim
from inherit_sg.retrieval.placement import PlacementMeter
from inherit_sg.retrieval.plan import (
    IMAGE_TERM,
    IMAGE_WEIGHT,
    VIEWPOINT,
    VIEWPOINT_TOWARD,
    NodeSpec,
)
from inherit_sg.retrieval.score_table import RankedRows, ScoreTable
from inherit_sg.retrieval.scored import Scored
from inherit_sg.retrieval.scored import Term as Term  # re-exported: callers import it here
from inherit_sg.retrieval.sizes import (
    bulk,
    linear_size,
    measured_in_views,
    size_word,
    size_word_sim,
)
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.retrieval.viewer import KeyframeViews, View, ViewerPose, ViewFinder

# Share of the distance to a landmark's centre added to the distance to its box, when
# "closest" / "farthest" measure from an object landmark.
CENTRE_SHARE = 0.1
# Distance to a landmark, as "closest" measures it (ordinals counted from a landmark).
_AS_CLOSEST = Superlative(measure="closest")
# A label / function similarity at least this strong means "is what was named" (exact,
# a kind of it, a likely function kind), not merely "resembles it".
STRONG_MATCH = 0.5
# share of a room's similarity that an object standing in a doorway gets from the room
# on the doorway's other side (see MapSnapshot.doorway_rooms)
DOORWAY_SHARE = 0.9
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
MAX_MEASURES = frozenset({"largest", "tallest", "highest", "widest", "farthest", "most"})
# Ordinals and "the middle one": the chosen candidate scores 1, the others this much
# over (1 + their rank distance); of an even tier's two central ones, the one farther
# from the viewer scores MIDDLE_RUNNER_UP.
ORDINAL_FALLOFF = 0.5
MIDDLE_RUNNER_UP = 0.9
_WORD = re.compile(r"[a-z]+")


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
# a value scores this much (a measured mismatch scores 0, a neighbouring colour name part
# of a match).
OBSERVABLE = frozenset({"colour", "material"})
UNKNOWN_SIM = 0.35
# A material read from texture is a weak cue (on generated house 811, 52 of the 123
# materials the map set were wrong; paper reads as plastic, fabric as wood): a mismatch
# ranks below "not observed", but it is no contradiction.
MATERIAL_MISMATCH_SIM = 0.15


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
            if con.key == "material" and seen != value:
                return MATERIAL_MISMATCH_SIM, f"material is {seen}"
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
        # no peers of its kind to compare with: "small" is relative to the kind ("a small
        # toilet" is a medium-sized box), so the absolute box size may confirm a size
        # word but not contradict it
        have = size_class(tuple(float(v) for v in node.bbox.size))  # type: ignore[arg-type]
        if have == value:
            return 1.0, f"box size is {have}"
        return UNKNOWN_SIM, f"box size is {have}; no other {node.label.lower()} to compare with"
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
    ) -> tuple[Sequence[Scored], list[str]]:
        """Ranked candidates of ``spec`` and notes for the trace (a read-only sequence
        whose candidates are made when read)."""
        notes: list[str] = []
        finder = ViewFinder(
            self.snap,
            viewpoint=spec.viewpoint,
            viewpoint_marks=landmarks.get(VIEWPOINT, ()) if spec.viewpoint is not None else (),
            toward_marks=landmarks.get(VIEWPOINT_TOWARD, ()) if spec.viewpoint is not None else (),
            robot=self.robot,
            keyframes=self.keyframes,
        )
        viewing = _Viewing(finder, spec.key, notes)
        table = ScoreTable(list(cands.found_by), list(cands.found_by.values()))
        for con in spec.scored():
            if isinstance(con, RelationConstraint):
                table.add(con)
            elif not isinstance(con, Superlative):
                sims, whys = self._column(spec, con, table, cands)
                table.add(con, sims, whys)
        if spec.image is not None:
            sims = [cands.visual_sim.get(i, 0.0) for i in table.ids]
            whys = [f"appearance similarity {sim:.2f}" for sim in sims]
            table.add_term(IMAGE_TERM, "visual", IMAGE_WEIGHT, 1, sims, whys)
        for cid, found in self._relations(spec, table, landmarks, viewing).items():
            table.set(cid, found)
        self._heights(spec, table)
        self._floor(spec, table, notes)
        roomed = any(isinstance(c, RoomConstraint) and not c.negated for c in spec.scored())
        for sup in spec.scored():
            if isinstance(sup, Superlative):
                self._superlative(
                    sup, table, landmarks.get(sup.id, ()), notes, viewing, in_view=not roomed
                )
        return table.ranked(self._order(table)), notes

    def _order(self, table: ScoreTable) -> np.ndarray:
        """Row order of the ranking: what is not the kind asked for after what surely
        is (see :func:`_kind_first`), then best score, best label / function match, most
        observations and id (:func:`_rank_key`)."""
        live = table.h_floor != 0
        named = table.named_best()
        other = np.zeros(len(table), dtype=bool)
        if np.any(live & (named >= SURE_KIND)):
            other = live & (named < STRONG_MATCH)
        keys = self._seen_and_rank(table)
        return np.lexsort((*keys, -table.named_sum(), -table.scores(), other))

    def _seen_and_rank(self, table: ScoreTable) -> tuple[np.ndarray, np.ndarray]:
        """The last two sort keys per row: the id's sorted position, and minus the
        observation count (0 for nodes that are no objects)."""
        snap = self.snap
        rows = self._object_rows(table)
        if rows is not None:
            seen, rank = snap.memo("object_seen_and_rank", lambda: _object_seen_and_rank(snap))
            return rank[rows], -seen[rows]
        ranks = snap.memo("id_rank", lambda: _id_ranks(snap))
        ids = np.fromiter((ranks[i] for i in table.ids), dtype=np.int64, count=len(table))
        objs = snap.objects
        seen_list = [
            o.observation_count if (o := objs.get(i)) is not None else 0 for i in table.ids
        ]
        return ids, -np.asarray(seen_list, dtype=np.int64)

    def _object_rows(self, table: ScoreTable) -> np.ndarray | None:
        """Snapshot object rows of the table's candidates (None unless all are objects;
        worked out once per table)."""
        if table.obj_rows is None:
            index = self.snap.obj_index
            table.obj_rows = np.fromiter(
                (index.get(i, -1) for i in table.ids), dtype=np.int64, count=len(table)
            )
        rows = table.obj_rows
        return rows if not len(rows) or rows.min() >= 0 else None

    def _leading(self, spec: NodeSpec, table: ScoreTable) -> list[str]:
        """The candidates that lead on everything but relations (on the allowed floors
        when any is there): the group a viewer-relative relation is seen for."""
        rows = np.arange(len(table))
        if spec.levels is not None:
            allowed = np.flatnonzero(self._on_levels(spec.levels, table))
            rows = allowed if len(allowed) else rows
        if not len(rows):
            return []
        partial = table.totals()[rows]
        best = partial.max()
        return [
            table.ids[r] for r, v in zip(rows, partial, strict=True) if v >= best - SUPERLATIVE_TIER
        ]

    def _on_levels(self, levels: frozenset[int], table: ScoreTable) -> np.ndarray:
        """Whether each row's floor level is one of ``levels``."""
        rows = self._object_rows(table)
        if rows is not None:  # objects: the snapshot's level column (-1: unknown, never allowed)
            return np.isin(self.snap.level[rows], np.fromiter(levels, dtype=int))
        level_of = self.snap.level_of
        return np.fromiter((level_of(i) in levels for i in table.ids), dtype=bool, count=len(table))

    # ------------------------------------------------------------- per kind
    def _column(
        self, spec: NodeSpec, con: Constraint, table: ScoreTable, cands: Candidates
    ) -> tuple[Iterable[float], list[str]]:
        """Sim and reason of ``con`` for every row of ``table``. Label, function, room
        and area terms depend only on the candidate's label / place: each distinct one
        is worked out once (for objects, through the snapshot's code columns)."""
        snap = self.snap
        rows = self._object_rows(table)
        if isinstance(con, LabelConstraint | FunctionConstraint):
            if rows is not None and not cands.text_sim:
                labels, codes = snap.memo("label_codes", lambda: _codes(snap, "label"))
                return _by_code(
                    rows, codes, labels, lambda k: self._label_sim(spec, con, k, k, 0.0)
                )
            objs = snap.objects
            pairs = [
                (o.label, o.label)
                if (o := objs.get(i)) is not None
                else (i, getattr(snap.node(i), "label", ""))
                for i in table.ids
            ]
            texts = cands.text_sim
            found = [
                self._label_sim(spec, con, key, label, texts.get(i, 0.0))
                for i, (key, label) in zip(table.ids, pairs, strict=True)
            ]
        elif con.kind in ("room", "area"):
            if rows is not None:
                places, codes = snap.memo(("place_codes", con.kind), lambda: _codes(snap, con.kind))
                return _by_code(rows, codes, places, lambda k: self._place_sim(spec, con, k))
            keys = [snap.place_key(i, con.kind) for i in table.ids]
            found = self._by_key(keys, lambda k: self._place_sim(spec, con, k))
        else:
            found = [self._sim(spec, con, i, cands) for i in table.ids]
        return [s for s, _ in found], [w for _, w in found]

    @staticmethod
    def _by_key(
        keys: list[str], make: Callable[[str], tuple[float, str]]
    ) -> list[tuple[float, str]]:
        cache: dict[str, tuple[float, str]] = {}
        out = []
        for key in keys:
            hit = cache.get(key)
            if hit is None:
                hit = cache[key] = make(key)
            out.append(hit)
        return out

    @staticmethod
    def _label_sim(
        spec: NodeSpec, con: Constraint, key: str, label: str, text_sim: float
    ) -> tuple[float, str]:
        """Label / function sim of a node (``key``: its label, or its id when it is no
        object; ``label``: its label), or the text evidence of the candidate steps
        when that is stronger."""
        sim, why = spec.matches.get(con.id, {}).get(key, (0.0, ""))
        text = text_sim * LABEL_SEMANTIC_MAX
        if text > sim and not con.negated:
            return text, "found by text search"
        return sim, why or f"label '{label}' does not match"

    def _place_sim(self, spec: NodeSpec, con: Constraint, place: str) -> tuple[float, str]:
        """Room / area sim of a node in ``place`` (empty: in none; ``own|other…``: in a
        doorway, see :meth:`MapSnapshot.place_key`). A doorway's other rooms count at
        :data:`DOORWAY_SHARE`, so that of two doors that match alike, the one mapped in
        the room asked for comes first."""
        if not place:
            return 0.0, f"not in any {con.kind}"
        if "|" in place:
            own, *others = place.split("|")
            best = self._place_sim(spec, con, own)
            for other in others:
                sim, why = self._place_sim(spec, con, other)
                if sim * DOORWAY_SHARE > best[0]:
                    best = (sim * DOORWAY_SHARE, f"in the doorway from {own} to {other}: {why}")
            return best
        hit = spec.matches.get(con.id, {}).get(place)
        if hit is not None:
            return hit
        node = self.snap.rooms.get(place) or self.snap.areas.get(place)
        return 0.0, f"in {place} ({node.label if node is not None else '?'})"

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
            label = getattr(node, "label", "")
            return self._label_sim(spec, con, key, label, cands.text_sim.get(node_id, 0.0))
        if con.kind in ("room", "area"):
            return self._place_sim(spec, con, snap.place_key(node_id, con.kind))
        if isinstance(con, AttributeConstraint):
            return attribute_sim(snap, node_id, con)
        if isinstance(con, PlacementConstraint):
            measured, why = self.placement.sim(node_id, con.where)
            return (UNKNOWN_SIM if measured is None else measured), why
        return 0.0, f"{con.kind} is not scored"

    def _relations(
        self,
        spec: NodeSpec,
        table: ScoreTable,
        landmarks: dict[str, Landmarks],
        viewing: _Viewing,
    ) -> dict[str, dict[str, tuple[float, str]]]:
        """GraphRAG checks of every relation constraint for all candidates at once;
        viewer-relative predicates are decided geometrically when a viewer can be
        formed (else approximated by 'near', as the checker does)."""
        ids = table.ids
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
                view = viewing.view(self._leading(spec, table), con.id)
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

    def _heights(self, spec: NodeSpec, table: ScoreTable) -> None:
        """Height words without a stated height: rank candidates by box height."""
        if not any(isinstance(c, AttributeConstraint) and c.key == "height" for c in spec.scored()):
            return
        heights = [self._height(i) for i in table.ids]
        known = [h for h in heights if h is not None]
        if not known:
            return
        lo, hi = min(known), max(known)
        for con in spec.scored():
            if not (isinstance(con, AttributeConstraint) and con.key == "height"):
                continue
            col = table.columns[con.id]
            for row, h in enumerate(heights):
                if col.sims[row] > 0.0 or h is None:
                    continue
                rel = 1.0 if hi - lo < 1e-6 else (h - lo) / (hi - lo)
                col.sims[row] = rel if con.value == "tall" else 1.0 - rel
                col.whys[row] = f"box height {h:.2f} m among {lo:.2f}–{hi:.2f} m"

    def _height(self, node_id: str) -> float | None:
        node = self.snap.node(node_id)
        return float(node.bbox.size[2]) if isinstance(node, ObjectNode) else None

    def _floor(self, spec: NodeSpec, table: ScoreTable, notes: list[str]) -> None:
        """Apply H_floor. When no candidate on the allowed floors matches (is what was
        named — a strong label or function match — or, for unnamed targets, scores
        above zero) but candidates elsewhere do, the filter is lifted: the global
        fallback."""
        if spec.levels is None:
            return
        table.h_floor = self._on_levels(spec.levels, table).astype(int)
        named = any(c.kind in ("label", "function") and not c.negated for c in spec.scored())
        matches = table.named_best() >= STRONG_MATCH if named else table.scores() > 0.0
        if np.any(matches & (table.h_floor != 0)) or not np.any(matches):
            return
        table.h_floor = np.ones(len(table), dtype=int)
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
                return bulk(node.bbox.size)
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
            if here is None:
                return None
            dists = [
                self._to_landmark(here, lid) for lid in best_landmarks(landmarks) if lid != node_id
            ]
            found = [d for d in dists if d is not None]
            return min(found) if found else None
        if con.measure in ("closest", "farthest") and viewer is not None:
            here = self.snap.position(node_id)
            return math.dist(here[:2], viewer) if here is not None else None
        if con.measure in ("most", "fewest") and landmarks:
            return float(len(self._counted(node_id, best_landmarks(landmarks))))
        return None

    def _to_landmark(self, here: Sequence[float], lid: str) -> float | None:
        """How far a point is from a landmark: from the landmark's box for an object (a
        long curtain or a sofa is near all along it), with a share of the distance to its
        centre to tell apart points inside or beside the box; to its position otherwise."""
        node = self.snap.node(lid)
        if isinstance(node, ObjectNode):
            lo, hi = np.asarray(node.bbox.min), np.asarray(node.bbox.max)
            point = np.asarray(here, dtype=float)
            edge = float(np.linalg.norm(point - np.clip(point, lo, hi)))
            return edge + CENTRE_SHARE * float(np.linalg.norm(point - node.bbox.center))
        there = self.snap.position(lid)
        return math.dist(here, there) if there is not None else None

    def _counted(self, node_id: str, things: list[str]) -> list[str]:
        """Which of ``things`` a node holds: a floor or room the things on it or in it, an
        area its members, an object those its stored relations join it to ("the books on
        the shelf") or that stand within reach of it."""
        snap = self.snap
        if node_id in snap.floors:
            return [t for t in things if snap.floor_of.get(t) == node_id and t != node_id]
        if node_id in snap.rooms or node_id in snap.areas:
            places = snap.room_of if node_id in snap.rooms else snap.area_of
            return [t for t in things if places.get(t) == node_id and t != node_id]
        joined = snap.adjacent.get(node_id, set())
        return [
            t
            for t in things
            if t != node_id and (t in joined or self.checker.holds(node_id, t, "near")[0])
        ]

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
        table: ScoreTable,
        landmarks: Landmarks,
        notes: list[str],
        viewing: _Viewing,
        *,
        in_view: bool = True,
    ) -> None:
        """Rank the best-scoring tier by ``con``'s measure: the tier's rows are worked
        on as :class:`Scored` s and their ``con`` terms written back to the table. With
        ``in_view`` (the request names no room), an ordinal seen from a viewpoint counts
        among the candidates in view of it before any others."""
        table.add(con)
        live = np.flatnonzero(table.h_floor != 0)
        if not len(live):
            return
        if in_view and con.measure in ("ordinal", "middle"):
            # "the little table on the left" seen from the bed: the tables in the bed's
            # room are the ones counted, however a table elsewhere scores
            seen = self._in_view(con, [table.ids[int(r)] for r in live], viewing)
            if seen:
                live = np.array([r for r in live if table.ids[int(r)] in seen], dtype=int)
        scores = table.scores(hints=False)[live]
        best = scores.max()
        rows = [int(r) for r, s in zip(live, scores, strict=True) if s >= best - SUPERLATIVE_TIER]
        tier = [table.scored(r) for r in rows]
        self._rank_tier(con, tier, landmarks, notes, viewing)
        table.write_back(con.id, rows, tier)

    def _rank_tier(
        self,
        con: Superlative,
        tier: list[Scored],
        landmarks: Landmarks,
        notes: list[str],
        viewing: _Viewing,
    ) -> None:
        """Set the ``con`` terms of the tier's candidates by its measure."""
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
        if len(tier) < 2:
            return tier
        seen = self._in_view(con, [c.id for c in tier], viewing)
        if seen is None:
            return tier
        near = [c for c in tier if c.id in seen]
        return _compared(
            con, tier, near, 1, notes,
            left_out="out of the viewpoint's room: not ordered",
            note=f"the {len(near)} of {len(tier)} candidates in the viewpoint's room are ordered",
        )  # fmt: skip

    def _in_view(self, con: Superlative, ids: list[str], viewing: _Viewing) -> set[str] | None:
        """Of ``ids``, those in the room of the landmark a viewpoint stands at or faces,
        or within :data:`VIEW_REACH` of it; None without a viewpoint landmark."""
        if viewing.finder.viewpoint is None or not ids:
            return None
        view = viewing.view(ids, con.id)
        anchor = view.anchor if view is not None else None
        spot = self.snap.position(anchor) if anchor else None
        if anchor is None or spot is None:
            return None
        room = self.snap.room_of.get(anchor)
        return {
            i
            for i in ids
            if (room is not None and self.snap.room_of.get(i) == room)
            or (
                (here := self.snap.position(i)) is not None
                and math.dist(here[:2], spot[:2]) <= VIEW_REACH
            )
        }

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


def _codes(snap: MapSnapshot, what: str) -> tuple[list[str], np.ndarray]:
    """The distinct labels (``what`` = ``label``) or rooms / areas (``room``, ``area``;
    ``""`` for none) of the snapshot's objects, and each object row's index into them."""
    if what == "label":
        values = [snap.objects[i].label for i in snap.obj_ids]
    else:
        values = [snap.place_key(i, what) for i in snap.obj_ids]
    names = list(dict.fromkeys(values))
    index = {name: k for k, name in enumerate(names)}
    return names, np.array([index[v] for v in values], dtype=np.int64).reshape(-1)


def _by_code(
    rows: np.ndarray,
    codes: np.ndarray,
    names: list[str],
    make: Callable[[str], tuple[float, str]],
) -> tuple[np.ndarray, list[str]]:
    """Sims and reasons of object ``rows`` by their code in ``codes`` (into ``names``):
    ``make`` runs once per distinct name present."""
    mine = codes[rows]
    sims = np.zeros(len(names))
    whys = [""] * len(names)
    for k in np.unique(mine).tolist():
        sims[k], whys[k] = make(names[k])
    return sims[mine], [whys[k] for k in mine.tolist()]


def _object_seen_and_rank(snap: MapSnapshot) -> tuple[np.ndarray, np.ndarray]:
    """Per snapshot object row: its observation count and its id's place in the sorted
    ids of all nodes."""
    ranks = _id_ranks(snap)
    seen = np.array([snap.objects[i].observation_count for i in snap.obj_ids], dtype=np.int64)
    return seen, np.array([ranks[i] for i in snap.obj_ids], dtype=np.int64)


def _id_ranks(snap: MapSnapshot) -> dict[str, int]:
    """Every node id of ``snap`` → its place in sorted order (the last tie-break of a
    ranking, as comparing the ids would give)."""
    ids = sorted({*snap.objects, *snap.rooms, *snap.areas, *snap.floors})
    return {node_id: i for i, node_id in enumerate(ids)}


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


# Landmark candidates kept for a landmark that asks nothing of its thing ("a table
# without anything on it"): each object found is one.
ANY_LANDMARKS = 2000


def landmark_quality(spec: NodeSpec, ranked: Sequence[Scored], limit: int = 50) -> Landmarks:
    """Landmark candidates with quality ``S(n) / max S`` in (0, 1], best first; for a
    landmark with nothing to score ("anything"), every candidate on its floor at 1."""
    if not spec.scored():
        return [
            (c.id, 1.0) for c in itertools.islice((c for c in ranked if c.h_floor), ANY_LANDMARKS)
        ]
    top = spec.max_score()
    if isinstance(ranked, RankedRows):
        kept = ranked.positive(limit)
    else:
        kept = [c for c in ranked if c.h_floor and c.score > 0.0][:limit]
    return [(c.id, min(1.0, c.score / top)) for c in kept]
