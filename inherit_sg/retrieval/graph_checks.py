"""GraphRAG spatial checks: does ``predicate(candidate, landmark)`` hold in the map?

The check walks the candidate's neighbourhood in the graph: RELATION edges to the
landmark's candidates (which were themselves scored against the landmark's nested
constraints, so chains resolve recursively), HAS_* edges when the landmark is a room or
an area. Where a pair of objects has no RELATION edge at all — maps imported from
elsewhere, pairs the mapping did not compare — the boxes are compared with the mapping's
own geometric rules (:func:`inherit_sg.mapping.relations.infer_relations`), so both
paths share one definition of "on", "next to", "near" ...

Stored predicates are ``on``, ``above``, ``inside``, ``next to`` and ``near``; the
request predicates map onto them (``under`` is the inverse of ``above``/``on``,
``supports`` the inverse of ``on``, ``contains`` the inverse of ``inside``; a book on
a bookshelf's shelf lies inside the shelf's box, so ``on`` accepts ``inside`` too).
``facing`` is approximated by ``near`` at half strength, and so are ``left_of``,
``right_of``, ``in_front_of`` and ``behind`` when no viewer can be formed (with one, the
scorer decides them geometrically: :mod:`inherit_sg.retrieval.directions`). ``between``
is geometric: the candidate's centre lies inside the segment joining one landmark of
each kind, close to it. A candidate that holds the relation with no landmark gets a
small credit for standing close to one (:meth:`GraphChecker.proximity_all`), so that
ties among unrelated candidates break by distance rather than by id.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from inherit_sg.mapping.relations import NEAR_GAP, infer_relations
from inherit_sg.model import AreaNode, RoomNode
from inherit_sg.retrieval.snapshot import MapSnapshot

# between: the two landmarks at most this far apart, the candidate's centre within this
# distance of the segment joining them.
BETWEEN_MAX_SPAN = 4.0
BETWEEN_BAND = 0.5
# Predicates answered only approximately (no viewpoint): near, at this strength.
APPROXIMATE = {"facing": 0.5, "in_front_of": 0.5, "behind": 0.5, "left_of": 0.5, "right_of": 0.5}

# request predicate -> (stored predicates candidate→landmark, stored landmark→candidate)
_EDGE_RULES: dict[str, tuple[frozenset[str], frozenset[str]]] = {
    "on": (frozenset({"on", "inside"}), frozenset()),
    "supports": (frozenset(), frozenset({"on", "inside"})),
    "above": (frozenset({"on", "above"}), frozenset()),
    "under": (frozenset(), frozenset({"on", "above"})),
    "next_to": (frozenset({"next to"}), frozenset({"next to"})),
    "near": (frozenset({"near", "next to"}), frozenset({"near", "next to"})),
    "inside": (frozenset({"inside"}), frozenset()),
    "contains": (frozenset(), frozenset({"inside"})),
    "with": (frozenset({"next to"}), frozenset({"on", "inside", "next to"})),
}

# A candidate for which a relation holds with no landmark still gets this much of the
# landmark's quality when it stands close to one, decaying with the gap between their
# footprints (PROXIMITY_SCALE metres): among lamps none of which the map relates to the
# nightstand, the one beside it ranks first. Far below a relation that holds.
PROXIMITY_MAX = 0.3
PROXIMITY_SCALE = 1.0
# How a proximity credit's reason opens (verification tells it from a relation that holds).
PROXIMITY_NOTE = "no relation found"
# Landmark candidates with their quality in [0, 1], best first.
Landmarks = Sequence[tuple[str, float]]


def footprint_gap(lo_a: np.ndarray, hi_a: np.ndarray, lo_b: np.ndarray, hi_b: np.ndarray) -> float:
    """Shortest horizontal distance between two boxes' footprints (0 when they meet)."""
    dx = max(0.0, lo_a[0] - hi_b[0], lo_b[0] - hi_a[0])
    dy = max(0.0, lo_a[1] - hi_b[1], lo_b[1] - hi_a[1])
    return math.hypot(dx, dy)


