"""MP3D house → world: polygons, walls and openings, mesh, lights, walk and the reader,
on a small hand-written ``.house`` file (four rooms, one door, one open plan)."""

from __future__ import annotations

import math
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.mp3d_dataset import HouseWorld, load_house_world
from inherit_sg.ingest.mp3d_polygons import clean_ccw, contains, signed_area, triangulate
from inherit_sg.ingest.mp3d_walk import free_space
from inherit_sg.ingest.mp3d_world import colour_name
from inherit_sg.ingest.readers import detect_format, open_dataset
from inherit_sg.ingest.synthetic.generate import make_intrinsics
from inherit_sg.ingest.synthetic.render import Renderer
from inherit_sg.ingest.synthetic.trajectory import camera_pose

# Regions (code, x0, y0, x1, y1): bedroom | living (door between them), kitchen open to the
# living room, a bathroom that only a wall separates from everything.
ROOMS = [
    ("b", 0.0, 0.0, 4.0, 3.0),
    ("l", 4.1, 0.0, 8.0, 3.0),
    ("k", 4.1, 3.05, 8.0, 6.0),
    ("a", 0.0, 3.1, 4.0, 6.0),
]
# Objects: (region, category, centre, axis0, axis1, radii)
OBJECTS = [
    (0, 1, (1.5, 1.5, 0.3), (1, 0, 0), (0, 1, 0), (0.9, 0.8, 0.3)),  # bed
    (0, 2, (4.05, 1.45, 1.0), (0, 0, 1), (0, 1, 0), (1.0, 0.45, 0.05)),  # door in the wall
    (2, 3, (6.0, 5.0, 0.45), (1, 0, 0), (0, 1, 0), (0.6, 0.4, 0.45)),  # table
    (3, 4, (1.0, 5.5, 0.4), (1, 0, 0), (0, 1, 0), (0.2, 0.25, 0.4)),  # toilet
    (1, 0, (6.0, 1.5, 1.4), (1, 0, 0), (0, 1, 0), (2, 1, 1)),  # a wall box: structure
]
CATEGORIES = ["wall", "bed", "door", "table", "toilet"]


# A second storey 3 m up: an office beside a hallway, a table in the office.
UPSTAIRS = [
    "L  1  2  -  4 3 3  0 0 3  8 6 5.8  0 0 0 0 0",
    "R  4 1  0 0  o  2 1.5 3  0 0 3  4 3 5.5  2.5  0 0 0 0",
    "S  4 4  0  F  0 0 3  0 0 1  0 0 3  4 3 3  0 0 0 0 0",
    *(
        f"V  {16 + k} 4  F  {x} {y} 3  0 0 1  0 0 0"
        for k, (x, y) in enumerate([(0, 0), (4, 0), (4, 3), (0, 3)])
    ),
    "R  5 1  0 0  h  6 1.5 3  4.1 0 3  8 3 5.5  2.5  0 0 0 0",
    "S  5 5  0  F  0 0 3  0 0 1  4.1 0 3  8 3 3  0 0 0 0 0",
    *(
        f"V  {20 + k} 5  F  {x} {y} 3  0 0 1  0 0 0"
        for k, (x, y) in enumerate([(4.1, 0), (8, 0), (8, 3), (4.1, 3)])
    ),
    "O  9 4 3  2 1.5 3.45  1 0 0  0 1 0  0.6 0.4 0.45  0 0 0 0 0 0 0 0",
]


def write_house(path: Path, extra: list[str] | None = None) -> Path:
    lines = ["ASCII 1.1", "H  test  -  0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0  0 0 0  8 6 2.8  0 0 0 0 0"]
    lines.append("L  0  4  -  4 3 0  0 0 0  8 6 2.8  0 0 0 0 0")
    v = 0
    for i, (code, x0, y0, x1, y1) in enumerate(ROOMS):
        centre = f"{(x0 + x1) / 2} {(y0 + y1) / 2} 0"
        lines.append(f"R  {i} 0  0 0  {code}  {centre}  {x0} {y0} 0  {x1} {y1} 2.5  2.5  0 0 0 0")
        lines.append(f"S  {i} {i}  0  F  0 0 0  0 0 1  {x0} {y0} 0  {x1} {y1} 0  0 0 0 0 0")
        for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1)):
            lines.append(f"V  {v} {i}  F  {x} {y} 0  0 0 1  0 0 0")
            v += 1
    for i, name in enumerate(CATEGORIES):
        lines.append(f"C  {i}  {i + 1} {name}  {i + 1} {name}  0 0 0 0 0")
    for i, (region, cat, c, a0, a1, r) in enumerate(OBJECTS):
        nums = " ".join(str(float(x)) for x in (*c, *a0, *a1, *r))
        lines.append(f"O  {i} {region} {cat}  {nums}  0 0 0 0 0 0 0 0")
    path.write_text("\n".join([*lines, *(extra or [])]) + "\n")
    return path


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> HouseWorld:
    return load_house_world(write_house(tmp_path_factory.mktemp("mp3d") / "small.house"))


