"""In-memory scene graph: the mapping working set with change tracking.

After Spark-DSG: nodes by id and layer, edges keyed by ``(kind, src, dst, predicate)``,
``add_or_update``, ``merge_nodes`` and a change log (new/updated/removed nodes and edges
since the last :meth:`SceneGraph.flush_changes`) that the single writer persists.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from inherit_sg.errors import NodeNotFoundError
from inherit_sg.model.ids import EdgeKind, Layer
from inherit_sg.model.nodes import Edge, Node, ObjectNode

EdgeKey = tuple[str, str, str, str]

# Edges whose source is the parent of their destination in the hierarchy.
_PARENT_KINDS = (EdgeKind.HAS_ROOM, EdgeKind.HAS_AREA, EdgeKind.HAS_OBJECT)


@dataclass
class ChangeSet:
    """What changed since the last flush."""

    new_nodes: set[str] = field(default_factory=set)
    updated_nodes: set[str] = field(default_factory=set)
    removed_nodes: set[str] = field(default_factory=set)
    new_edges: set[EdgeKey] = field(default_factory=set)
    removed_edges: set[EdgeKey] = field(default_factory=set)

    @property
    def empty(self) -> bool:
        """True when nothing changed."""
        return not (
            self.new_nodes
            or self.updated_nodes
            or self.removed_nodes
            or self.new_edges
            or self.removed_edges
        )


class SceneGraph:
    """Nodes of the four layers plus typed edges, with a change log."""

    def __init__(self) -> None:
        self._nodes: dict[str, Node] = {}
        self._edges: dict[EdgeKey, Edge] = {}
        self._out: dict[str, set[EdgeKey]] = defaultdict(set)
        self._in: dict[str, set[EdgeKey]] = defaultdict(set)
        self._changes = ChangeSet()

    # ----------------------------------------------------------------- nodes
    def __contains__(self, node_id: object) -> bool:
        return node_id in self._nodes

    def __len__(self) -> int:
        return len(self._nodes)

    def get(self, node_id: str) -> Node:
        """The node with ``node_id``; NodeNotFoundError if absent."""
        try:
            return self._nodes[node_id]
        except KeyError:
            raise NodeNotFoundError(f"no node {node_id!r} in the scene graph") from None

    def nodes(self, layer: Layer | None = None) -> Iterator[Node]:
        """All nodes, or those of one layer, in insertion order."""
        for node in self._nodes.values():
            if layer is None or node.layer == layer:
                yield node

    def objects(self) -> Iterator[ObjectNode]:
        """All object nodes."""
        for node in self._nodes.values():
            if isinstance(node, ObjectNode):
                yield node

    def add_or_update(self, node: Node) -> bool:
        """Insert ``node`` or replace the node with the same id. Returns True if new."""
        is_new = node.id not in self._nodes
        self._nodes[node.id] = node
        if is_new:
            if node.id in self._changes.removed_nodes:
                self._changes.removed_nodes.discard(node.id)
                self._changes.updated_nodes.add(node.id)
            else:
                self._changes.new_nodes.add(node.id)
        elif node.id not in self._changes.new_nodes:
            self._changes.updated_nodes.add(node.id)
        return is_new

    def touch(self, node_id: str) -> None:
        """Record that a node was modified in place."""
        self.get(node_id)
        if node_id not in self._changes.new_nodes:
            self._changes.updated_nodes.add(node_id)

    def remove(self, node_id: str) -> Node:
        """Remove a node and every edge touching it."""
        node = self.get(node_id)
        for key in list(self._out[node_id] | self._in[node_id]):
            self._drop_edge(key)
        del self._nodes[node_id]
        self._out.pop(node_id, None)
        self._in.pop(node_id, None)
        if node_id in self._changes.new_nodes:
            self._changes.new_nodes.discard(node_id)
        else:
            self._changes.updated_nodes.discard(node_id)
            self._changes.removed_nodes.add(node_id)
        return node

    def merge_nodes(self, keep_id: str, drop_id: str) -> Node:
        """Merge ``drop_id`` into ``keep_id``: edges are redirected (self-loops dropped),
        object observations and keyframes are combined, then ``drop_id`` is removed."""
        keep, drop = self.get(keep_id), self.get(drop_id)
        if keep.layer != drop.layer:
            raise ValueError(
                f"cannot merge {keep_id} ({keep.layer.name}) with {drop_id} ({drop.layer.name})"
            )
        for key in list(self._out[drop_id] | self._in[drop_id]):
            edge = self._edges[key]
            src = keep_id if edge.src == drop_id else edge.src
            dst = keep_id if edge.dst == drop_id else edge.dst
            if src != dst:
                self.add_edge(Edge(edge.kind, src, dst, edge.props))
        if isinstance(keep, ObjectNode) and isinstance(drop, ObjectNode):
            keep.observation_count += drop.observation_count
            keep.first_seen = min(keep.first_seen, drop.first_seen)
            keep.last_seen = max(keep.last_seen, drop.last_seen)
            keep.keyframe_ids.extend(k for k in drop.keyframe_ids if k not in keep.keyframe_ids)
            keep.bbox = keep.bbox.union(drop.bbox)
        self.remove(drop_id)
        self.touch(keep_id)
        return keep

    # ----------------------------------------------------------------- edges
    def add_edge(self, edge: Edge) -> bool:
        """Insert or replace an edge (same key). Both ends must exist unless the
        destination is a keyframe (SEEN_IN). Returns True if new; an existing edge whose
        properties change is logged in ``new_edges`` again so that it is re-persisted."""
        self.get(edge.src)
        if edge.kind is not EdgeKind.SEEN_IN:
            self.get(edge.dst)
        key = edge.key
        previous = self._edges.get(key)
        is_new = previous is None
        self._edges[key] = edge
        self._out[edge.src].add(key)
        self._in[edge.dst].add(key)
        if is_new:
            if key in self._changes.removed_edges:
                self._changes.removed_edges.discard(key)
            self._changes.new_edges.add(key)
        elif previous != edge:  # same key, new properties: log it to be written again
            self._changes.new_edges.add(key)
        return is_new

    def remove_edge(self, kind: EdgeKind, src: str, dst: str, predicate: str = "") -> None:
        """Remove one edge if present."""
        key = (kind.value, src, dst, predicate)
        if key in self._edges:
            self._drop_edge(key)

    def _drop_edge(self, key: EdgeKey) -> None:
        edge = self._edges.pop(key)
        self._out[edge.src].discard(key)
        self._in[edge.dst].discard(key)
        if key in self._changes.new_edges:
            self._changes.new_edges.discard(key)
        else:
            self._changes.removed_edges.add(key)

    def edges(self, kind: EdgeKind | None = None) -> Iterator[Edge]:
        """All edges, or those of one kind."""
        for edge in self._edges.values():
            if kind is None or edge.kind is kind:
                yield edge

    def edge(self, key: EdgeKey) -> Edge | None:
        """The edge with ``key`` if present."""
        return self._edges.get(key)

    def out_edges(self, node_id: str, kind: EdgeKind | None = None) -> list[Edge]:
        """Edges leaving ``node_id``."""
        return [
            e
            for k in self._out.get(node_id, ())
            if (e := self._edges[k]) and (kind is None or e.kind is kind)
        ]

    def in_edges(self, node_id: str, kind: EdgeKind | None = None) -> list[Edge]:
        """Edges entering ``node_id``."""
        return [
            e
            for k in self._in.get(node_id, ())
            if (e := self._edges[k]) and (kind is None or e.kind is kind)
        ]

    def neighbours(
        self, node_id: str, kinds: Iterable[EdgeKind] | None = None, direction: str = "both"
    ) -> list[str]:
        """Ids adjacent to ``node_id`` over edges of ``kinds`` ('out', 'in' or 'both')."""
        wanted = set(kinds) if kinds is not None else None
        out: list[str] = []
        if direction in ("out", "both"):
            out += [e.dst for e in self.out_edges(node_id) if wanted is None or e.kind in wanted]
        if direction in ("in", "both"):
            out += [e.src for e in self.in_edges(node_id) if wanted is None or e.kind in wanted]
        return list(dict.fromkeys(out))

    def parent(self, node_id: str) -> str | None:
        """Hierarchical parent (floor of a room, room of an area, area of an object)."""
        parents = [e.src for e in self.in_edges(node_id) if e.kind in _PARENT_KINDS]
        return parents[0] if parents else None

    def children(self, node_id: str) -> list[str]:
        """Hierarchical children."""
        return [e.dst for e in self.out_edges(node_id) if e.kind in _PARENT_KINDS]

    # --------------------------------------------------------------- changes
    @property
    def changes(self) -> ChangeSet:
        """Changes since the last flush (live view; do not mutate)."""
        return self._changes

    def flush_changes(self) -> ChangeSet:
        """Return the accumulated changes and start a new log."""
        out, self._changes = self._changes, ChangeSet()
        return out

    def restore_changes(self, changes: ChangeSet) -> None:
        """Put back a flushed change set whose persistence failed, merged with whatever
        changed since, so that the next flush includes it again."""
        log = self._changes
        for node_id in changes.new_nodes | changes.updated_nodes | changes.removed_nodes:
            if node_id in self._nodes:
                log.removed_nodes.discard(node_id)
                if node_id in changes.new_nodes and node_id not in log.updated_nodes:
                    log.new_nodes.add(node_id)
                elif node_id not in log.new_nodes:
                    log.updated_nodes.add(node_id)
            else:
                log.removed_nodes.add(node_id)
        for key in changes.new_edges | changes.removed_edges:
            if key in self._edges:
                log.new_edges.add(key)
                log.removed_edges.discard(key)
            else:
                log.new_edges.discard(key)
                log.removed_edges.add(key)