class GraphChecker:
    """Relation checks over one snapshot (pairs compared geometrically are cached)."""

    def __init__(self, snap: MapSnapshot) -> None:
        self.snap = snap
        self._pairs: dict[tuple[str, str], tuple[set[str], set[str]]] = {}

    # ------------------------------------------------------------------ pairs
    def predicates(self, a: str, b: str) -> tuple[set[str], set[str], str]:
        """Stored predicates a→b and b→a, and where they came from."""
        snap = self.snap
        if snap.has_edge_between(a, b):
            return snap.related(a, b), snap.related(b, a), "edge"
        if a not in snap.objects or b not in snap.objects:
            return set(), set(), "none"
        i, j = snap.obj_index[a], snap.obj_index[b]
        if footprint_gap(snap.lo[i], snap.hi[i], snap.lo[j], snap.hi[j]) > NEAR_GAP:
            return set(), set(), "geometry"
        key = (a, b) if a < b else (b, a)
        if key not in self._pairs:
            self._pairs[key] = self._geometry(key[0], key[1])
        fwd, back = self._pairs[key]
        return (fwd, back, "geometry") if key[0] == a else (back, fwd, "geometry")

    def _geometry(self, a: str, b: str) -> tuple[set[str], set[str]]:
        """Predicates a→b and b→a by the mapping's box rules. The mapping compares only
        objects of one room or of rooms joined by a door; here the pair is compared
        whatever rooms hold it ("near" is a distance), while "next to" still needs one
        room."""
        pair = [self.snap.objects[a], self.snap.objects[b]]
        rooms: dict[str, str | None] = {
            o.id: self.snap.room_of.get(o.id) or f"?{o.id}" for o in pair
        }
        ra, rb = rooms[a], rooms[b]
        assert ra is not None and rb is not None
        rels = infer_relations(pair, rooms, {ra: {rb}, rb: {ra}})
        return {r.predicate for r in rels if r.src == a}, {r.predicate for r in rels if r.src == b}

    def holds(self, a: str, b: str, predicate: str) -> tuple[bool, str]:
        """Whether ``predicate(a, b)`` holds, and the evidence in words."""
        snap = self.snap
        if a == b:
            return False, ""
        node_b = snap.node(b)
        node_a = snap.node(a)
        if isinstance(node_b, RoomNode | AreaNode) or isinstance(node_a, RoomNode | AreaNode):
            return self._hierarchy(a, b, predicate)
        rule = _EDGE_RULES.get("near" if predicate in APPROXIMATE else predicate)
        if rule is None:
            return False, ""
        out, back, source = self.predicates(a, b)
        fwd_hit = sorted(out & rule[0])
        back_hit = sorted(back & rule[1])
        if fwd_hit:
            return True, f"{a} -[{fwd_hit[0]}]-> {b} ({source})"
        if back_hit:
            return True, f"{b} -[{back_hit[0]}]-> {a} ({source})"
        return False, ""

    def _hierarchy(self, a: str, b: str, predicate: str) -> tuple[bool, str]:
        """Relations involving rooms or areas, answered by HAS_* membership."""
        snap = self.snap
        if isinstance(snap.node(b), RoomNode | AreaNode):
            inside_b = b in (snap.room_of.get(a), snap.area_of.get(a))
            if inside_b and predicate in ("inside", "near", "next_to", "with", "on"):
                return True, f"{a} is in {b} (HAS_*)"
            if predicate == "near" and self._distance(a, b) <= NEAR_GAP:
                return True, f"{a} is within {NEAR_GAP} m of {b}"
            return False, ""
        inside_a = a in (snap.room_of.get(b), snap.area_of.get(b))
        if inside_a and predicate in ("contains", "with", "near"):
            return True, f"{b} is in {a} (HAS_*)"
        return False, ""

    def _distance(self, a: str, b: str) -> float:
        pa, pb = self.snap.position(a), self.snap.position(b)
        if pa is None or pb is None:
            return math.inf
        return math.dist(pa[:2], pb[:2])

    # -------------------------------------------------------------- relations
    def relation(self, node: str, predicate: str, landmarks: Landmarks) -> tuple[float, str]:
        """Best landmark quality among landmarks ``predicate(node, ·)`` holds with."""
        return self.relation_all([node], predicate, landmarks).get(node, (0.0, ""))

    def _close_to(self, lid: str, nodes: list[str], rows: np.ndarray) -> set[str]:
        """Object ``nodes`` (snapshot rows ``rows``) whose footprints come within
        NEAR_GAP of landmark object ``lid``: every stored relation lies within it."""
        snap = self.snap
        j = snap.obj_index[lid]
        lo, hi = snap.lo[rows], snap.hi[rows]
        dx = np.maximum(0.0, np.maximum(lo[:, 0] - snap.hi[j, 0], snap.lo[j, 0] - hi[:, 0]))
        dy = np.maximum(0.0, np.maximum(lo[:, 1] - snap.hi[j, 1], snap.lo[j, 1] - hi[:, 1]))
        return {nodes[i] for i in np.flatnonzero(np.hypot(dx, dy) <= NEAR_GAP)}

    def relation_all(
        self, nodes: Sequence[str], predicate: str, landmarks: Landmarks
    ) -> dict[str, tuple[float, str]]:
        """:meth:`relation` for many nodes at once (only nodes that hold): landmark by
        landmark, best first, checking only the nodes joined to it by an edge or close
        enough to it for any relation."""
        snap = self.snap
        factor = APPROXIMATE.get(predicate, 1.0)
        note = " (approximated by 'near')" if predicate in APPROXIMATE else ""
        wanted = set(nodes)
        objs = [n for n in nodes if n in snap.obj_index]
        rows = np.array([snap.obj_index[n] for n in objs], dtype=int)
        others = [n for n in nodes if n not in snap.obj_index]
        out: dict[str, tuple[float, str]] = {}
        for lid, quality in landmarks:
            if len(out) == len(wanted):
                break
            if lid in snap.obj_index:
                todo = (snap.adjacent.get(lid, set()) & wanted) | set(others)
                if len(rows):
                    todo |= self._close_to(lid, objs, rows)
            else:  # a room or area landmark: membership or distance, node by node
                todo = set(nodes)
            for node in sorted(todo - out.keys()):
                ok, why = self.holds(node, lid, predicate)
                if ok:
                    out[node] = (quality * factor, why + note)
        return out

    def proximity_all(
        self, nodes: Sequence[str], landmarks: Landmarks
    ) -> dict[str, tuple[float, str]]:
        """Partial credit for object ``nodes`` near object landmarks:
        ``PROXIMITY_MAX * quality * exp(-gap / PROXIMITY_SCALE)`` for the best landmark,
        gap being the horizontal distance between the footprints; nothing for a landmark
        on another floor."""
        snap = self.snap
        objs = [n for n in nodes if n in snap.obj_index]
        marks = [(lid, q) for lid, q in landmarks if lid in snap.obj_index and q > 0.0]
        if not objs or not marks:
            return {}
        rows = np.array([snap.obj_index[n] for n in objs], dtype=int)
        lo, hi = snap.lo[rows], snap.hi[rows]
        best = np.zeros(len(objs))
        which = [""] * len(objs)
        gaps = np.full(len(objs), np.inf)
        for lid, quality in marks:
            j = snap.obj_index[lid]
            dx = np.maximum(0.0, np.maximum(lo[:, 0] - snap.hi[j, 0], snap.lo[j, 0] - hi[:, 0]))
            dy = np.maximum(0.0, np.maximum(lo[:, 1] - snap.hi[j, 1], snap.lo[j, 1] - hi[:, 1]))
            gap = np.hypot(dx, dy)
            credit = PROXIMITY_MAX * quality * np.exp(-gap / PROXIMITY_SCALE)
            credit[rows == j] = 0.0  # never its own landmark
            # a light upstairs is not near the TV right below it
            other_floor = (snap.level[rows] != snap.level[j]) & (snap.level[rows] >= 0)
            credit[other_floor & (snap.level[j] >= 0)] = 0.0
            better = credit > best
            best = np.where(better, credit, best)
            gaps = np.where(better, gap, gaps)
            for i in np.flatnonzero(better):
                which[i] = lid
        return {
            n: (float(best[i]), f"{PROXIMITY_NOTE}; {gaps[i]:.1f} m from {which[i]}")
            for i, n in enumerate(objs)
            if best[i] > 0.0
        }

    def _xy(self, node: str) -> tuple[float, float]:
        i = self.snap.obj_index.get(node)
        if i is not None:
            return float(self.snap.centre[i, 0]), float(self.snap.centre[i, 1])
        p = self.snap.position(node)
        assert p is not None
        return p[0], p[1]

    def between(self, node: str, first: Landmarks, second: Landmarks) -> tuple[float, str]:
        """Best ``min(q1, q2)`` over landmark pairs the node lies between."""
        return self.between_all([node], first, second).get(node, (0.0, ""))

    def between_all(
        self, nodes: Sequence[str], first: Landmarks, second: Landmarks
    ) -> dict[str, tuple[float, str]]:
        """:meth:`between` for many nodes: the centre lies inside the segment joining
        one landmark of each kind (on one floor, at most BETWEEN_MAX_SPAN apart), within
        BETWEEN_BAND of it and closer to each landmark than they are to each other."""
        snap = self.snap
        found = [n for n in nodes if n in snap.obj_index or snap.position(n) is not None]
        if not found:
            return {}
        pts = np.array([self._xy(n) for n in found], dtype=float).reshape(-1, 2)
        levels = np.array([snap.level_of(n) for n in found], dtype=object)
        pairs: list[tuple[float, str, str, np.ndarray, np.ndarray, int | None]] = []
        for b, qb in first:
            for c, qc in second:
                pb, pc, lb = snap.position(b), snap.position(c), snap.level_of(b)
                if b == c or pb is None or pc is None or lb != snap.level_of(c):
                    continue
                span = math.dist(pb[:2], pc[:2])
                if 1e-9 < span <= BETWEEN_MAX_SPAN:
                    pairs.append((min(qb, qc), b, c, np.asarray(pb[:2]), np.asarray(pc[:2]), lb))
        pairs.sort(key=lambda p: (-p[0], p[1], p[2]))
        out: dict[str, tuple[float, str]] = {}
        for q, b, c, xb, xc, level in pairs:
            seg = xc - xb
            span = float(np.hypot(seg[0], seg[1]))
            rel = pts - xb
            far = pts - xc
            t = rel @ seg / (span * span)
            offset = np.abs(seg[0] * rel[:, 1] - seg[1] * rel[:, 0]) / span
            ok = (
                (t > 0.0)
                & (t < 1.0)
                & (offset <= BETWEEN_BAND)
                & (np.hypot(rel[:, 0], rel[:, 1]) < span)
                & (np.hypot(far[:, 0], far[:, 1]) < span)
                & (levels == level)
            )
            for i in np.flatnonzero(ok):
                node = found[i]
                if node not in out and node not in (b, c):
                    out[node] = (q, f"{node} lies between {b} and {c} (geometry)")
        return out
