"""The global map update (paper §III-C "Event-Triggered Map Updates"): after the room
masks are refined, objects are reassigned to rooms and the area and room layers are
rebuilt bottom-up; relations are re-inferred; node texts and embeddings are refreshed
only where they changed. Everything is written into the working :class:`SceneGraph` as
a diff, so the single writer persists only what changed."""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np

from inherit_sg.mapping.area_labeller import AreaLabeller, RuleAreaLabeller
from inherit_sg.mapping.areas import cluster_objects
from inherit_sg.mapping.exterior import (
    DEFAULT_EXTERIOR,
    EXTERIOR_DOOR,
    ExteriorParams,
    exterior_doors,
    is_plain_door,
)
from inherit_sg.mapping.node_text import node_text
from inherit_sg.mapping.object_map import ObjectMap
from inherit_sg.mapping.open_plan import DEFAULT_SPLIT, SplitParams, split_open_plan_rooms
from inherit_sg.mapping.relation_verifier import Box, GeometricVerifier, RelationVerifier
from inherit_sg.mapping.relations import Relation, infer_relations
from inherit_sg.mapping.room_merge import DEFAULT_MERGE, MergeParams, merge_over_segmented_rooms
from inherit_sg.mapping.room_semantics import (
    infer_room_types,
    kept_types,
    room_label,
    room_shape,
    separate_single_types,
    summarise_room,
)
from inherit_sg.mapping.semantic import LabelEmbedder
from inherit_sg.model import (
    AreaNode,
    Edge,
    EdgeKind,
    FloorNode,
    Layer,
    ObjectNode,
    ObjectStatus,
    RoomMask,
    RoomNode,
    SceneGraph,
    make_id,
)
from inherit_sg.model.doorways import doorway_rooms, doorways_of
from inherit_sg.perception.describer import UNNAMED, is_round_footprint, template_description

_NUMBERS = re.compile(r"\d+(?:\.\d+)?")


def _wording(text: str) -> str:
    """A node text with its numbers masked: the key that decides re-embedding."""
    return _NUMBERS.sub("#", text)


RoomLocator = Callable[[float, float, str | None], str | None]
# object id -> (JPEG of a keyframe showing it, pixel boxes of the objects in that JPEG)
KeyframeView = Callable[[str], tuple[bytes | None, dict[str, Box]] | None]


# An object outside every room's mask belongs to the nearest room within this many
# metres of it (the floor a camera saw past a doorway or over furniture is often not
# segmented into its room).
ROOM_REACH = 2.5


def nearest_room(graph: SceneGraph, node: ObjectNode) -> str | None:
    """Closest room of the object's floor, within :data:`ROOM_REACH` of its mask
    (of its centre when it has none): objects on thresholds, in doorways or outside
    the observed free space (a corner of a room the camera only looked into)."""
    best, best_d = None, ROOM_REACH
    x, y = node.position[0], node.position[1]
    for room in graph.nodes(Layer.ROOM):
        if isinstance(room, RoomNode) and room.floor_id == node.floor_id:
            if room.mask is None:
                d = float(np.hypot(room.position[0] - x, room.position[1] - y))
            else:
                d = room.mask.distance_xy(x, y)
            if d == 0.0:
                return room.id
            if d < best_d:
                best, best_d = room.id, d
    return best


@dataclass
class UpdateStats:
    """What one global update changed."""

    objects: int = 0
    rooms: int = 0
    areas: int = 0
    relations: int = 0
    embedded: int = 0


def sync_edges(
    graph: SceneGraph, kind: EdgeKind, desired: Iterable[Edge], scope: set[str] | None = None
) -> int:
    """Make the ``kind`` edges of ``graph`` (whose source is in ``scope``, default all)
    equal to ``desired``; returns how many edges were added or replaced."""
    wanted = {e.key: e for e in desired}
    for edge in list(graph.edges(kind)):
        if (scope is None or edge.src in scope) and edge.key not in wanted:
            graph.remove_edge(kind, edge.src, edge.dst, str(edge.prop("predicate", "")))
    changed = 0
    for key, edge in wanted.items():
        if graph.edge(key) != edge:
            graph.add_edge(edge)
            changed += 1
    return changed


