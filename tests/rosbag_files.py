"""Real ROS 1 / ROS 2 bags written with ``rosbags`` from an isg folder, for the rosbag
reader tests: the frames of the folder as a RealSense-like recording."""

from __future__ import annotations

import json
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import cv2
import numpy as np
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from scipy.spatial.transform import Rotation

from inherit_sg.ingest.isg import read_poses
from inherit_sg.ingest.readers.rosbag_msgs import BODY_FROM_OPTICAL

RGB = "/camera/color/image_raw"
RGB_COMPRESSED = "/camera/color/image_raw/compressed"
DEPTH = "/camera/aligned_depth_to_color/image_raw"
INFO = "/camera/color/camera_info"
POSE = "/camera/pose"
CAMERA_FRAME = "camera_color_optical_frame"
START_S = 1_700_000_000
TF_MESSAGE_MSG = "geometry_msgs/TransformStamped[] transforms"
#: the colour image comes this long after the depth image it belongs to
RGB_DELAY_NS = 4_000_000
#: base_link -> camera_link: the camera 0.2 m ahead and 1.1 m up, looking ahead
BASE_TO_CAMERA_LINK = np.array(
    [[1.0, 0, 0, 0.2], [0, 1.0, 0, 0.0], [0, 0, 1.0, 1.1], [0, 0, 0, 1.0]]
)


@dataclass
class BagSpec:
    """What to write: ROS 1 or 2, colour raw or compressed (PNG), poses as a PoseStamped
    topic or through TF, and extra or missing topics for the error cases."""

    ros1: bool = False
    compressed: bool = False
    pose: str = "topic"  # "topic", "tf" or "both"
    depth: bool = True
    second_camera: bool = False
    storage: str = "sqlite3"
    rgb_delay_ns: int = RGB_DELAY_NS


class _Bag:
    """A bag being written: connections by topic and the right serialiser."""

    def __init__(self, writer: Any, spec: BagSpec) -> None:
        self.writer = writer
        self.ros1 = spec.ros1
        self.store = get_typestore(Stores.ROS1_NOETIC if spec.ros1 else Stores.ROS2_HUMBLE)
        if spec.ros1:  # rosbags' Noetic store has no tf2_msgs: add it from its .msg text
            self.store.register(get_types_from_msg(TF_MESSAGE_MSG, "tf2_msgs/msg/TFMessage"))
        self.types = self.store.types
        self.connections: dict[str, Any] = {}

    def header(self, stamp_ns: int, frame_id: str) -> Any:
        time = self.types["builtin_interfaces/msg/Time"](
            sec=stamp_ns // 1_000_000_000, nanosec=stamp_ns % 1_000_000_000
        )
        if self.ros1:
            return self.types["std_msgs/msg/Header"](seq=0, stamp=time, frame_id=frame_id)
        return self.types["std_msgs/msg/Header"](stamp=time, frame_id=frame_id)

    def write(self, topic: str, msg: Any, stamp_ns: int) -> None:
        msgtype = msg.__msgtype__
        if topic not in self.connections:
            self.connections[topic] = self.writer.add_connection(
                topic, msgtype, typestore=self.store
            )
        data = (
            self.store.serialize_ros1(msg, msgtype)
            if self.ros1
            else self.store.serialize_cdr(msg, msgtype)
        )
        self.writer.write(self.connections[topic], stamp_ns, data)


@contextmanager
def _open(path: Path, spec: BagSpec) -> Iterator[_Bag]:
    if spec.ros1:
        writer: Any = Writer1(path)
    else:
        from rosbags.rosbag2 import StoragePlugin

        plugin = StoragePlugin.MCAP if spec.storage == "mcap" else StoragePlugin.SQLITE3
        writer = Writer2(path, version=9, storage_plugin=plugin)
    with writer:
        yield _Bag(writer, spec)


def _image(bag: _Bag, stamp: int, pixels: np.ndarray, encoding: str) -> Any:
    height, width = pixels.shape[:2]
    data = np.ascontiguousarray(pixels).view(np.uint8).reshape(-1)
    return bag.types["sensor_msgs/msg/Image"](
        header=bag.header(stamp, CAMERA_FRAME),
        height=height,
        width=width,
        encoding=encoding,
        is_bigendian=0,
        step=data.size // height,
        data=data,
    )


def _compressed(bag: _Bag, stamp: int, rgb: np.ndarray) -> Any:
    ok, png = cv2.imencode(".png", cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR))
    assert ok
    return bag.types["sensor_msgs/msg/CompressedImage"](
        header=bag.header(stamp, CAMERA_FRAME),
        format="rgb8; png compressed bgr8",
        data=png.reshape(-1),
    )


