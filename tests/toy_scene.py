"""A tiny ray-cast renderer of coloured boxes in a walled room, producing real posed
RGB-D :class:`Frame` objects with instance images.

It exists so perception backends can be tested and benchmarked on frames whose truth
is known (which pixels belong to which box, what colour it is) without any dataset:
Lambertian shading, optional face patterns, optional RGB and depth noise.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from inherit_sg.model import Frame, Intrinsics, Pose
from inherit_sg.perception.colour_names import linear_to_srgb, srgb_to_linear

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class ToyBox:
    """A box standing in the room: centre and full size in metres (world, z up), yaw
    about z in radians, sRGB albedo, and the amplitude of a checker pattern on its faces."""

    label: str
    centre: Vec3
    size: Vec3
    colour: tuple[int, int, int]
    yaw: float = 0.0
    pattern: float = 0.0


@dataclass(frozen=True)
class ToyRoom:
    """Axis-aligned room: floor at z = 0, walls at the x/y bounds, a ceiling."""

    x_range: tuple[float, float] = (-3.0, 3.0)
    y_range: tuple[float, float] = (-1.0, 4.0)
    height: float = 2.6
    wall_colour: tuple[int, int, int] = (200, 200, 195)
    floor_colour: tuple[int, int, int] = (150, 120, 90)


def toy_intrinsics(width: int = 160, height: int = 120, hfov_deg: float = 70.0) -> Intrinsics:
    """Pinhole intrinsics with the given horizontal field of view."""
    fx = (width / 2.0) / np.tan(np.radians(hfov_deg) / 2.0)
    return Intrinsics(width, height, fx, fx, (width - 1) / 2.0, (height - 1) / 2.0, 1000.0)


def look_at(eye: Sequence[float], target: Sequence[float]) -> Pose:
    """``T_world_camera`` of an OpenCV camera at ``eye`` looking at ``target`` (z up)."""
    e, t = np.asarray(eye, dtype=float), np.asarray(target, dtype=float)
    f = (t - e) / np.linalg.norm(t - e)
    r = np.cross(f, [0.0, 0.0, 1.0])
    r /= np.linalg.norm(r)
    d = np.cross(f, r)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = r, d, f, e
    return Pose.from_matrix(m)


def _room_hit(o: np.ndarray, d: np.ndarray, room: ToyRoom) -> tuple[np.ndarray, np.ndarray]:
    """Distance to the room's inside surface along each ray, and the axis hit (0 x, 1 y,
    2 floor, 3 ceiling)."""
    lo = np.array([room.x_range[0], room.y_range[0], 0.0])
    hi = np.array([room.x_range[1], room.y_range[1], room.height])
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(d > 0, (hi - o) / d, np.where(d < 0, (lo - o) / d, np.inf))
    axis = np.argmin(t, axis=1)
    dist = t[np.arange(len(t)), axis]
    axis = np.where((axis == 2) & (d[:, 2] > 0), 3, axis)
    return dist, axis


def _box_hit(
    o: np.ndarray, d: np.ndarray, box: ToyBox
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Entry distance (inf on a miss), world normal and local hit point of each ray."""
    c, s = np.cos(box.yaw), np.sin(box.yaw)
    rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])  # local → world
    ol = (o - np.asarray(box.centre)) @ rot
    dl = d @ rot
    half = np.asarray(box.size) / 2.0
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (-half - ol) / dl, (half - ol) / dl
    tmin, tmax = np.minimum(t1, t2), np.maximum(t1, t2)
    tmin = np.where(np.isnan(tmin), -np.inf, tmin)
    tmax = np.where(np.isnan(tmax), np.inf, tmax)
    axis = np.argmax(tmin, axis=1)
    near = tmin[np.arange(len(o)), axis]
    far = tmax.min(axis=1)
    hit = (near <= far) & (near > 1e-6)
    dist = np.where(hit, near, np.inf)
    normal_l = np.zeros_like(o)
    normal_l[np.arange(len(o)), axis] = -np.sign(dl[np.arange(len(o)), axis])
    local = ol + dl * np.where(hit, near, 0.0)[:, None]
    return dist, normal_l @ rot.T, local


def render_toy_frame(
    boxes: Sequence[ToyBox],
    pose: Pose,
    intrinsics: Intrinsics | None = None,
    room: ToyRoom | None = None,
    light: Vec3 = (0.4, -0.6, 0.8),
    rgb_noise: float = 0.0,
    depth_noise: float = 0.0,
    seed: int = 0,
    index: int = 0,
) -> Frame:
    """Render one frame; box ``i`` gets instance id ``i + 1`` (room surfaces are 0)."""
    k = intrinsics or toy_intrinsics()
    room = room or ToyRoom()
    vs, us = np.mgrid[0 : k.height, 0 : k.width].astype(np.float64)
    d_cam = np.stack([(us - k.cx) / k.fx, (vs - k.cy) / k.fy, np.ones_like(us)], -1).reshape(-1, 3)
    d = d_cam @ pose.rotation.T  # unnormalised: the ray parameter equals camera depth
    o = np.broadcast_to(pose.translation, d.shape)
    dist, axis = _room_hit(o, d, room)
    normals = np.zeros_like(d)
    normals[np.arange(len(d)), np.minimum(axis, 2)] = -np.sign(
        d[np.arange(len(d)), np.minimum(axis, 2)]
    )
    albedo = np.where(
        (axis == 2)[:, None], srgb_to_linear(room.floor_colour), srgb_to_linear(room.wall_colour)
    )
    ids = np.zeros(len(d), dtype=np.uint16)
    for i, box in enumerate(boxes):
        bd, bn, local = _box_hit(o, d, box)
        closer = bd < dist
        dist = np.where(closer, bd, dist)
        normals[closer] = bn[closer]
        ids[closer] = i + 1
        checker = (np.floor(local[closer] / 0.1).sum(axis=1) % 2) * 2 - 1
        shade = 1.0 + box.pattern * checker
        albedo[closer] = srgb_to_linear(box.colour) * shade[:, None]
    light_dir = np.asarray(light) / np.linalg.norm(light)
    lambert = 0.35 + 0.65 * np.clip(normals @ light_dir, 0.0, 1.0)
    rng = np.random.default_rng(seed)
    rgb = linear_to_srgb(albedo * lambert[:, None])
    if rgb_noise > 0:
        rgb = rgb + rng.normal(0.0, rgb_noise, rgb.shape)
    depth = dist.astype(np.float32)
    if depth_noise > 0:
        depth = depth * (1.0 + rng.normal(0.0, depth_noise, depth.shape).astype(np.float32))
    shape = (k.height, k.width)
    return Frame(
        index=index,
        frame_id=f"toy{index:04d}",
        timestamp=float(index),
        rgb=np.clip(rgb + 0.5, 0, 255).astype(np.uint8).reshape(*shape, 3),
        depth=np.maximum(depth, 0.0).reshape(shape),
        pose=pose,
        intrinsics=k,
        instances=ids.reshape(shape),
        instance_labels={i + 1: b.label for i, b in enumerate(boxes)},
    ).validate()
