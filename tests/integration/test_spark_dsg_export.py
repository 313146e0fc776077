"""Spark-DSG export with the official spark-dsg package: the file loads in spark_dsg with
the layers, attributes, parents and label spaces Spark-DSG tools read, and a map exported
and imported again through the CLI has the same floors, rooms, areas, objects and edges."""

from __future__ import annotations

import copy
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from inherit_sg.exchange.scene_truth import scene_file_to_graph
from inherit_sg.exchange.spark_dsg import spark_dsg_to_graph
from inherit_sg.exchange.spark_dsg_export import export_spark_dsg
from inherit_sg.ingest.synthetic.generate import generate_house
from inherit_sg.model import EdgeKind, FloorNode, Layer, ObjectNode, SceneGraph
from inherit_sg.store import MapStore

sd = pytest.importorskip("spark_dsg")

CLI = [sys.executable, "-m", "inherit_sg.cli.main"]


def run(*args: str, check: bool = True) -> subprocess.CompletedProcess[str]:
    proc = subprocess.run([*CLI, *args], capture_output=True, text=True, timeout=300)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


@pytest.fixture(scope="module")
def two_storeys(tmp_path_factory: pytest.TempPathFactory) -> SceneGraph:
    """The oracle graph of a small generated two-storey house: floors, rooms with doors,
    areas, objects, relations and stairs (no rendering needed)."""
    folder = tmp_path_factory.mktemp("house")
    return scene_file_to_graph(generate_house(3, 2, 4).scene.save(folder))


def _parent(dsg: Any, node: Any) -> int | None:
    return int(node.get_parent()) if node.has_parent() else None


def test_export_loads_in_spark_dsg(two_storeys: SceneGraph, tmp_path: Path) -> None:
    graph = two_storeys
    out = tmp_path / "g.json"
    counts = export_spark_dsg(graph, out)
    dsg = sd.DynamicSceneGraph.load(str(out))
    assert counts == {"nodes": dsg.num_nodes(), "edges": dsg.num_edges()}
    objects = {n.attributes.metadata.get()["inherit_sg"]["id"]: n for n in dsg.get_layer(2).nodes}
    rooms = {n.attributes.metadata.get()["inherit_sg"]["id"]: n for n in dsg.get_layer(4).nodes}
    buildings = list(dsg.get_layer(5).nodes)
    assert len(objects) == len(list(graph.objects())) > 50
    assert len(rooms) == len(list(graph.nodes(Layer.ROOM)))
    assert len(buildings) == 2  # one building-layer node per storey
    names = dsg.get_labelspace(2)
    assert names.labels_to_names == dsg.get_labelspace("OBJECTS").labels_to_names
    for obj in graph.objects():
        node = objects[obj.id]
        attrs = node.attributes
        assert isinstance(attrs, sd.ObjectNodeAttributes)
        assert names.get_category(attrs.semantic_label) == obj.label == attrs.name
        assert np.allclose(attrs.position, obj.position, atol=1e-6)
        assert np.allclose(attrs.bounding_box.min, obj.bbox.min, atol=1e-4)
        assert np.allclose(attrs.bounding_box.max, obj.bbox.max, atol=1e-4)
        assert _parent(dsg, node) == rooms[obj.room_id or ""].id.value  # areas folded
    room_labels = dsg.get_labelspace(4)
    for room in graph.nodes(Layer.ROOM):
        attrs = rooms[room.id].attributes
        assert isinstance(attrs, sd.RoomNodeAttributes) and attrs.name == room.label
        assert room_labels.get_category(attrs.semantic_label) == room.label
        assert attrs.bounding_box.is_valid()  # from the room mask and the storey's heights
        parent = dsg.get_node(_parent(dsg, rooms[room.id]))
        assert parent.layer.layer == 5
    # doors: room-room edges; relations: object-object edges with their predicates
    for edge in graph.edges(EdgeKind.CONNECTS):
        assert dsg.has_edge(rooms[edge.src].id.value, rooms[edge.dst].id.value)
    relation = next(iter(graph.edges(EdgeKind.RELATION)))
    info = dsg.get_edge(objects[relation.src].id.value, objects[relation.dst].id.value).info
    entries = info.metadata.get()["inherit_sg"]
    assert {"kind": "RELATION", "predicate": relation.prop("predicate")}.items() <= next(
        e for e in entries if e["predicate"] == relation.prop("predicate")
    ).items()
    assert info.weighted and 0 < info.weight <= 1


