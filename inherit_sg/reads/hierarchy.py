"""The floors → rooms → areas → objects tree of a map (ids and labels only)."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from inherit_sg.reads.models import Hierarchy, TreeNode

if TYPE_CHECKING:
    from inherit_sg.facade import MapService

_DIGITS = re.compile(r"(\d+)")


def natural_key(text: str) -> tuple[str | int, ...]:
    """Sort key that orders ``obj:2`` before ``obj:10``."""
    return tuple(int(p) if i % 2 else p for i, p in enumerate(_DIGITS.split(text)))


def _sort_key(node: TreeNode) -> tuple[bool, tuple[str | int, ...]]:
    # rooms and areas before loose objects, then by id
    return (node.layer == "object", natural_key(node.id))


def build_hierarchy(service: MapService) -> Hierarchy:
    """The whole tree; every node appears once, under its nearest known parent."""

    def rows(query: str) -> list[list[str | None]]:
        return service.cypher(query, max_rows=None).rows

    floors = {
        fid: TreeNode(id=fid, label=label or "", layer="floor")
        for fid, label, _ in rows("MATCH (f:Floor) RETURN f.id, f.label, f.level ORDER BY f.level")
        if fid is not None
    }

    def layer(query: str, name: str) -> tuple[dict[str, TreeNode], dict[str, str | None]]:
        """Nodes of one layer by id, and each one's parent id (id, label, parent rows)."""
        nodes: dict[str, TreeNode] = {}
        parent: dict[str, str | None] = {}
        for nid, label, parent_id in rows(query):
            assert nid is not None
            nodes[nid] = TreeNode(id=nid, label=label or "", layer=name)
            parent[nid] = parent_id
        return nodes, parent

    rooms, room_parent = layer("MATCH (r:Room) RETURN r.id, r.label, r.floor_id", "room")
    areas, area_parent = layer("MATCH (a:Area) RETURN a.id, a.label, a.room_id", "area")
    unassigned: list[TreeNode] = []

    def attach(node: TreeNode, *parents: TreeNode | None) -> None:
        for parent in parents:
            if parent is not None:
                parent.children.append(node)
                return
        unassigned.append(node)

    objects = rows("MATCH (o:Object) RETURN o.id, o.label, o.area_id, o.room_id, o.floor_id")
    for oid, label, area_id, room_id, floor_id in objects:
        assert oid is not None
        node = TreeNode(id=oid, label=label or "", layer="object")
        attach(
            node,
            areas.get(area_id or ""),
            rooms.get(room_id or ""),
            floors.get(floor_id or ""),
        )
    for aid, node in areas.items():
        attach(node, rooms.get(area_parent[aid] or ""))
    for rid, node in rooms.items():
        attach(node, floors.get(room_parent[rid] or ""))
    for node in [*floors.values(), *rooms.values(), *areas.values()]:
        node.children.sort(key=_sort_key)
    unassigned.sort(key=lambda n: (n.layer, natural_key(n.id)))
    return Hierarchy(floors=list(floors.values()), unassigned=unassigned)
