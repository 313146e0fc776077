"""How MP3D objects are drawn: thin fronts inside a cabinet box, a pillow inside a bed box,
a tall rug box and a light above the ceiling, in a small hand-written ``.house`` file
rendered at low resolution."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.ingest.mp3d_dataset import HouseWorld, load_house_world
from inherit_sg.ingest.mp3d_drawn import PROUD, Drawn
from inherit_sg.ingest.mp3d_visibility import visibility_table, walk_visibility
from inherit_sg.ingest.mp3d_world import build_house_world
from inherit_sg.ingest.synthetic.generate import make_intrinsics
from inherit_sg.ingest.synthetic.render import Renderer
from inherit_sg.ingest.synthetic.trajectory import camera_pose

# (raw name, mpcat40 index, mpcat40 name)
CATEGORIES = [
    ("kitchen#cabinet", 7, "cabinet"),
    ("oven", 37, "appliances"),
    ("dishwasher", 37, "appliances"),
    ("bed", 11, "bed"),
    ("pillow", 8, "cushion"),
    ("rug", 2, "floor"),
    ("light", 28, "lighting"),
]
# (category, centre, radii): axis-aligned boxes in one 4 m × 4 m kitchen, 2.5 m high.
OBJECTS = [
    (0, (2.0, 0.3, 0.45), (1.5, 0.3, 0.45)),  # o0 cabinet against the south wall, front y=0.6
    (1, (2.95, 0.5, 0.45), (0.35, 0.05, 0.35)),  # o1 oven: 10 cm deep, front 5 cm behind
    (2, (1.1, 0.55, 0.45), (0.3, 0.05, 0.4)),  # o2 dishwasher: front flush with the cabinet
    (3, (2.0, 3.25, 0.45), (1.0, 0.75, 0.45)),  # o3 bed box with its headboard, top 0.9
    (4, (2.0, 3.65, 0.6), (0.4, 0.15, 0.1)),  # o4 pillow inside the bed box
    (5, (2.0, 1.7, 0.25), (1.0, 0.5, 0.25)),  # o5 rug annotated as a 0.5 m tall box
    (6, (3.0, 2.0, 2.52), (0.2, 0.2, 0.02)),  # o6 light above the 2.5 m ceiling
]


def write_kitchen(path: Path) -> Path:
    lines = ["ASCII 1.1", "L  0  1  -  2 2 0  0 0 0  4 4 2.5  0 0 0 0 0"]
    lines.append("R  0 0  0 0  k  2 2 0  0 0 0  4 4 2.5  2.5  0 0 0 0")
    lines.append("S  0 0  0  F  2 2 0  0 0 1  0 0 0  4 4 0  0 0 0 0 0")
    for v, (x, y) in enumerate(((0, 0), (4, 0), (4, 4), (0, 4))):
        lines.append(f"V  {v} 0  F  {x} {y} 0  0 0 1  0 0 0")
    for i, (raw, k, name) in enumerate(CATEGORIES):
        lines.append(f"C  {i}  {i + 1} {raw}  {k} {name}  0 0 0 0 0")
    for i, (cat, c, r) in enumerate(OBJECTS):
        nums = " ".join(str(float(x)) for x in (*c, 1, 0, 0, 0, 1, 0, *r))
        lines.append(f"O  {i} 0 {cat}  {nums}  0 0 0 0 0 0 0 0")
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture(scope="module")
def kitchen(tmp_path_factory: pytest.TempPathFactory) -> HouseWorld:
    return load_house_world(write_kitchen(tmp_path_factory.mktemp("mp3d") / "kitchen.house"))


def _span(drawn: Drawn) -> tuple[np.ndarray, np.ndarray]:
    corners = np.concatenate([p.corners() for p in drawn.parts])
    return corners.min(axis=0), corners.max(axis=0)


def test_buried_boxes_are_drawn_proud_of_what_buries_them(kitchen: HouseWorld) -> None:
    drawn = kitchen.drawn
    assert drawn["o0"].notes == [] and drawn["o3"].notes == []  # the containers stay
    for oid in ("o1", "o2"):  # thin fronts come out through the cabinet's front
        assert drawn[oid].exposure < 0.15
        assert drawn[oid].note.startswith("proud of o0") and "(+y side)" in drawn[oid].note
        lo, hi = _span(drawn[oid])
        assert 0.6 + PROUD - 1e-6 <= hi[1] < 0.65
        assert lo[1] == pytest.approx(kitchen.house.boxes[oid].corners()[:, 1].min())
    pillow_lo, pillow_hi = _span(drawn["o4"])  # the pillow rises out of the bed's top
    assert "proud of o3" in drawn["o4"].note and "(top)" in drawn["o4"].note
    assert 0.9 < pillow_hi[2] < 1.0 and pillow_lo[2] == pytest.approx(0.5)
    assert drawn["o5"].notes == ["flattened"]
    assert _span(drawn["o5"])[1][2] == pytest.approx(0.02)
    assert drawn["o6"].notes == ["under ceiling"]
    assert _span(drawn["o6"])[1][2] == pytest.approx(2.49)
    # The ground truth keeps the file's boxes and says what was drawn differently.
    oven = kitchen.scene.object("o1")
    assert oven.bbox_max[1] == pytest.approx(0.55) and "proud of o0" in oven.attributes["drawn"]
    assert "drawn" not in kitchen.scene.object("o0").attributes


def test_thin_fronts_and_pillow_get_their_own_instance_ids(kitchen: HouseWorld) -> None:
    k = make_intrinsics(64, 48)
    ids = {o.id: o.instance_id for o in kitchen.scene.objects}
    # Standing in the middle of the kitchen, looking south and down at the cabinet.
    pose = camera_pose(2.0, 2.4, 1.4, -math.pi / 2, math.radians(35))
    drawn = Renderer(kitchen.world, kitchen.lights, k).render(pose).instances
    for oid in ("o0", "o1", "o2"):
        assert (drawn == ids[oid]).sum() >= 20, oid
    # The same view of the boxes as annotated: the cabinet hides the recessed oven (the
    # flush dishwasher front shares the cabinet's plane: which one shows is a coin toss).
    raw = {
        o.id: Drawn(o.id, [kitchen.house.boxes[o.id]])
        for o in kitchen.scene.objects
        if o.id in kitchen.house.boxes
    }
    world = build_house_world(kitchen.house, kitchen.levels, kitchen.walls, raw)
    hidden = Renderer(world, kitchen.lights, k).render(pose).instances
    assert (hidden == ids["o0"]).sum() > 0
    assert (hidden == ids["o1"]).sum() == 0
    # Looking north and down at the bed: the pillow shows on top of it.
    bed_view = camera_pose(2.0, 1.8, 1.4, math.pi / 2, math.radians(30))
    on_bed = Renderer(kitchen.world, kitchen.lights, k).render(bed_view).instances
    assert (on_bed == ids["o4"]).sum() >= 10 and (on_bed == ids["o3"]).sum() > 0


def test_walk_visibility_counts_true_instance_pixels(kitchen: HouseWorld) -> None:
    sights = walk_visibility(kitchen, width=48, height=36, max_frames=40)
    assert [s.object_id for s in sights] == [o.id for o in kitchen.scene.objects]
    by_id = {s.object_id: s for s in sights}
    assert by_id["o0"].max_pixels > 0 and by_id["o0"].frames(1) >= by_id["o0"].frames(50)
    assert all(0 <= f < 40 for s in sights for f in s.pixels)
    rows = visibility_table(sights, (1, 30))
    frames = rows[0]["frames"]
    assert rows[0]["id"] == "o0" and isinstance(frames, dict) and set(frames) == {"1", "30"}
    with pytest.raises(TypeError):
        walk_visibility(object())
