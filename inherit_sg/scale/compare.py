"""What "the same map" means when comparing a build-many map with one built alone.

Measured here: two builds of one dataset give the same objects (ids, labels, positions,
boxes), keyframes, SEEN_IN edges and sessions, to the 4th decimal. Rooms and areas are
not always the same: the semantic stream runs a global update (room masks, areas) when
its queue empties, so where in the walk it happens depends on thread timing (a process's
first build, which also loads the models, gave 3 rooms where five later builds of the
same walk gave 4). :func:`map_signature` therefore keeps the layers apart.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

DECIMALS = 4


def _rounded(values: Any, decimals: int) -> tuple[float, ...]:
    return tuple(round(float(v), decimals) for v in values)


def map_signature(map_dir: str | Path, decimals: int = DECIMALS) -> dict[str, Any]:
    """The comparable content of a map, each part sorted: ``objects`` (id, label,
    position, box, status), ``seen_in`` (object → keyframe), ``keyframes`` (ids),
    ``sessions`` (id, name, dataset, frames, state), and the timing-dependent upper
    layers: ``places`` (floors, rooms, areas with label and position), ``edges`` (every
    other edge: kind, ends, predicate) and ``counts`` per table."""
    from inherit_sg.model.ids import EdgeKind, Layer
    from inherit_sg.store import MapStore

    with MapStore.open(map_dir) as store:
        graph = store.load_graph()
        sessions = [(s.id, s.name, s.dataset, s.frames, s.state) for s in store.sessions()]
        counts = store.stats().to_dict()
    objects = sorted(
        (
            o.id,
            o.label,
            _rounded(o.position, decimals),
            _rounded(o.bbox.min, decimals),
            _rounded(o.bbox.max, decimals),
            str(o.status),
        )
        for o in graph.objects()
    )
    places = sorted(
        (n.id, str(n.layer), n.label, _rounded(getattr(n, "position", ()), decimals))
        for n in graph.nodes()
        if n.layer != Layer.OBJECT
    )
    seen_in = sorted((e.src, e.dst) for e in graph.edges(EdgeKind.SEEN_IN))
    edges = sorted(
        (str(e.kind), e.src, e.dst, str(dict(e.props).get("predicate", "")))
        for e in graph.edges()
        if e.kind != EdgeKind.SEEN_IN
    )
    return {
        "objects": objects,
        "seen_in": seen_in,
        "keyframes": sorted({kf for _, kf in seen_in}),
        "sessions": sessions,
        "places": places,
        "edges": edges,
        "counts": {"nodes": counts["nodes"], "edges": counts["edges"]},
    }


def same_objects(a: dict[str, Any], b: dict[str, Any]) -> bool:
    """Whether two signatures hold the same objects, observations and sessions (the
    parts two builds of one dataset share; session ids and names included)."""
    return all(a[k] == b[k] for k in ("objects", "seen_in", "keyframes", "sessions"))