def test_polygons_triangulate_and_contain() -> None:
    l_shape = np.array([[0, 0], [0, 2], [1, 2], [1, 1], [3, 1], [3, 0]], float)  # clockwise
    poly = clean_ccw([[*p] for p in l_shape] + [[3.0, 0.0]])  # repeated last vertex dropped
    assert len(poly) == 6 and signed_area(poly) == pytest.approx(4.0)
    tris = triangulate(poly)
    assert tris.shape == (4, 3)
    areas = [signed_area(poly[t]) for t in tris]
    assert all(a > 0 for a in areas) and sum(areas) == pytest.approx(4.0)
    inside = contains(poly, np.array([[0.5, 1.5], [2.0, 0.5], [2.0, 1.5], [-1.0, 0.5]]))
    assert inside.tolist() == [True, True, False, False]


def test_openings_follow_doors_open_plans_and_connectivity(small: HouseWorld) -> None:
    kinds = {frozenset(o.rooms): o.kind for o in small.walls.openings}
    assert kinds[frozenset(("r0", "r1"))] == "door"  # bedroom | living: the door's gap
    assert kinds[frozenset(("r1", "r2"))] == "open"  # living | kitchen: open plan
    # The bathroom had no door: one doorway is inferred, into the open-plan kitchen.
    assert kinds[frozenset(("r2", "r3"))] == "doorway"
    assert len(kinds) == 3
    door = next(o for o in small.walls.openings if o.kind == "door")
    assert door.door_id == "o1" and door.width == pytest.approx(0.9, abs=0.01)
    assert door.centre == pytest.approx([4.05, 1.45], abs=0.01)
    scene = small.scene
    assert len(scene.doors) == 3 and {tuple(sorted(d.rooms)) for d in scene.doors} >= {
        ("r0", "r1"),
        ("r1", "r2"),
    }
    # Wall pieces at walking height never cross the door gap.
    for w in small.walls.walls:
        if w.z0 < 1.0 and abs(w.a[0] - w.b[0]) < 1e-6 and 3.9 < w.a[0] < 4.2:
            lo, hi = sorted((w.a[1], w.b[1]))
            assert hi <= 1.0 + 1e-6 or lo >= 1.9 - 1e-6


def test_scene_keeps_file_coordinates_and_gets_colours(small: HouseWorld) -> None:
    scene = small.scene
    assert [r.type for r in scene.rooms] == ["bedroom", "living room", "kitchen", "bathroom"]
    labels = {o.label for o in scene.objects}
    assert labels == {"bed", "door", "table", "toilet"}  # the wall box is structure
    bed = next(o for o in scene.objects if o.label == "bed")
    assert bed.centroid == [1.5, 1.5, 0.3]
    assert bed.bbox_min == pytest.approx([0.6, 0.7, 0.0]) and bed.bbox_max == pytest.approx(
        [2.4, 2.3, 0.6]
    )
    assert bed.attributes["colour"] == colour_name("bed") == colour_name("bed")
    assert all(o.attributes["colour"] for o in scene.objects)


def test_depth_matches_walls_door_gap_and_objects(small: HouseWorld) -> None:
    k = make_intrinsics(64, 48)
    renderer = Renderer(small.world, small.lights, k)
    cu, cv = round(k.cx), round(k.cy)
    # From the bedroom, looking +x level: through the door gap to the living room's far wall.
    through = renderer.render(camera_pose(2.0, 1.45, 1.0, 0.0, 0.0))
    assert through.depth[cv, cu] == pytest.approx(8.0 - 2.0, abs=0.02)
    # Beside the gap the bedroom's own east wall stands at x = 4.
    wall = renderer.render(camera_pose(2.0, 2.5, 1.0, 0.0, 0.0))
    assert wall.depth[cv, cu] == pytest.approx(2.0, abs=0.02)
    assert wall.instances[cv, cu] == 0
    # Looking down at the bed from above: its top at z = 0.6.
    down = renderer.render(camera_pose(1.5, 1.5, 2.0, 0.0, math.pi / 2))
    bed = next(o for o in small.scene.objects if o.label == "bed")
    assert down.instances[cv, cu] == bed.instance_id
    assert down.depth[cv, cu] == pytest.approx(1.4, abs=0.02)
    # The door is a frame: its jambs are door pixels, its middle is open.
    assert through.instances[cv, cu] == 0
    door = next(o for o in small.scene.objects if o.label == "door")
    assert (through.instances == door.instance_id).sum() > 10


