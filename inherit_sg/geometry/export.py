"""Scene-graph view of the geometric stream: floor and room nodes (L0, L1), HAS_ROOM,
CONNECTS (through a door, with its position) and STAIRS edges, and an in-place update
of a :class:`~inherit_sg.model.SceneGraph` that keeps what the semantic side wrote on
room nodes (label, summary, embeddings)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from inherit_sg.geometry.records import room_node_id
from inherit_sg.model import Edge, EdgeKind, FloorNode, RoomNode, SceneGraph

if TYPE_CHECKING:
    from inherit_sg.geometry.stream import GeometricStream


def floor_nodes(stream: GeometricStream) -> list[FloorNode]:
    """Floor nodes from the lowest up; ``z_max`` is the next floor's surface."""
    floors = stream.tracker.ordered()
    out = []
    for i, f in enumerate(floors):
        z = f.floor_z
        top = floors[i + 1].floor_z if i + 1 < len(floors) else z + stream.cfg.storey_height
        out.append(FloorNode(id=f.id, level=f.level, label=f"floor {f.level}", z_min=z, z_max=top))
    return out


def room_nodes(
    stream: GeometricStream, floor_id: str | None = None, refined: bool = False
) -> list[RoomNode]:
    """Room nodes with 2D masks and centroids (refined masks when ``refined``)."""
    out = []
    for fid, fmap in stream.maps.items():
        if floor_id and fid != floor_id:
            continue
        z = stream.tracker.floors[fid].floor_z
        for room, mask in sorted(fmap.masks(refined).items()):
            r, c = np.nonzero(mask.cells)
            x = mask.origin_x + (float(c.mean()) + 0.5) * mask.resolution
            y = mask.origin_y + (float(r.mean()) + 0.5) * mask.resolution
            out.append(
                RoomNode(
                    id=room_node_id(room),
                    label="room",
                    floor_id=fid,
                    position=(x, y, z),
                    mask=mask,
                    best_view=stream.best_view.get(room),
                )
            )
    return out


def geometry_edges(stream: GeometricStream, refined: bool = False) -> list[Edge]:
    """HAS_ROOM, CONNECTS and STAIRS edges."""
    rooms = room_nodes(stream, refined=refined)
    present = {r.id for r in rooms}
    edges = [Edge.make(EdgeKind.HAS_ROOM, str(r.floor_id), r.id) for r in rooms]
    seen: set[tuple[str, str]] = set()
    for fid, door in stream.doors():
        if door.rooms is None:
            continue
        a, b = (room_node_id(n) for n in sorted(door.rooms))
        if a not in present or b not in present or (a, b) in seen:
            continue
        seen.add((a, b))
        z = stream.tracker.floors[fid].floor_z
        edges.append(
            Edge.make(
                EdgeKind.CONNECTS,
                a,
                b,
                door=[door.position[0], door.position[1], z],
                width=door.width,
                source=door.source,
            )
        )
    levels: dict[str, int] = {f.id: f.level for f in stream.tracker.floors.values()}
    for s in stream.stairs:
        lo, hi = (s.from_floor, s.to_floor)
        bottom, top = s.start, s.end
        if levels[lo] > levels[hi]:
            lo, hi, bottom, top = hi, lo, top, bottom
        edges.append(Edge.make(EdgeKind.STAIRS, lo, hi, bottom=list(bottom), top=list(top)))
    return edges


def apply_to_graph(stream: GeometricStream, graph: SceneGraph, refined: bool = True) -> None:
    """Bring the floor/room layers of ``graph`` in line with the stream.

    Existing room nodes keep their label, summary and embeddings; rooms this stream
    published earlier and that no longer exist are removed with their edges.
    """
    for node in floor_nodes(stream):
        if node.id in graph:
            old = graph.get(node.id)
            if isinstance(old, FloorNode):
                old.level, old.z_min, old.z_max = node.level, node.z_min, node.z_max
                graph.touch(node.id)
                continue
        graph.add_or_update(node)
    rooms = room_nodes(stream, refined=refined)
    current: set[str] = {r.id for r in rooms}
    for rid in stream.published_rooms - current:
        if rid in graph:
            graph.remove(rid)
    for room in rooms:
        prev = graph.get(room.id) if room.id in graph else None
        if isinstance(prev, RoomNode):
            prev.mask, prev.position, prev.floor_id = room.mask, room.position, room.floor_id
            prev.best_view = room.best_view or prev.best_view
            graph.touch(room.id)
        else:
            graph.add_or_update(room)
    stream.published_rooms = current
    edges = geometry_edges(stream, refined=refined)
    keys = {e.key for e in edges}
    for kind in (EdgeKind.HAS_ROOM, EdgeKind.CONNECTS):
        for e in list(graph.edges(kind)):
            ours = e.dst in current or (kind is EdgeKind.CONNECTS and e.src in current)
            if ours and e.key not in keys:
                graph.remove_edge(e.kind, e.src, e.dst)
    for e in edges:
        if graph.edge(e.key) != e:
            graph.add_edge(e)