class HierarchyBuilder:
    """Rebuilds objects → areas → rooms in the working graph and keeps embeddings fresh."""

    def __init__(
        self,
        embedder: LabelEmbedder,
        refresh_descriptions: bool = True,
        area_labeller: AreaLabeller | None = None,
        relation_verifier: RelationVerifier | None = None,
        keyframe_view: KeyframeView | None = None,
        open_plan: SplitParams | None = DEFAULT_SPLIT,
        merge: MergeParams | None = DEFAULT_MERGE,
        exterior: ExteriorParams | None = DEFAULT_EXTERIOR,
    ) -> None:
        """``open_plan``: thresholds of the open-plan room split (None: rooms stay as
        the geometry made them); ``merge``: thresholds of the join of over-segmented
        rooms, done before the split (None: no join); ``exterior``: thresholds of the
        test that names the doors leading out of a floor "exterior door" (None: doors
        keep their detected label)."""
        self.embedder = embedder
        self.exterior = exterior
        self.open_plan = open_plan
        self.merge = merge
        self.refresh_descriptions = refresh_descriptions
        self.area_labeller = area_labeller or RuleAreaLabeller()
        self.relation_verifier = relation_verifier or GeometricVerifier()
        self.keyframe_view = keyframe_view
        self._embedded_text: dict[str, str] = {}

    @staticmethod
    def _label_rooms(
        rooms: dict[str, RoomNode],
        by_room: dict[str, list[ObjectNode]],
        in_doorways: dict[str, list[ObjectNode]],
    ) -> None:
        """Infer every room's type distribution from its objects' labels (with the
        objects standing in its doorways from the other side, ``in_doorways``: a hall is
        where many doors open) and its mask's size and shape (and whether its storey
        holds the building's entrance, an exterior door, while another does), apply the
        one-per-storey prior floor by floor (:func:`separate_single_types`); each label
        is its room's best type."""
        floors: dict[str | None, dict[str, list[tuple[str, float]]]] = {}
        entrances = {
            room.floor_id
            for room_id, room in rooms.items()
            if any(o.label == EXTERIOR_DOOR for o in by_room.get(room_id, []))
        }
        for room_id, room in rooms.items():
            labels = [o.label for o in by_room.get(room_id, []) + in_doorways.get(room_id, [])]
            off_entrance = bool(entrances) and room.floor_id not in entrances
            types = infer_room_types(labels, shape=room_shape(room.mask), off_entrance=off_entrance)
            floors.setdefault(room.floor_id, {})[room_id] = types
        separated = separate_single_types(list(floors.values()))
        for room_id, room in rooms.items():
            room.types = kept_types(separated[room_id])
            room.label = room_label(separated[room_id])

    def _name_exterior_doors(self, graph: SceneGraph, objects: ObjectMap) -> None:
        """Label the doors that lead out of their floor "exterior door", and give a
        door that no longer does its detected label back."""
        assert self.exterior is not None
        doors = [
            t.node
            for t in objects.objects.values()
            if t.node.status is not ObjectStatus.REMOVED and is_plain_door(t.label)
        ]
        if not doors:
            return
        masks: dict[str | None, list[RoomMask]] = defaultdict(list)
        for room in graph.nodes(Layer.ROOM):
            if isinstance(room, RoomNode) and room.mask is not None:
                masks[room.floor_id].append(room.mask)
        outer = exterior_doors(doors, masks, self.exterior)
        door_ids = {d.id for d in doors}
        for tracked in objects.objects.values():
            if tracked.node.id in door_ids:
                tracked.node.label = EXTERIOR_DOOR if tracked.node.id in outer else tracked.label

    def rebuild(self, graph: SceneGraph, objects: ObjectMap, locate: RoomLocator) -> UpdateStats:
        """Run the bottom-up rebuild; the floor/room layers must already be current."""
        stats = UpdateStats()
        for dropped in objects.removed:
            if dropped in graph:
                graph.remove(dropped)
        objects.removed.clear()
        before = {
            t.id: (t.node.room_id, t.node.area_id, t.node.description, t.node.label, t.node.status)
            for t in objects.objects.values()
        }
        by_room: dict[str, list[ObjectNode]] = defaultdict(list)
        for tracked in objects.objects.values():
            node = tracked.node
            node.floor_id = tracked.floor_id
            if node.status is ObjectStatus.REMOVED:
                continue
            found = locate(node.position[0], node.position[1], node.floor_id) or nearest_room(
                graph, node
            )
            node.room_id = found
            if found is not None:
                by_room[found].append(node)
            else:
                node.area_id = None
            stats.objects += 1
        if self.exterior is not None:
            self._name_exterior_doors(graph, objects)
        if self.merge is not None:
            by_room = defaultdict(list, merge_over_segmented_rooms(graph, by_room, self.merge))
        if self.open_plan is not None:
            by_room = defaultdict(list, split_open_plan_rooms(graph, by_room, self.open_plan))
        rooms = {r.id: r for r in graph.nodes(Layer.ROOM) if isinstance(r, RoomNode)}
        areas_wanted: dict[str, AreaNode] = {}
        has_area: list[Edge] = []
        has_object: list[Edge] = []
        self._label_rooms(rooms, by_room, _doorway_members(graph, rooms, by_room))
        for room_id, members in sorted(by_room.items()):
            if room_id not in rooms:
                continue
            room = rooms[room_id]
            room_num = room_id.partition(":")[2]
            summaries = []
            for k, cluster in enumerate(cluster_objects(members)):
                label, summary = self.area_labeller.label([o.label for o in cluster], room.label)
                pts = np.array([o.position for o in cluster], dtype=float)
                area = AreaNode(
                    make_id(Layer.AREA, f"{room_num}.{k}"),
                    label,
                    room_id=room_id,
                    position=tuple(float(v) for v in pts.mean(axis=0)),  # type: ignore[arg-type]
                    summary=summary,
                )
                areas_wanted[area.id] = area
                summaries.append(area.summary)
                has_area.append(Edge.make(EdgeKind.HAS_AREA, room_id, area.id))
                for o in cluster:
                    o.area_id = area.id
                    has_object.append(Edge.make(EdgeKind.HAS_OBJECT, area.id, o.id))
            labels = [o.label for o in members]
            floor = graph.get(room.floor_id) if room.floor_id and room.floor_id in graph else None
            level = floor.level if isinstance(floor, FloorNode) else None
            room.summary = summarise_room(room.label, level, summaries, labels)
            graph.touch(room_id)
        for room_id, room in rooms.items():
            if room_id not in by_room:
                floor = (
                    graph.get(room.floor_id) if room.floor_id and room.floor_id in graph else None
                )
                room.summary = summarise_room(room.label, getattr(floor, "level", None), [], [])
                graph.touch(room_id)
        stats.rooms = len(rooms)
        if self.refresh_descriptions:
            room_labels = {rid: r.label for rid, r in rooms.items()}
            for tracked in objects.objects.values():
                node = tracked.node
                colour = str(node.attributes.get("colour", "unknown"))
                extent = tuple(float(v) for v in node.bbox.size)
                node.description = template_description(
                    node.label,
                    colour,
                    (extent[0], extent[1], extent[2]),
                    room_labels.get(node.room_id or ""),
                    material=node.attributes.get("material"),
                    round_footprint=node.label == UNNAMED and is_round_footprint(tracked.points),
                )
        for tracked in objects.objects.values():
            node = tracked.node
            state = (node.room_id, node.area_id, node.description, node.label, node.status)
            if node.id not in graph:
                graph.add_or_update(node)
            elif tracked.dirty or before.get(node.id) != state:
                graph.touch(node.id)
            tracked.dirty = False
        self._sync_areas(graph, areas_wanted)
        stats.areas = len(areas_wanted)
        sync_edges(graph, EdgeKind.HAS_AREA, has_area)
        sync_edges(graph, EdgeKind.HAS_OBJECT, has_object)
        live = [
            o.node for o in objects.objects.values() if o.node.status is not ObjectStatus.REMOVED
        ]
        neighbours: dict[str, set[str]] = defaultdict(set)
        for e in graph.edges(EdgeKind.CONNECTS):
            neighbours[e.src].add(e.dst)
            neighbours[e.dst].add(e.src)
        relations = infer_relations(live, {o.id: o.room_id for o in live}, neighbours)
        relations = self._verify(relations, {o.id: o.label for o in live})
        stats.relations = len(relations)
        sync_edges(graph, EdgeKind.RELATION, [r.to_edge() for r in relations])
        stats.embedded = self.embed_changed(graph)
        return stats

    def _verify(self, relations: list[Relation], labels: dict[str, str]) -> list[Relation]:
        """Relations the verifier keeps, checked on a keyframe of each source object."""
        if isinstance(self.relation_verifier, GeometricVerifier) or self.keyframe_view is None:
            return relations
        by_src: dict[str, list[Relation]] = defaultdict(list)
        for r in relations:
            by_src[r.src].append(r)
        kept: list[Relation] = []
        for src, group in by_src.items():
            view = self.keyframe_view(src)
            if view is None:
                kept.extend(group)
            else:
                kept.extend(self.relation_verifier.verify(group, view[0], view[1], labels))
        return kept

    def _sync_areas(self, graph: SceneGraph, wanted: dict[str, AreaNode]) -> None:
        for node in list(graph.nodes(Layer.AREA)):
            if node.id not in wanted:
                graph.remove(node.id)
        for area_id, area in wanted.items():
            old = graph.get(area_id) if area_id in graph else None
            if isinstance(old, AreaNode):
                if (old.label, old.summary, old.position, old.room_id) != (
                    area.label,
                    area.summary,
                    area.position,
                    area.room_id,
                ):
                    old.label, old.summary, old.position, old.room_id = (
                        area.label,
                        area.summary,
                        area.position,
                        area.room_id,
                    )
                    graph.touch(area_id)
            else:
                graph.add_or_update(area)

    def embed_changed(self, graph: SceneGraph) -> int:
        """Embed nodes whose text changed in words since they were last embedded (a
        fused size moving by a centimetre does not change what a node means)."""
        todo = []
        for node in graph.nodes():
            text = node_text(node)
            if text is not None and self._embedded_text.get(node.id) != _wording(text):
                todo.append((node, text))
        if not todo:
            return 0
        vectors = self.embedder.embed([t for _, t in todo])
        for (node, text), vec in zip(todo, vectors, strict=True):
            node.text_embedding = vec  # type: ignore[union-attr]
            self._embedded_text[node.id] = _wording(text)
            graph.touch(node.id)
        return len(todo)

    def remember_embedded(self, graph: SceneGraph) -> None:
        """Mark the embeddings already in ``graph`` (a reopened map) as current."""
        for node in graph.nodes():
            text = node_text(node)
            if text is not None and getattr(node, "text_embedding", None) is not None:
                self._embedded_text[node.id] = _wording(text)


def _doorway_members(
    graph: SceneGraph, rooms: dict[str, RoomNode], by_room: dict[str, list[ObjectNode]]
) -> dict[str, list[ObjectNode]]:
    """Room id → the objects mapped in another room that stand in a doorway of this one
    (see :mod:`inherit_sg.model.doorways`)."""
    placed = [(room_id, o) for room_id in sorted(by_room) for o in by_room[room_id]]
    members = [o for _, o in placed]
    if not members:
        return {}
    doorways = doorways_of(graph, lambda rid: rooms[rid].floor_id if rid in rooms else None)
    if not doorways:
        return {}
    found = doorway_rooms(
        np.array([o.bbox.min for o in members], dtype=float).reshape(-1, 3),
        np.array([o.bbox.max for o in members], dtype=float).reshape(-1, 3),
        [o.floor_id for o in members],
        [room_id for room_id, _ in placed],
        doorways,
    )
    out: dict[str, list[ObjectNode]] = defaultdict(list)
    for row, others in sorted(found.items()):
        for room_id in others:
            out[room_id].append(members[row])
    return dict(out)