def test_lights_are_per_region(small: HouseWorld) -> None:
    pts = np.array([[1.0, 1.0, 1.0], [6.0, 1.0, 1.0], [6.0, 5.0, 1.0], [1.0, 5.0, 1.0]])
    rooms = small.lights.room_index(pts)
    assert rooms.tolist() == [0, 1, 2, 3]
    assert small.lights.room_index(np.array([[20.0, 20.0, 1.0]]))[0] == small.lights.outside
    assert small.lights.pos[0] == pytest.approx([2.0, 1.5, 2.2])


def test_walk_visits_every_room_and_stays_free(small: HouseWorld) -> None:
    traj = small.trajectory(3)
    assert set(traj.rooms) >= {"r0", "r1", "r2", "r3"}
    looks = traj.activity.count("look")
    # one look-around per room at least; rooms that one stop does not see get more
    assert 40 < len(traj) < 300 and looks % 12 == 0 and 4 * 12 <= looks <= 4 * 4 * 12
    looking_up = [
        p
        for p, a in zip(traj.poses, traj.activity, strict=True)
        if a == "look" and p.rotation[2, 2] > 0.2
    ]
    assert len(looking_up) == looks // 2  # every other frame of a look-around tilts up
    space = small.spaces[0]
    free = free_space(space, small.walls.walls)
    eye = []
    for pose in traj.poses:
        x, y, z = pose.translation
        assert free[space.grid.cell(x, y)]
        eye.append(z)
    assert min(eye) > 1.25 and max(eye) < 1.55
    yaws = [math.atan2(p.rotation[1, 2], p.rotation[0, 2]) for p in traj.poses]
    steps = [abs((b - a + math.pi) % (2 * math.pi) - math.pi) for a, b in pairwise(yaws)]
    assert max(steps) < math.radians(36)
    again = small.trajectory(3)
    assert [p.to_list() for p in again.poses] == [p.to_list() for p in traj.poses]
    other = small.trajectory(4)
    assert [p.to_list() for p in other.poses] != [p.to_list() for p in traj.poses]


def test_levels_are_walked_lowest_first(tmp_path: Path) -> None:
    house = load_house_world(write_house(tmp_path / "two.house", UPSTAIRS))
    assert [(lv.index, lv.z) for lv in house.levels] == [(0, 0.0), (1, 3.0)]
    assert {frozenset(o.rooms) for o in house.walls.openings} >= {frozenset(("r4", "r5"))}
    traj = house.trajectory(0)
    first_up = traj.floors.index(1)
    assert set(traj.floors[first_up:]) == {1} and set(traj.floors[:first_up]) == {0}
    assert {r for r in traj.rooms[first_up:] if r} == {"r4", "r5"}
    zs = np.array([p.translation[2] for p in traj.poses])
    assert zs[:first_up].max() < 1.6 and zs[first_up:].min() > 4.2
    points = np.array([[1.0, 1.0, 1.0], [1.0, 1.0, 4.0], [6.0, 1.0, 4.0]])
    assert house.lights.room_index(points).tolist() == [0, 4, 5]


def test_reader_renders_the_walk(tmp_path: Path) -> None:
    house_file = write_house(tmp_path / "x.house")
    assert detect_format(house_file) == "mp3d" and detect_format(tmp_path) == "mp3d"
    reader = open_dataset(house_file, width=32, height=24, max_frames=4, noise="noisy")
    assert reader.format_name == "mp3d" and len(reader) == 4
    frames = list(reader)
    assert all(f.rgb.shape == (24, 32, 3) and f.instances is not None for f in frames)
    depth = frames[0].depth
    assert depth.max() > 0.5 and np.allclose(depth * 1000, np.round(depth * 1000), atol=1e-3)
    again = open_dataset(house_file, width=32, height=24, max_frames=4, noise="noisy").read(3)
    assert np.array_equal(again.rgb, frames[3].rgb) and again.pose == frames[3].pose
    with pytest.raises(IndexError):
        reader.read(4)


def test_bad_house_inputs(tmp_path: Path) -> None:
    (tmp_path / "a.house").write_text("ASCII 1.1\n")
    with pytest.raises(DatasetError, match="no regions"):
        load_house_world(tmp_path / "a.house")
    (tmp_path / "b.house").write_text("ASCII 1.1\n")
    with pytest.raises(DatasetError, match=r"expected one \.house file, found 2"):
        open_dataset(tmp_path, format="mp3d")
