"""ROS bags as input: a small generated house written into real ROS 1 and ROS 2 bags
(``rosbags`` writers, RealSense-like topics), read back frame by frame and mapped with
``inherit-sg map build --format rosbag``; the maps must match the map of the house's isg
folder. Also the errors a user meets: ambiguous topics, no depth, a wrong TF pair."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

from inherit_sg.cli.main import app
from inherit_sg.errors import DatasetError
from inherit_sg.ingest.isg import IsgReader
from inherit_sg.ingest.readers import detect_format, open_dataset
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.model import Layer
from inherit_sg.store import MapStore
from tests.rosbag_files import CAMERA_FRAME, DEPTH, POSE, RGB, RGB_COMPRESSED, BagSpec, write_bag

# The bags carry no instance masks, so both sides use the classical segmenter.
SEGMENTER = ["--set", "perception.segmenter=classical"]
FRAMES = 40  # enough of the walk for two rooms
runner = CliRunner()


@pytest.fixture(scope="module")
def house(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("rosbag_house") / "isg"
    write_dataset(generate_house(5, 1, 4), out, width=160, height=120, workers=1, max_frames=FRAMES)
    return out


def _map(dataset: Path, map_dir: Path, *options: str) -> dict[str, Any]:
    result = runner.invoke(
        app, ["map", "build", str(dataset), "--map", str(map_dir), "--json", *SEGMENTER, *options]
    )
    assert result.exit_code == 0, result.output
    return dict(json.loads(result.stdout))


@pytest.fixture(scope="module")
def isg_map(house: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("rosbag_maps") / "isg"
    _map(house, out)
    return out


def _graph_summary(map_dir: Path) -> dict[str, Any]:
    with MapStore.open(map_dir) as store:
        graph = store.load_graph()
    objects = sorted(graph.objects(), key=lambda o: tuple(round(v, 2) for v in o.position))
    return {
        "rooms": sorted(r.label for r in graph.nodes(Layer.ROOM)),
        "labels": [o.label for o in objects],
        # without the room: an object in a doorway is described in either room, even
        # between two builds of the same isg folder (the description races the room update)
        "descriptions": sorted(o.description.split(", in the ")[0] for o in objects),
        "positions": np.array([o.position for o in objects]),
    }


def _assert_same_map(bag_map: Path, isg_map: Path) -> None:
    got, want = _graph_summary(bag_map), _graph_summary(isg_map)
    assert got["rooms"] == want["rooms"] and len(want["rooms"]) >= 2
    assert got["labels"] == want["labels"] and len(want["labels"]) >= 5
    assert got["descriptions"] == want["descriptions"]
    # poses went through quaternions: equal to round-off
    assert np.abs(got["positions"] - want["positions"]).max() < 1e-3


def _assert_same_frames(bag: Path, house: Path, **options: Any) -> None:
    reader = open_dataset(bag, "rosbag", **options)
    reference = IsgReader(house)
    assert len(reader) == len(reference) and not getattr(reader, "skipped", {})
    assert reader.intrinsics == reference.intrinsics
    for got, want in zip(reader, reference, strict=True):
        assert np.array_equal(got.rgb, want.rgb)
        assert np.array_equal(got.depth, want.depth)
        assert np.allclose(got.pose.matrix, want.pose.matrix, atol=1e-6)
        assert got.timestamp == want.timestamp


def test_ros2_bag_with_pose_topic_maps_like_the_isg_folder(
    house: Path, isg_map: Path, tmp_path: Path
) -> None:
    bag = write_bag(house, tmp_path / "recording", BagSpec())
    assert detect_format(bag) == "rosbag"
    _assert_same_frames(bag, house)
    summary = _map(bag, tmp_path / "map", "--format", "rosbag")
    assert summary["frames"] == FRAMES
    _assert_same_map(tmp_path / "map", isg_map)


def test_ros1_bag_with_tf_chain_and_compressed_colour_maps_like_the_isg_folder(
    house: Path, isg_map: Path, tmp_path: Path
) -> None:
    """Poses through map -> odom -> base_link -> camera_link -> optical frame, colour as
    PNG CompressedImage; topics and the TF pair named as a user would."""
    bag = write_bag(
        house, tmp_path / "recording.bag", BagSpec(ros1=True, compressed=True, pose="tf")
    )
    assert detect_format(bag) == "rosbag"
    _assert_same_frames(bag, house)  # the TF pair is found by itself
    options = ["--rgb", RGB_COMPRESSED, "--depth", DEPTH, "--tf", f"map:{CAMERA_FRAME}"]
    summary = _map(bag, tmp_path / "map", *options)  # --format auto finds the .bag
    assert summary["frames"] == FRAMES
    _assert_same_map(tmp_path / "map", isg_map)


def test_mcap_bag_and_body_axes(house: Path, tmp_path: Path) -> None:
    """MCAP storage reads the same; a pose of the camera_link body frame needs
    camera_axes='body' to give the optical frame's pose."""
    bag = write_bag(house, tmp_path / "recording", BagSpec(storage="mcap", pose="tf"))
    _assert_same_frames(bag, house, tf=f"odom:{CAMERA_FRAME}")
    _assert_same_frames(bag, house, tf="map:camera_link", camera_axes="body")