def _camera_info(bag: _Bag, stamp: int, intr: dict[str, float]) -> Any:
    k = np.array([intr["fx"], 0, intr["cx"], 0, intr["fy"], intr["cy"], 0, 0, 1], dtype=float)
    p = np.array([intr["fx"], 0, intr["cx"], 0, 0, intr["fy"], intr["cy"], 0, 0, 0, 1, 0.0])
    fields = {"d": np.zeros(5), "k": k, "r": np.eye(3).reshape(-1), "p": p}
    if bag.ros1:
        fields = {name.upper(): value for name, value in fields.items()}
    return bag.types["sensor_msgs/msg/CameraInfo"](
        header=bag.header(stamp, CAMERA_FRAME),
        height=int(intr["height"]),
        width=int(intr["width"]),
        distortion_model="plumb_bob",
        binning_x=0,
        binning_y=0,
        roi=bag.types["sensor_msgs/msg/RegionOfInterest"](
            x_offset=0, y_offset=0, height=0, width=0, do_rectify=False
        ),
        **fields,
    )


def _tq(bag: _Bag, matrix: np.ndarray) -> tuple[Any, Any]:
    x, y, z, w = Rotation.from_matrix(matrix[:3, :3]).as_quat()
    t = matrix[:3, 3]
    return (
        bag.types["geometry_msgs/msg/Vector3"](x=t[0], y=t[1], z=t[2]),
        bag.types["geometry_msgs/msg/Quaternion"](x=x, y=y, z=z, w=w),
    )


def _pose_stamped(bag: _Bag, stamp: int, matrix: np.ndarray) -> Any:
    t, q = _tq(bag, matrix)
    point = bag.types["geometry_msgs/msg/Point"](x=t.x, y=t.y, z=t.z)
    pose = bag.types["geometry_msgs/msg/Pose"](position=point, orientation=q)
    return bag.types["geometry_msgs/msg/PoseStamped"](header=bag.header(stamp, "map"), pose=pose)


def _tf(bag: _Bag, stamp: int, edges: list[tuple[str, str, np.ndarray]]) -> Any:
    transforms = []
    for parent, child, matrix in edges:
        t, q = _tq(bag, matrix)
        transforms.append(
            bag.types["geometry_msgs/msg/TransformStamped"](
                header=bag.header(stamp, parent),
                child_frame_id=child,
                transform=bag.types["geometry_msgs/msg/Transform"](translation=t, rotation=q),
            )
        )
    return bag.types["tf2_msgs/msg/TFMessage"](transforms=transforms)


def _static_edges() -> list[tuple[str, str, np.ndarray]]:
    return [
        ("map", "odom", np.eye(4)),
        ("base_link", "camera_link", BASE_TO_CAMERA_LINK),
        ("camera_link", CAMERA_FRAME, BODY_FROM_OPTICAL),
    ]


def write_bag(isg: Path, out: Path, spec: BagSpec) -> Path:
    """Write the frames of the isg folder ``isg`` into a new bag at ``out`` (a ROS 2
    folder, or a ``.bag`` file for ROS 1); frame ``i`` has depth stamp START_S + i s."""
    intr = json.loads((isg / "intrinsics.json").read_text())
    start = START_S * 1_000_000_000
    camera_in_base = BASE_TO_CAMERA_LINK @ BODY_FROM_OPTICAL
    with _open(out, spec) as bag:
        if spec.pose in ("tf", "both"):
            bag.write("/tf_static", _tf(bag, start, _static_edges()), start)
        for i, (frame_id, pose) in enumerate(read_poses(isg)):
            stamp = start + i * 1_000_000_000
            base = isg / "frames" / frame_id
            bgr = cv2.imread(f"{base}.rgb.png", cv2.IMREAD_COLOR)
            rgb = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
            rgb_stamp = stamp + spec.rgb_delay_ns
            if spec.compressed:
                bag.write(RGB_COMPRESSED, _compressed(bag, rgb_stamp, rgb), rgb_stamp)
            else:
                bag.write(RGB, _image(bag, rgb_stamp, rgb, "rgb8"), rgb_stamp)
            if spec.second_camera:
                bag.write("/camera2/color/image_raw", _image(bag, stamp, bgr, "bgr8"), stamp)
            if spec.depth:
                raw = cv2.imread(f"{base}.depth.png", cv2.IMREAD_UNCHANGED)
                bag.write(DEPTH, _image(bag, stamp, raw.astype(np.uint16), "16UC1"), stamp)
            bag.write(INFO, _camera_info(bag, stamp, intr), stamp)
            world_camera = pose.matrix
            if spec.pose in ("topic", "both"):
                bag.write(POSE, _pose_stamped(bag, stamp, world_camera), stamp)
            if spec.pose in ("tf", "both"):
                odom_base = world_camera @ np.linalg.inv(camera_in_base)
                bag.write("/tf", _tf(bag, stamp, [("odom", "base_link", odom_base)]), stamp)
    return out
