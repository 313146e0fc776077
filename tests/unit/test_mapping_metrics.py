"""Object-level mapping quality: a duplicate is an object mapped twice, not one of a few
small things standing close together."""

from __future__ import annotations

from inherit_sg.benchmark.metrics.mapping import evaluate_objects
from inherit_sg.ingest.synthetic.scene import ObjectGT, Scene
from inherit_sg.model import BBox3D, Layer, ObjectNode, make_id


def _truth(key: str, x: float) -> ObjectGT:
    return ObjectGT(
        key, 1, "bottle", None, 0, (x, 0.0, 1.0), (x - 0.03, -0.03, 0.9), (x + 0.03, 0.03, 1.1)
    )


def _node(key: str, x: float) -> ObjectNode:
    box = BBox3D((x - 0.03, -0.03, 0.9), (x + 0.03, 0.03, 1.1))
    return ObjectNode(make_id(Layer.OBJECT, key), "bottle", (x, 0.0, 1.0), box)


def test_things_side_by_side_are_no_duplicates_but_one_mapped_twice_is() -> None:
    scene = Scene("s", 0, objects=[_truth("b1", 0.0), _truth("b2", 0.15), _truth("b3", 0.3)])
    three = [_node("1", 0.0), _node("2", 0.15), _node("3", 0.3)]
    quality = evaluate_objects(three, scene)
    assert quality.matched == 3 and quality.duplicate_rate == 0.0
    twice = [*three, _node("4", 0.02)]  # the first bottle once more
    quality = evaluate_objects(twice, scene)
    assert quality.matched == 3 and quality.duplicate_rate == 1 / 4
    # a prediction with nothing of its kind nearby is a false positive, not a duplicate
    stray = [*three, _node("5", 3.0)]
    assert evaluate_objects(stray, scene).duplicate_rate == 0.0
