"""The ray-casting renderer: depth against known geometry, instance ids, shading."""

from __future__ import annotations

import numpy as np
import pytest

from inherit_sg.ingest.synthetic.generate import generate_house, make_intrinsics
from inherit_sg.ingest.synthetic.geom import Rect
from inherit_sg.ingest.synthetic.placement import Placed
from inherit_sg.ingest.synthetic.plan import WALL_T, FloorPlan, HousePlan, RoomPlan
from inherit_sg.ingest.synthetic.render import Renderer
from inherit_sg.ingest.synthetic.trajectory import camera_pose
from inherit_sg.ingest.synthetic.walls import build_walls
from inherit_sg.ingest.synthetic.world import build_world


def _box_room() -> tuple[HousePlan, Placed]:
    """A 4 m × 3 m closed room with one cabinet against its east wall."""
    floor = FloorPlan(index=0, z=0.0, height=2.8)
    floor.rooms.append(RoomPlan("r0_0", "bedroom", 0, Rect(0.0, 0.0, 4.0, 3.0), "bedroom"))
    plan = HousePlan(footprint=Rect(0.0, 0.0, 4.0, 3.0), level_spacing=3.0, floors=[floor])
    build_walls(plan, floor)
    cabinet = Placed(
        label="cabinet", floor=0, room_id="r0_0", x=3.5, y=1.5, z=0.0,
        dims=(0.9, 0.45, 0.9), quarter=3, colour="red", material="wood", id="o1", instance_id=1,
    )  # fmt: skip
    return plan, cabinet


@pytest.fixture(scope="module")
def room_renderer() -> Renderer:
    plan, cabinet = _box_room()
    world = build_world(plan, [cabinet], np.random.default_rng(0))
    return Renderer(world, plan, make_intrinsics(160, 120))


def test_depth_of_a_facing_wall_is_its_distance(room_renderer):
    # Camera at x = 1 looking along +x, level: the east wall's face is at x = 4 - t/2.
    out = room_renderer.render(camera_pose(1.0, 1.5, 1.4, 0.0, 0.0))
    expected = 4.0 - WALL_T / 2 - 1.0
    # Rays within ±0.45 of the axis (in both directions) hit the east wall above the cabinet.
    k = room_renderer.intrinsics
    du, dv = int(0.45 * k.fx), int(0.45 * k.fy)
    patch = out.depth[int(k.cy) - dv : int(k.cy), int(k.cx) - du : int(k.cx) + du]
    assert patch.size > 500
    assert np.allclose(patch, expected, atol=2e-3)
    assert not out.instances[int(k.cy) - dv : int(k.cy)].any()
    assert out.depth.dtype == np.float32 and out.instances.dtype == np.uint16
    assert out.rgb.shape == (120, 160, 3) and out.rgb.dtype == np.uint8


def test_instances_mark_the_object_and_its_depth(room_renderer):
    out = room_renderer.render(camera_pose(1.0, 1.5, 1.4, 0.0, 0.0))
    mask = out.instances == 1
    assert mask.sum() > 200
    front = 3.5 - 0.45 / 2 - 1.0  # the cabinet's front face
    depths = out.depth[mask]
    assert depths.min() == pytest.approx(front, abs=0.01)
    assert depths.max() < 3.5 + 0.45 / 2 - 1.0 + 0.01
    assert set(np.unique(out.instances)) == {0, 1}


def test_shading_varies_over_a_flat_coloured_object(room_renderer):
    out = room_renderer.render(camera_pose(1.0, 1.5, 1.4, 0.0, 0.0))
    red = out.rgb[out.instances == 1].astype(float)
    assert red[:, 0].mean() > red[:, 1].mean() + 40  # still reads as red
    assert np.ptp(red[:, 0]) > 25  # top and front faces are lit differently
    face = 3.5 - 0.45 / 2 - 1.0
    front = out.rgb[(out.instances == 1) & (np.abs(out.depth - face) < 0.005)].astype(float)
    assert len(front) > 50
    assert front[:, 0].std() > 1.0  # light falloff and texture within one face


def test_render_is_deterministic(room_renderer):
    pose = camera_pose(2.0, 1.0, 1.3, 0.7, 0.2)
    a, b = room_renderer.render(pose), room_renderer.render(pose)
    assert np.array_equal(a.rgb, b.rgb) and np.array_equal(a.depth, b.depth)


def test_pixels_back_project_into_their_object_boxes():
    house = generate_house(7, 2)
    traj = house.trajectory()
    k = make_intrinsics(120, 90)
    renderer = Renderer(house.world, house.plan, k)
    boxes = {o.instance_id: o for o in house.scene.objects}
    checked = 0
    for pose in traj.poses[::40]:
        out = renderer.render(pose)
        v, u = np.nonzero(out.instances)
        z = out.depth[v, u]
        pts = np.stack([(u - k.cx) / k.fx * z, (v - k.cy) / k.fy * z, z], axis=1)
        world = pose.transform_points(pts)
        for inst in np.unique(out.instances[v, u]):
            obj = boxes[int(inst)]
            sel = world[out.instances[v, u] == inst]
            assert np.all(sel >= np.array(obj.bbox_min) - 0.02), obj.label
            assert np.all(sel <= np.array(obj.bbox_max) + 0.02), obj.label
            checked += 1
    assert checked > 20
