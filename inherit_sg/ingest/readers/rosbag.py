"""ROS 1 ``.bag`` files and ROS 2 bag folders (sqlite3 or MCAP storage), read with the
``rosbags`` library (the ``ros`` extra: ``pip install 'inherit-sg[ros]'``).

Topics: a colour image (``sensor_msgs/Image`` rgb8/bgr8/rgba8/bgra8/mono8, or
``sensor_msgs/CompressedImage`` JPEG/PNG), a depth image (16UC1 times ``depth_scale``,
millimetres by default, or 32FC1 metres) aligned to the colour image, the colour camera's
``sensor_msgs/CameraInfo`` and the camera pose: a topic of PoseStamped,
PoseWithCovarianceStamped, TransformStamped or Odometry, or a ``parent:child`` frame pair
looked up through ``/tf`` and ``/tf_static``. Topics left unnamed are picked by message
type and name (``color``/``rgb`` vs ``depth``, ``aligned_depth`` first, the camera info
next to the colour topic, the TF chain from its root to the colour image's frame); when
that leaves several, DatasetError lists them with the option that picks one.

Synchronisation (as TUM's): each depth image is paired one-to-one with the colour image
nearest in header time within ``max_dt`` (0.02 s); its pose is interpolated at the depth
stamp between samples within ``max_pose_dt`` (0.05 s), else the nearest such sample.
Frames with no partner or pose are left out (``skipped``). Frame ids are the depth
stamps in seconds; frame timestamps are seconds since the first frame.

Conventions: ROS worlds (``map``, ``odom``) are z-up and ROS optical frames already have
OpenCV axes, so a pose of the optical frame is ``T_world_camera`` as it stands. A pose of
a REP 103 body frame (x forward, y left, z up, e.g. ``camera_link``) needs
``camera_axes="body"``. Lens distortion is ignored (a warning says when it is not zero).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.errors import DatasetError, FrameError
from inherit_sg.ingest.readers import rosbag_msgs as msgs
from inherit_sg.ingest.readers.base import IndexedReader
from inherit_sg.ingest.readers.convert import to_pose
from inherit_sg.ingest.readers.rosbag_tf import TfTree
from inherit_sg.ingest.readers.tum import associate, pose_at
from inherit_sg.model import Frame, Intrinsics, Pose

log = logging.getLogger(__name__)

INSTALL_HINT = "reading ROS bags needs the rosbags package: pip install 'inherit-sg[ros]'"
_IMAGE_TYPES = (msgs.IMAGE, msgs.COMPRESSED_IMAGE)
_COLOUR_HINTS = ("color", "colour", "rgb")
_NS = 1_000_000_000


@dataclass(frozen=True)
class TopicInfo:
    """One topic of a bag: name, message type and message count."""

    name: str
    msgtype: str
    count: int

    def describe(self) -> str:
        """``/topic (type, N msgs)``."""
        return f"{self.name} ({self.msgtype}, {self.count} msgs)"


@dataclass(frozen=True)
class _ImageRef:
    """Where one image message is: its topic, bag time and header stamp (ns)."""

    topic: str
    log_ns: int
    stamp_ns: int


def bag_paths(path: Path) -> list[Path]:
    """What ``rosbags`` opens for ``path``: a ROS 2 bag folder (with ``metadata.yaml``;
    an ``.mcap`` file inside one opens the folder), or ROS 1 ``.bag`` files (a file, or
    every ``.bag`` in a folder)."""
    if not path.exists():
        raise DatasetError(f"bag not found: {path}")
    if path.is_file() and path.suffix == ".mcap":
        if (path.parent / "metadata.yaml").is_file():
            return [path.parent]
        raise DatasetError(
            f"{path}: an .mcap file is read through its ROS 2 bag folder; pass a folder "
            "that holds it and its metadata.yaml"
        )
    if path.is_file() and path.suffix == ".bag":
        return [path]
    if path.is_dir() and (path / "metadata.yaml").is_file():
        return [path]
    bags = sorted(path.glob("*.bag")) if path.is_dir() else []
    if bags:
        return bags
    if path.is_dir() and any(path.glob("*.mcap")):
        raise DatasetError(f"{path}: .mcap files without the metadata.yaml of a ROS 2 bag")
    raise DatasetError(
        f"{path}: not a ROS bag (a .bag file, a folder of .bag files, or a ROS 2 bag folder "
        "with metadata.yaml)"
    )


@contextmanager
def open_bag(path: Path) -> Iterator[Any]:
    """An open ``rosbags`` AnyReader on ``path``; DatasetError when it cannot be read."""
    try:
        from rosbags.highlevel import AnyReader, AnyReaderError
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise DatasetError(INSTALL_HINT) from None
    paths = bag_paths(path)
    try:
        # ROS 2 bags recorded before rosbag2 stored message definitions (Humble and
        # earlier by default) are read with the standard message types
        reader = AnyReader(paths, default_typestore=get_typestore(Stores.LATEST))
        reader.open()
    except (AnyReaderError, OSError) as exc:
        raise DatasetError(f"cannot read bag {path}: {exc}") from None
    try:
        yield reader
    finally:
        reader.close()


def list_topics(path: str | Path) -> list[TopicInfo]:
    """The topics of a bag, sorted by name."""
    with open_bag(Path(path)) as bag:
        return _topics(bag)


def topic_roles(topics: list[TopicInfo]) -> tuple[dict[str, str], list[str]]:
    """What the reader would take each topic for when no topic is named (``colour``,
    ``depth``, ``camera info``, ``pose?`` for a possible pose source, ``tf``), and the
    reasons a pick is impossible (ambiguous or missing)."""
    roles: dict[str, str] = {}
    problems: list[str] = []
    rgb: str | None = None
    for role, pick in (("colour", pick_rgb), ("depth", pick_depth)):
        try:
            chosen = pick(topics).name
        except DatasetError as exc:
            problems.append(exc.message)
            continue
        roles[chosen] = role
        rgb = chosen if role == "colour" else rgb
    if rgb is not None:
        try:
            info = pick_camera_info(topics, rgb)
        except DatasetError as exc:
            problems.append(exc.message)
        else:
            if info is not None:
                roles[info.name] = "camera info"
    for t in topics:
        if t.msgtype in msgs.POSE_TYPES:
            roles[t.name] = "pose?"
        elif t.msgtype == msgs.TF_MESSAGE:
            roles[t.name] = "tf"
    return roles, problems


def _topics(bag: Any) -> list[TopicInfo]:
    return [
        TopicInfo(name, info.msgtype or "?", int(info.msgcount))
        for name, info in sorted(bag.topics.items())
    ]


def _choose(
    what: str, candidates: list[TopicInfo], preferred: list[TopicInfo], option: str
) -> TopicInfo:
    """The one candidate (or the one preferred candidate when there are several);
    DatasetError listing them otherwise."""
    if len(candidates) == 1:
        return candidates[0]
    if len(preferred) == 1:
        return preferred[0]
    if not candidates:
        raise DatasetError(f"the bag has no {what} topic")
    listed = ", ".join(t.describe() for t in candidates)
    raise DatasetError(f"several {what} topics: {listed}; choose one with {option} TOPIC")


def _without_compressed_twins(topics: list[TopicInfo]) -> list[TopicInfo]:
    """Drop ``X/compressed`` (and ``X/compressedDepth``) when raw ``X`` is there too."""
    names = {t.name for t in topics}
    return [t for t in topics if t.name.rsplit("/", 1)[0] not in names]


def pick_rgb(topics: list[TopicInfo]) -> TopicInfo:
    """The colour image topic: image topics not named ``depth``, those named
    ``color``/``rgb`` first."""
    images = [t for t in topics if t.msgtype in _IMAGE_TYPES and "depth" not in t.name.lower()]
    images = _without_compressed_twins(images)
    hinted = [t for t in images if any(h in t.name.lower() for h in _COLOUR_HINTS)]
    return _choose("colour image", images, hinted, "--rgb")


def pick_depth(topics: list[TopicInfo]) -> TopicInfo:
    """The depth image topic: raw images named ``depth``, ``aligned_depth`` first."""
    depth = [t for t in topics if t.msgtype == msgs.IMAGE and "depth" in t.name.lower()]
    if not depth:
        raise DatasetError(
            "the bag has no depth image topic (a sensor_msgs/Image with 'depth' in its "
            "name); name it with --depth TOPIC. Topics: " + ", ".join(t.describe() for t in topics)
        )
    aligned = [t for t in depth if "aligned" in t.name.lower()]
    return _choose("depth image", depth, aligned, "--depth")


def pick_camera_info(topics: list[TopicInfo], rgb: str) -> TopicInfo | None:
    """The camera info next to the colour topic (``/cam/color/camera_info`` for
    ``/cam/color/image_raw``) or the only one; None when the bag has none."""
    infos = [t for t in topics if t.msgtype == msgs.CAMERA_INFO]
    if not infos:
        return None
    # the info whose folder is the deepest one holding the colour topic
    depth = {
        t.name: len(folder) for t in infos if rgb.startswith((folder := _folder(t.name)) + "/")
    }
    nearest = [t for t in infos if depth and depth.get(t.name) == max(depth.values())]
    return _choose("camera info", infos, nearest, "--camera-info")


def _folder(topic: str) -> str:
    return topic.rsplit("/", 1)[0]


def _topic(topics: list[TopicInfo], name: str, types: tuple[str, ...], option: str) -> TopicInfo:
    found = next((t for t in topics if t.name == name), None)
    if found is None:
        listed = ", ".join(t.describe() for t in topics if t.msgtype in types) or "none"
        raise DatasetError(f"{option} {name}: no such topic in the bag; candidates: {listed}")
    if found.msgtype not in types:
        raise DatasetError(
            f"{option} {name}: a {found.msgtype} topic, expected {' or '.join(types)}"
        )
    return found


def parse_tf_pair(text: str) -> tuple[str, str]:
    """``"map:camera_optical"`` -> ``("map", "camera_optical")`` (parent, child)."""
    parent, sep, child = text.partition(":")
    if not sep or not parent.strip() or not child.strip():
        raise DatasetError(
            f"tf {text!r}: expected PARENT:CHILD, e.g. map:camera_color_optical_frame"
        )
    return msgs.frame_name(parent.strip()), msgs.frame_name(child.strip())


class RosbagReader(IndexedReader):
    """Reads a ROS 1 or ROS 2 bag (see the module docstring)."""

    format_name = "rosbag"
    _pose_at: Callable[[float], np.ndarray | None]

    def __init__(
        self,
        root: str | Path,
        rgb_topic: str | None = None,
        depth_topic: str | None = None,
        camera_info_topic: str | None = None,
        pose_topic: str | None = None,
        tf: str | tuple[str, str] | None = None,
        depth_scale: float = 0.001,
        camera_axes: str = "optical",
        intrinsics: Intrinsics | None = None,
        max_dt: float = 0.02,
        max_pose_dt: float = 0.05,
    ) -> None:
        super().__init__(root, single_file=Path(root).is_file())
        if pose_topic is not None and tf is not None:
            raise DatasetError("pass a pose topic or a TF frame pair, not both")
        if not depth_scale > 0:
            raise DatasetError(f"depth_scale must be positive (metres per unit), got {depth_scale}")
        if camera_axes not in ("optical", "body"):
            raise DatasetError(f"camera_axes must be 'optical' or 'body', got {camera_axes!r}")
        self.depth_scale = depth_scale
        self.max_dt = max_dt
        self.max_pose_dt = max_pose_dt
        self._axes = msgs.BODY_FROM_OPTICAL if camera_axes == "body" else np.eye(4)
        tf_pair = parse_tf_pair(tf) if isinstance(tf, str) else tf
        with open_bag(self.root) as bag:
            topics = _topics(bag)
            self.rgb_topic = self._pick(topics, rgb_topic, _IMAGE_TYPES, "--rgb", pick_rgb)
            self.depth_topic = self._pick(topics, depth_topic, (msgs.IMAGE,), "--depth", pick_depth)
            info = (
                _topic(topics, camera_info_topic, (msgs.CAMERA_INFO,), "--camera-info")
                if camera_info_topic
                else pick_camera_info(topics, self.rgb_topic)
            )
            self.camera_info_topic = None if info is None else info.name
            pose_info = None
            if pose_topic is not None:
                pose_info = _topic(topics, pose_topic, msgs.POSE_TYPES, "--pose")
            scan = _scan(bag, topics, self)
        self.intrinsics = self._intrinsics(scan, intrinsics)
        self.pose_source = self._pose_source(scan, topics, pose_info, tf_pair)
        self._index(scan)
        self._report_skipped()

    @staticmethod
    def _pick(
        topics: list[TopicInfo],
        given: str | None,
        types: tuple[str, ...],
        option: str,
        auto: Callable[[list[TopicInfo]], TopicInfo],
    ) -> str:
        return (_topic(topics, given, types, option) if given else auto(topics)).name

    def _intrinsics(self, scan: _Scan, given: Intrinsics | None) -> Intrinsics:
        units_per_metre = 1.0 / self.depth_scale
        if given is not None:
            out = given
        elif scan.camera_info is None:
            raise DatasetError(
                "the bag has no sensor_msgs/CameraInfo topic: name one with --camera-info "
                "TOPIC, or pass intrinsics to the reader"
            )
        else:
            try:
                out = msgs.intrinsics_from_camera_info(scan.camera_info, units_per_metre)
            except FrameError as exc:
                raise DatasetError(f"{self.camera_info_topic}: {exc.message}") from None
            if any(abs(d) > 1e-6 for d in msgs.distortion(scan.camera_info)):
                log.warning(
                    "%s: lens distortion is not zero; images are used as they are "
                    "(record rectified images for accurate geometry)",
                    self.camera_info_topic,
                )
        for topic, size in (
            (self.rgb_topic, scan.rgb_size),
            (self.depth_topic, scan.depth_size),
        ):
            if size is not None and size != (out.width, out.height):
                raise DatasetError(
                    f"{topic} images are {size[0]}x{size[1]} but the camera info says "
                    f"{out.width}x{out.height}: colour and depth must be aligned (record e.g. "
                    "aligned_depth_to_color and name the colour camera info)"
                )
        return out

    def _pose_source(
        self,
        scan: _Scan,
        topics: list[TopicInfo],
        pose_info: TopicInfo | None,
        tf_pair: tuple[str, str] | None,
    ) -> str:
        """Set ``self._pose_at`` and return a description of where poses come from."""
        if pose_info is not None:
            return self._use_pose_topic(scan, pose_info)
        if tf_pair is not None:
            return self._use_tf(scan, tf_pair)
        options: list[tuple[str, Callable[[], str]]] = [
            (t.describe(), partial(self._use_pose_topic, scan, t))
            for t in topics
            if t.msgtype in msgs.POSE_TYPES
        ]
        camera = scan.rgb_frame
        if camera and camera in scan.tf.frames:
            root = scan.tf.root(camera)
            if root != camera and scan.tf.is_dynamic(root, camera):
                pair = (root, camera)
                options.append(
                    (
                        f"TF {root} -> {camera} (--tf {root}:{camera})",
                        lambda: self._use_tf(scan, pair),
                    )
                )
        if len(options) == 1:
            return options[0][1]()
        listed = "; ".join(o[0] for o in options) or "none"
        raise DatasetError(
            f"{'several' if options else 'no'} camera pose sources: {listed}. Choose with "
            f"--pose TOPIC or --tf PARENT:CHILD (TF frames in the bag: "
            f"{', '.join(scan.tf.frames) or 'none'}; the colour images are in frame "
            f"{camera or '?'!r})"
        )

    def _use_pose_topic(self, scan: _Scan, info: TopicInfo) -> str:
        samples = scan.poses.get(info.name, [])
        if not samples:
            raise DatasetError(f"pose topic {info.name} has no messages")
        samples.sort(key=lambda s: s[0])
        times = [s[0] for s in samples]
        mats = [s[1] @ self._axes for s in samples]
        child = scan.pose_frames.get(info.name, "")
        if child and scan.rgb_frame and child != scan.rgb_frame:
            log.warning(
                "pose topic %s places frame %r but the colour images are in %r; its poses "
                "are taken as the camera's (use --tf to go through the TF chain instead)",
                info.name,
                child,
                scan.rgb_frame,
            )

        def at(t: float) -> np.ndarray | None:
            return pose_at(t, times, mats, self.max_pose_dt)

        self._pose_at = at
        return f"topic {info.name}"

    def _use_tf(self, scan: _Scan, pair: tuple[str, str]) -> str:
        parent, child = pair
        tree = scan.tf
        missing = [f for f in pair if f not in tree.frames]
        if missing or not tree.connected(parent, child):
            raise DatasetError(
                f"--tf {parent}:{child}: no TF chain between them "
                f"({'unknown frame ' + ', '.join(missing) if missing else 'separate trees'}); "
                f"TF frames in the bag: {', '.join(tree.frames) or 'none'}"
            )

        def at(t: float) -> np.ndarray | None:
            found = tree.lookup(parent, child, t, self.max_pose_dt)
            return None if found is None else found @ self._axes

        self._pose_at = at
        return f"tf {parent}:{child}"

    def _index(self, scan: _Scan) -> None:
        depth_times = [r.stamp_ns / _NS for r in scan.depth]
        rgb_times = [r.stamp_ns / _NS for r in scan.rgb]
        pairs = dict(associate(depth_times, rgb_times, self.max_dt))
        self._refs: list[tuple[_ImageRef, _ImageRef]] = []
        self._poses: list[Pose] = []
        stamps: list[int] = []
        for j, ref in enumerate(scan.depth):
            frame_id = f"{ref.stamp_ns / _NS:.6f}"
            i = pairs.get(j)
            if i is None:
                self._skip(frame_id, f"no colour image within {self.max_dt} s")
                continue
            matrix = self._pose_at(depth_times[j])
            if matrix is None:
                self._skip(frame_id, f"no pose within {self.max_pose_dt} s")
                continue
            try:
                pose = to_pose(matrix)
            except FrameError as exc:
                self._skip(frame_id, f"invalid pose: {exc.message}")
                continue
            self.frame_ids.append(frame_id)
            self._refs.append((scan.rgb[i], ref))
            self._poses.append(pose)
            stamps.append(ref.stamp_ns)
        start = stamps[0] if stamps else 0
        self.timestamps = [(s - start) / _NS for s in stamps]

    @contextmanager
    def _opened(self) -> Iterator[Any]:
        with open_bag(self.root) as bag:
            yield bag

    def __iter__(self) -> Iterator[Frame]:
        """Frames in order, reading the bag through one open reader."""
        with self._opened() as bag:
            for index in range(len(self.frame_ids)):
                yield self._frame(bag, index).validate()

    def _load(self, index: int) -> Frame:
        with self._opened() as bag:
            return self._frame(bag, index)

    def _frame(self, bag: Any, index: int) -> Frame:
        rgb_ref, depth_ref = self._refs[index]
        rgb_type, rgb_msg = _fetch(bag, rgb_ref)
        _, depth_msg = _fetch(bag, depth_ref)
        where = f"frame {self.frame_ids[index]!r}"
        try:
            if rgb_type == msgs.COMPRESSED_IMAGE:
                rgb = msgs.compressed_to_rgb(rgb_msg)
            else:
                rgb = msgs.image_to_rgb(rgb_msg)
            depth = msgs.image_to_depth(depth_msg, self.depth_scale)
        except FrameError as exc:
            raise FrameError(f"{where}: {exc.message}") from None
        return Frame(
            index=index,
            frame_id=self.frame_ids[index],
            timestamp=self.timestamps[index],
            rgb=rgb,
            depth=depth,
            pose=self._poses[index],
            intrinsics=self.intrinsics,
        )


def _fetch(bag: Any, ref: _ImageRef) -> tuple[str, Any]:
    """The message ``ref`` points at, deserialised, with its type."""
    connections = [c for c in bag.connections if c.topic == ref.topic]
    for connection, _, raw in bag.messages(connections, start=ref.log_ns, stop=ref.log_ns + 1):
        msg = bag.deserialize(raw, connection.msgtype)
        if (msgs.stamp_ns(msg) or ref.log_ns) == ref.stamp_ns:
            return connection.msgtype, msg
    raise FrameError(f"{ref.topic}: message at bag time {ref.log_ns} ns is gone")


@dataclass
class _Scan:
    """What one pass over a bag found: image stamps, the first camera info, poses and TF."""

    rgb: list[_ImageRef]
    depth: list[_ImageRef]
    rgb_size: tuple[int, int] | None
    depth_size: tuple[int, int] | None
    rgb_frame: str
    camera_info: Any
    poses: dict[str, list[tuple[float, np.ndarray]]]
    pose_frames: dict[str, str]
    tf: TfTree


def _scan(bag: Any, topics: list[TopicInfo], reader: RosbagReader) -> _Scan:
    """Read the stamps of every colour and depth image, the first camera info, every pose
    message and the TF tree in one pass."""
    pose_topics = {t.name for t in topics if t.msgtype in msgs.POSE_TYPES}
    tf_topics = {t.name for t in topics if t.msgtype == msgs.TF_MESSAGE}
    wanted = {reader.rgb_topic, reader.depth_topic, *pose_topics, *tf_topics}
    if reader.camera_info_topic:
        wanted.add(reader.camera_info_topic)
    scan = _Scan([], [], None, None, "", None, {}, {}, TfTree())
    connections = [c for c in bag.connections if c.topic in wanted]
    for connection, log_ns, raw in bag.messages(connections):
        topic, msgtype = connection.topic, connection.msgtype
        if topic == reader.camera_info_topic and scan.camera_info is not None:
            continue
        msg = bag.deserialize(raw, msgtype)
        stamp = msgs.stamp_ns(msg) or log_ns
        if topic in (reader.rgb_topic, reader.depth_topic):
            _add_image(
                scan, topic == reader.rgb_topic, _ImageRef(topic, log_ns, stamp), msgtype, msg
            )
        elif topic == reader.camera_info_topic:
            scan.camera_info = msg
        elif topic in pose_topics:
            _add_pose(scan, topic, stamp, msgtype, msg)
        else:
            _add_tf(scan.tf, topic.endswith("tf_static"), log_ns, msg)
    scan.tf.finish()
    scan.rgb.sort(key=lambda r: r.stamp_ns)
    scan.depth.sort(key=lambda r: r.stamp_ns)
    return scan


def _add_image(scan: _Scan, is_rgb: bool, ref: _ImageRef, msgtype: str, msg: Any) -> None:
    if is_rgb:
        scan.rgb.append(ref)
        if scan.rgb_size is None:
            scan.rgb_size = msgs.image_size(msgtype, msg)
            scan.rgb_frame = msgs.frame_name(str(msg.header.frame_id))
    else:
        scan.depth.append(ref)
        if scan.depth_size is None:
            scan.depth_size = msgs.image_size(msgtype, msg)


def _add_pose(scan: _Scan, topic: str, stamp: int, msgtype: str, msg: Any) -> None:
    try:
        matrix = msgs.pose_message_matrix(msgtype, msg)
    except FrameError as exc:  # a zero quaternion: the sample is no pose
        log.debug("%s: pose at %d ns left out: %s", topic, stamp, exc.message)
        return
    scan.poses.setdefault(topic, []).append((stamp / _NS, matrix))
    scan.pose_frames.setdefault(topic, msgs.pose_child_frame(msgtype, msg))


def _add_tf(tree: TfTree, static: bool, log_ns: int, msg: Any) -> None:
    for transform in msg.transforms:
        try:
            matrix = msgs.transform_matrix(transform)
        except FrameError:
            continue
        tree.add(
            msgs.frame_name(str(transform.header.frame_id)),
            msgs.frame_name(str(transform.child_frame_id)),
            (msgs.stamp_ns(transform) or log_ns) / _NS,
            matrix,
            static,
        )