def test_a_ros2_bag_without_message_definitions_reads_with_the_standard_types(
    house: Path, tmp_path: Path
) -> None:
    """rosbag2 stored no message definitions before its format 8 (Humble records so)."""
    bag = write_bag(house, tmp_path / "recording", BagSpec())
    with sqlite3.connect(next(bag.glob("*.db3"))) as db:
        db.execute("DELETE FROM message_definitions")
    _assert_same_frames(bag, house)


def test_ambiguous_topics_are_listed_with_the_option_to_pass(house: Path, tmp_path: Path) -> None:
    bag = write_bag(house, tmp_path / "recording", BagSpec(second_camera=True, pose="both"))
    result = runner.invoke(app, ["map", "build", str(bag), "--map", str(tmp_path / "m")])
    assert result.exit_code == 2
    message = " ".join(result.output.split())
    assert "several colour image topics" in message and "--rgb TOPIC" in message
    assert RGB in message and "/camera2/color/image_raw" in message
    # the colour topic named, the pose sources are next: the topic and the TF chain
    with pytest.raises(DatasetError) as caught:
        open_dataset(bag, "rosbag", rgb_topic=RGB)
    assert POSE in caught.value.message and f"--tf map:{CAMERA_FRAME}" in caught.value.message
    assert "--pose TOPIC" in caught.value.message
    assert not (tmp_path / "m").exists()
    reader = open_dataset(bag, "rosbag", rgb_topic=RGB, pose_topic=POSE)
    assert len(reader) == FRAMES


def test_a_bag_without_depth_says_so(house: Path, tmp_path: Path) -> None:
    bag = write_bag(house, tmp_path / "recording", BagSpec(depth=False))
    result = runner.invoke(
        app, ["map", "build", str(bag), "--map", str(tmp_path / "m"), "--format", "rosbag"]
    )
    assert result.exit_code == 2
    message = " ".join(result.output.split())
    assert "no depth image topic" in message and "--depth TOPIC" in message and RGB in message


def test_topics_command_and_option_errors(house: Path, tmp_path: Path) -> None:
    bag = write_bag(house, tmp_path / "recording", BagSpec())
    result = runner.invoke(app, ["map", "topics", str(bag)])
    assert result.exit_code == 0, result.output
    rows = {line.split()[0]: line.split()[3:] for line in result.output.splitlines()[1:]}
    assert rows[RGB] == ["colour"] and rows[DEPTH] == ["depth"] and rows[POSE] == ["pose?"]
    bad_tf = runner.invoke(
        app, ["map", "build", str(bag), "--map", str(tmp_path / "m"), "--tf", "map:nowhere"]
    )
    assert bad_tf.exit_code == 2
    assert "no TF chain" in " ".join(bad_tf.output.split())
    not_a_bag = runner.invoke(
        app, ["map", "build", str(house), "--map", str(tmp_path / "m"), "--rgb", RGB]
    )
    assert not_a_bag.exit_code == 2 and "--format rosbag" in not_a_bag.output


def test_frames_without_a_colour_partner_in_time_are_skipped(house: Path, tmp_path: Path) -> None:
    bag = write_bag(house, tmp_path / "recording", BagSpec(rgb_delay_ns=30_000_000))
    reader = open_dataset(bag, "rosbag")
    assert len(reader) == 0
    skipped = getattr(reader, "skipped", {})
    assert len(skipped) == FRAMES and "no colour image within 0.02 s" in set(skipped.values())
    assert len(open_dataset(bag, "rosbag", max_dt=0.05)) == FRAMES
