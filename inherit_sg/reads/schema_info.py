"""The public graph tables of a map as an agent needs them to write Cypher: each table's
properties read from the map's own catalogue (``CALL TABLE_INFO``, so what the migrations
made, not a copy), the relationships' endpoints, example statements and the rules."""

from __future__ import annotations

from typing import TYPE_CHECKING

from inherit_sg.model import EdgeKind
from inherit_sg.reads.models import CypherExample, GraphSchema, PropertySchema, TableSchema
from inherit_sg.store.stats import NODE_TABLES

if TYPE_CHECKING:
    from inherit_sg.facade import MapService

NODE_NOTES = {
    "Floor": "A storey; level 0 is the lowest. Rooms, areas and objects name it in floor_id.",
    "Room": "A room with its label (best inferred type), summary, centroid position, "
    "floor_id, best_view keyframe and types (JSON [[type, probability], ...]).",
    "Area": "A functional area inside a room (e.g. 'cooking area'), with summary, "
    "position and room_id.",
    "Object": "An object with label, description, centroid position, axis-aligned box "
    "(bbox_min, bbox_max), status, floor_id / room_id / area_id and best_keyframe.",
    "Keyframe": "A stored camera view (pose: 16 numbers of T_world_camera, row-major) of a "
    "mapping session.",
    "Session": "A mapping session that added to the map.",
}
REL_NOTES = {
    EdgeKind.HAS_ROOM: "A floor contains a room.",
    EdgeKind.HAS_AREA: "A room contains a functional area.",
    EdgeKind.HAS_OBJECT: "An area contains an object.",
    EdgeKind.CONNECTS: "Two rooms joined by a door (door: its position).",
    EdgeKind.STAIRS: "Stairs between two floors.",
    EdgeKind.RELATION: "A spatial relation between objects: the source is <predicate> the "
    "target (e.g. 'on', 'next to', 'near'), with a confidence.",
    EdgeKind.SEEN_IN: "An object was detected in a keyframe (props: the detection as JSON).",
}
EXAMPLES = (
    CypherExample(
        question="Which rooms are on each floor?",
        cypher="MATCH (f:Floor)-[:HAS_ROOM]->(r:Room) "
        "RETURN f.id, f.level, r.id, r.label ORDER BY f.level, r.id",
    ),
    CypherExample(
        question="How many objects of each label are there?",
        cypher="MATCH (o:Object) RETURN o.label, count(*) AS n ORDER BY n DESC, o.label LIMIT 20",
    ),
    CypherExample(
        question="What is in each functional area of the kitchens?",
        cypher="MATCH (r:Room)-[:HAS_AREA]->(a:Area)-[:HAS_OBJECT]->(o:Object) "
        "WHERE lower(r.label) = 'kitchen' RETURN r.id, a.label, o.id, o.label ORDER BY o.id",
    ),
    CypherExample(
        question="Which objects are on something, and on what?",
        cypher="MATCH (a:Object)-[e:RELATION]->(b:Object) WHERE e.predicate = 'on' "
        "RETURN a.id, a.label, b.id, b.label, e.confidence ORDER BY a.id LIMIT 50",
    ),
    CypherExample(
        question="Which rooms connect through a door, and where is the door?",
        cypher="MATCH (a:Room)-[c:CONNECTS]->(b:Room) RETURN a.id, a.label, b.id, b.label, c.door",
    ),
    CypherExample(
        question="Which two objects are closest to each other on the floor plan?",
        cypher="MATCH (a:Object), (b:Object) WHERE a.id < b.id AND a.floor_id = b.floor_id "
        "RETURN a.id, a.label, b.id, b.label, "
        "sqrt((a.position[1] - b.position[1])^2 + (a.position[2] - b.position[2])^2) AS metres "
        "ORDER BY metres LIMIT 5",
    ),
    CypherExample(
        question="In which keyframes was each object seen?",
        cypher="MATCH (o:Object)-[:SEEN_IN]->(k:Keyframe) "
        "RETURN o.id, o.label, k.id, k.timestamp ORDER BY o.id, k.timestamp LIMIT 50",
    ),
)
NOTES = (
    "Statements are read-only: CREATE, MERGE, SET, DELETE, REMOVE, COPY, LOAD and "
    "procedures other than reading ones (TABLE_INFO, SHOW_TABLES, QUERY_VECTOR_INDEX, "
    "QUERY_FTS_INDEX, ...) are refused.",
    "Positions are world coordinates in metres, right-handed, z up: position[1] is x, "
    "position[2] is y, position[3] is z (Cypher lists start at 1).",
    "Labels are lower-case words such as 'chair' or 'living room'; compare with "
    "lower(x.label) = '...' or CONTAINS.",
    "Pass values as parameters ($name) rather than pasting them into the text.",
    "Results stop at max_rows rows (truncated is then true) and a statement is stopped "
    "at its time limit.",
)


def _properties(service: MapService, table: str) -> list[PropertySchema]:
    """Properties of ``table`` from the map's catalogue, in column order."""
    rows = service.cypher(f"CALL TABLE_INFO('{table}') RETURN *", max_rows=None).rows
    return [
        PropertySchema(name=str(row[1]), type=str(row[2]), primary_key=row[4] is True)
        for row in rows
    ]


def graph_schema(service: MapService) -> GraphSchema:
    """The public node and relationship tables of the map behind ``service``, examples
    of Cypher on them and the rules statements follow."""
    nodes = [
        TableSchema(
            name=table,
            kind="node",
            description=NODE_NOTES[table],
            properties=_properties(service, table),
        )
        for table in NODE_TABLES
    ]
    relationships = [
        TableSchema(
            name=kind.value,
            kind="relationship",
            description=REL_NOTES[kind],
            source=kind.endpoints[0],
            target=kind.endpoints[1],
            properties=_properties(service, kind.value),
        )
        for kind in EdgeKind
    ]
    return GraphSchema(
        nodes=nodes, relationships=relationships, examples=list(EXAMPLES), notes=list(NOTES)
    )