def _summary(graph: SceneGraph) -> dict[str, Any]:
    """What a round trip must keep: ids, labels, positions, boxes, parents, edges."""
    out: dict[str, Any] = {"floors": {}, "rooms": {}, "areas": {}, "objects": {}}
    for node in graph.nodes(Layer.FLOOR):
        assert isinstance(node, FloorNode)
        out["floors"][node.id] = (node.level, node.label)
    for node in graph.nodes(Layer.ROOM):
        out["rooms"][node.id] = (node.label, graph.parent(node.id))
    for node in graph.nodes(Layer.AREA):
        out["areas"][node.id] = (node.label, graph.parent(node.id))
    for obj in graph.objects():
        out["objects"][obj.id] = (obj.label, graph.parent(obj.id), obj.room_id, obj.floor_id)
    out["edges"] = sorted(
        e.key for e in graph.edges() if e.kind in (EdgeKind.CONNECTS, EdgeKind.STAIRS)
    )
    out["relations"] = sorted(e.key for e in graph.edges(EdgeKind.RELATION))
    return out


def _assert_same_geometry(a: SceneGraph, b: SceneGraph) -> None:
    for obj in a.objects():
        other = b.get(obj.id)
        assert isinstance(other, ObjectNode)
        assert np.allclose(other.position, obj.position, atol=1e-3)
        assert np.allclose(other.bbox.min, obj.bbox.min, atol=1e-3)
        assert np.allclose(other.bbox.max, obj.bbox.max, atol=1e-3)
    for room in a.nodes(Layer.ROOM):
        assert np.allclose(b.get(room.id).position, room.position, atol=1e-3)  # type: ignore[union-attr]


def test_cli_round_trip(two_storeys: SceneGraph, tmp_path: Path) -> None:
    first, second, out = tmp_path / "a", tmp_path / "b", tmp_path / "house_dsg.json"
    graph = copy.deepcopy(two_storeys)
    # built maps can hold objects outside every room (no area): they must stay so
    loose = next(graph.objects())
    graph.remove_edge(EdgeKind.HAS_OBJECT, loose.area_id or "", loose.id)
    loose.area_id = loose.room_id = None
    with MapStore.create(first) as store:
        store.write_changes(graph)
    proc = run("export", "--format", "spark-dsg", "--map", str(first), str(out), "--json")
    written = json.loads(proc.stdout)
    assert sd.DynamicSceneGraph.load(str(out)).num_nodes() == written["nodes"]
    run("import", "--format", "spark-dsg", str(out), "--map", str(second))
    with MapStore.open(first) as store:
        before = store.load_graph()
    with MapStore.open(second) as store:
        after = store.load_graph()
    assert _summary(after) == _summary(before)
    assert after.parent(loose.id) is None and "room:unassigned" not in after
    _assert_same_geometry(before, after)


def test_plain_spark_dsg_file_imports(tmp_path: Path) -> None:
    """A graph as Hydra writes it with spark-dsg 1.1 (no INHerit-SG metadata): label space
    in the graph metadata, boxes as centre + dimensions, a room-room edge."""
    dsg = sd.DynamicSceneGraph()
    for index, centre in enumerate(([0.0, 0.0, 0.0], [4.0, 0.0, 0.0])):
        room = sd.RoomNodeAttributes()
        room.position = np.array(centre)
        room.name = f"R{index}"
        dsg.add_node(sd.DsgLayers.ROOMS, sd.NodeSymbol("R", index), room)
    chair = sd.ObjectNodeAttributes()
    chair.position = np.array([4.2, 0.1, 0.45])
    chair.semantic_label = 7
    chair.bounding_box = sd.BoundingBox(
        np.array([0.5, 0.5, 0.9], dtype=np.float32), np.array([4.2, 0.1, 0.45], dtype=np.float32)
    )
    dsg.add_node(sd.DsgLayers.OBJECTS, sd.NodeSymbol("O", 0), chair)
    dsg.insert_edge(sd.NodeSymbol("R", 1), sd.NodeSymbol("O", 0))
    dsg.insert_edge(sd.NodeSymbol("R", 0), sd.NodeSymbol("R", 1))
    dsg.set_labelspace(sd.Labelspace({7: "chair"}), 2, 0)
    path = tmp_path / "hydra.json"
    dsg.save(str(path), include_mesh=False)

    graph = spark_dsg_to_graph(path)
    (obj,) = list(graph.objects())
    assert obj.label == "chair" and obj.room_id == "room:1"
    assert obj.bbox.min == pytest.approx((3.95, -0.15, 0.0))
    assert obj.bbox.max == pytest.approx((4.45, 0.35, 0.9))
    assert [(e.src, e.dst) for e in graph.edges(EdgeKind.CONNECTS)] == [("room:0", "room:1")]


def test_export_refuses_other_targets(two_storeys: SceneGraph, tmp_path: Path) -> None:
    with MapStore.create(tmp_path / "m") as store:
        store.write_changes(two_storeys)
    proc = run(
        "export", "--format", "spark-dsg", "--map", str(tmp_path / "m"), "x.bin", check=False
    )
    assert proc.returncode == 2 and "must be a .json file" in proc.stderr
    proc = run("export", "--format", "dot", "--map", str(tmp_path / "m"), "x.json", check=False)
    assert proc.returncode == 2 and "unknown export format" in proc.stderr
