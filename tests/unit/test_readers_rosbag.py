"""The rosbag reader's message handling on real ``rosbags`` message objects: image
encodings, row padding, byte order, depth units, the TF chain, topic picking."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from rosbags.typesys import Stores, get_typestore
from scipy.spatial.transform import Rotation

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers import rosbag_msgs as msgs
from inherit_sg.ingest.readers.rosbag import (
    TopicInfo,
    parse_tf_pair,
    pick_camera_info,
    pick_depth,
    pick_rgb,
)
from inherit_sg.ingest.readers.rosbag_tf import TfTree

TYPES = get_typestore(Stores.ROS2_HUMBLE).types


def _image(pixels: np.ndarray, encoding: str, pad: int = 0, big: bool = False) -> Any:
    height, width = pixels.shape[:2]
    stored = pixels.astype(pixels.dtype.newbyteorder(">" if big else "<"))
    rows = np.ascontiguousarray(stored).view(np.uint8).reshape(height, -1)
    data = np.concatenate([rows, np.zeros((height, pad), np.uint8)], axis=1).reshape(-1)
    header = TYPES["std_msgs/msg/Header"](
        stamp=TYPES["builtin_interfaces/msg/Time"](sec=1, nanosec=2), frame_id="cam"
    )
    return TYPES["sensor_msgs/msg/Image"](
        header=header,
        height=height,
        width=width,
        encoding=encoding,
        is_bigendian=int(big),
        step=rows.shape[1] + pad,
        data=data,
    )


RGB = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)


@pytest.mark.parametrize(
    ("encoding", "pixels"),
    [
        ("rgb8", RGB),
        ("bgr8", RGB[..., ::-1]),
        ("rgba8", np.concatenate([RGB, np.full((2, 3, 1), 255, np.uint8)], axis=2)),
        ("bgra8", np.concatenate([RGB[..., ::-1], np.full((2, 3, 1), 9, np.uint8)], axis=2)),
    ],
)
def test_colour_encodings_give_rgb(encoding: str, pixels: np.ndarray) -> None:
    assert np.array_equal(msgs.image_to_rgb(_image(pixels, encoding, pad=3)), RGB)


def test_mono8_is_grey_rgb_and_unknown_encodings_are_refused() -> None:
    grey = RGB[..., 0]
    out = msgs.image_to_rgb(_image(grey, "mono8"))
    assert out.shape == (2, 3, 3) and np.array_equal(out[..., 2], grey)
    with pytest.raises(FrameError, match="yuv422"):
        msgs.image_to_rgb(_image(grey, "yuv422"))
    with pytest.raises(FrameError, match="too few"):
        msgs.image_to_rgb(_image(grey, "rgb8"))


def test_depth_16uc1_in_millimetres_either_byte_order_and_32fc1_in_metres() -> None:
    mm = np.array([[0, 1000, 1500], [65535, 2, 3]], dtype=np.uint16)
    want = mm.astype(np.float32) / np.float32(1000.0)
    assert np.array_equal(msgs.image_to_depth(_image(mm, "16UC1", pad=2), 0.001), want)
    assert np.array_equal(msgs.image_to_depth(_image(mm, "16UC1", big=True), 0.001), want)
    assert np.allclose(msgs.image_to_depth(_image(mm, "16UC1"), 0.0001), want / 10)
    metres = np.array([[1.5, np.nan, np.inf], [-1.0, 0.0, 2.25]], dtype=np.float32)
    depth = msgs.image_to_depth(_image(metres, "32FC1"), 0.001)
    assert depth.dtype == np.float32
    assert np.array_equal(depth, [[1.5, 0, 0], [0, 0, 2.25]])
    with pytest.raises(FrameError, match="rgb8"):
        msgs.image_to_depth(_image(RGB, "rgb8"), 0.001)


def test_stamps_and_frame_names() -> None:
    assert msgs.stamp_ns(_image(RGB, "rgb8")) == 1_000_000_002
    assert msgs.frame_name("/map") == "map"


def _matrix(rotvec: list[float], t: list[float]) -> np.ndarray:
    out = np.eye(4)
    out[:3, :3] = Rotation.from_rotvec(rotvec).as_matrix()
    out[:3, 3] = t
    return out


def test_tf_chain_composes_and_interpolates() -> None:
    tree = TfTree()
    tree.add("map", "odom", 0.0, _matrix([0, 0, 0.5], [1, 2, 0]), static=True)
    tree.add("odom", "base", 10.0, _matrix([0, 0, 0], [0, 0, 0]), static=False)
    tree.add("odom", "base", 11.0, _matrix([0, 0, 0], [1, 0, 0]), static=False)
    optical = msgs.BODY_FROM_OPTICAL @ np.eye(4)
    tree.add("base", "cam", 0.0, optical, static=True)
    tree.finish()
    assert tree.root("cam") == "map" and tree.is_dynamic("map", "cam")
    assert not tree.is_dynamic("base", "cam")
    got = tree.lookup("map", "cam", 10.5, max_dt=0.6)
    assert got is not None
    want = _matrix([0, 0, 0.5], [1, 2, 0]) @ _matrix([0, 0, 0], [0.5, 0, 0]) @ optical
    assert np.allclose(got, want)
    assert tree.lookup("map", "cam", 12.0, max_dt=0.05) is None  # no sample near t
    back = tree.lookup("cam", "odom", 10.0, max_dt=0.05)
    assert back is not None and np.allclose(back, np.linalg.inv(optical))
    assert not tree.connected("map", "elsewhere")


def test_tf_pair_parsing() -> None:
    assert parse_tf_pair("/map:camera_optical") == ("map", "camera_optical")
    with pytest.raises(DatasetError, match="PARENT:CHILD"):
        parse_tf_pair("camera_optical")


def _topics(*pairs: tuple[str, str]) -> list[TopicInfo]:
    return [TopicInfo(name, msgtype, 10) for name, msgtype in pairs]


def test_topic_picking_prefers_colour_aligned_depth_and_the_nearby_camera_info() -> None:
    topics = _topics(
        ("/camera/color/image_raw", msgs.IMAGE),
        ("/camera/color/image_raw/compressed", msgs.COMPRESSED_IMAGE),
        ("/camera/infra1/image_rect_raw", msgs.IMAGE),
        ("/camera/depth/image_rect_raw", msgs.IMAGE),
        ("/camera/aligned_depth_to_color/image_raw", msgs.IMAGE),
        ("/camera/depth/camera_info", msgs.CAMERA_INFO),
        ("/camera/color/camera_info", msgs.CAMERA_INFO),
    )
    assert pick_rgb(topics).name == "/camera/color/image_raw"
    assert pick_depth(topics).name == "/camera/aligned_depth_to_color/image_raw"
    info = pick_camera_info(topics, "/camera/color/image_raw/compressed")
    assert info is not None and info.name == "/camera/color/camera_info"
    only_compressed = _topics(("/cam/image/compressed", msgs.COMPRESSED_IMAGE))
    assert pick_rgb(only_compressed).name == "/cam/image/compressed"


def test_two_unhinted_image_topics_are_ambiguous() -> None:
    topics = _topics(("/left/image", msgs.IMAGE), ("/right/image", msgs.IMAGE))
    with pytest.raises(DatasetError) as caught:
        pick_rgb(topics)
    assert "/left/image" in caught.value.message and "/right/image" in caught.value.message
    assert "--rgb TOPIC" in caught.value.message
