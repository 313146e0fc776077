"""Spark-DSG (Hydra) JSON import into the scene-graph model."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from inherit_sg.errors import DatasetError
from inherit_sg.exchange.spark_dsg import load_label_space, spark_dsg_to_graph
from inherit_sg.model import EdgeKind, Layer, ObjectNode


def test_real_apartment(real_data: Path) -> None:
    graph = spark_dsg_to_graph(real_data / "spark_dsg" / "apartment_dsg.json")
    objects = list(graph.objects())
    assert len(objects) == 7
    assert len(list(graph.nodes(Layer.ROOM))) == 1
    assert len(list(graph.nodes(Layer.FLOOR))) == 1
    # every object hangs under floor -> room -> area
    for obj in objects:
        area = graph.parent(obj.id)
        assert area is not None and graph.parent(area) == "room:0"
        assert obj.bbox.contains(obj.position, margin=1e-6)
    first = next(o for o in objects if o.attributes["source_name"] == "O(0)")
    assert first.label == "class 5"
    assert first.position == pytest.approx((-13.2168, -3.7464, 1.4928), abs=1e-3)
    assert first.bbox.min == pytest.approx((-13.7204, -4.3097, 0.9992), abs=1e-3)


def test_label_space_names_labels(real_data: Path, tmp_path: Path) -> None:
    names = tmp_path / "labels.csv"
    names.write_text("5,chair\n11,lamp\n16,plant\n")
    graph = spark_dsg_to_graph(
        real_data / "spark_dsg" / "apartment_dsg.json", load_label_space(names)
    )
    assert sorted({o.label for o in graph.objects()}) == ["chair", "lamp", "plant"]


def _write(tmp_path: Path, data: object) -> Path:
    path = tmp_path / "g.json"
    path.write_text(json.dumps(data))
    return path


def test_object_without_room_goes_to_unassigned(tmp_path: Path) -> None:
    data = {
        "nodes": [
            {
                "id": 1,
                "layer": 2,
                "attributes": {
                    "type": "ObjectNodeAttributes",
                    "position": [1, 2, 3],
                    "semantic_label": 3,
                },
            },
        ],
        "edges": [],
        "metadata": {"labelspace": {"3": "table"}},
    }
    graph = spark_dsg_to_graph(_write(tmp_path, data))
    (obj,) = list(graph.objects())
    assert isinstance(obj, ObjectNode) and obj.label == "table"
    assert obj.room_id == "room:unassigned"
    assert [e.src for e in graph.in_edges("room:unassigned", EdgeKind.HAS_ROOM)] == ["floor:0"]


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("{not json", "invalid JSON"),
        ('{"edges": []}', "no 'nodes' list"),
        ('{"nodes": [{"layer": 2}]}', "integer id"),
    ],
)
def test_malformed_files(tmp_path: Path, content: str, message: str) -> None:
    path = tmp_path / "bad.json"
    path.write_text(content)
    with pytest.raises(DatasetError, match=message):
        spark_dsg_to_graph(path)
    with pytest.raises(DatasetError, match="not found"):
        spark_dsg_to_graph(tmp_path / "missing.json")
