"""Where the viewer stands and which way it looks, for "left", "right", "in front",
ordinals ("the third chair from the left") and "closest to you".

A :class:`View` is a 2-D position and a unit forward vector in the world frame (z up,
right-handed). The right vector is ``r = (f_y, -f_x)``; a point ``c`` has the lateral
coordinate ``(c - p)·r`` (positive: to the right) and the depth ``(c - p)·f``.

:class:`ViewFinder` chooses the view for one scoring of a spec, from the nodes it ranks
(the *group*: the tier of a superlative, the best-matching candidates of a relation),
in this order:

a. the request's viewpoint, resolved on the map (the best landmark candidate, nearest
   the group among equally good ones): ``facing`` L — look from the group's centroid
   towards L, standing back from the centroid by the group's spread plus
   ``FACING_BACKOFF``; ``from`` L — stand at L, look towards the centroid;
   ``back_to`` L — stand at the centroid, look away from L; ``seated`` on L — sit at L
   and look the way a seat or bed faces, into its room: towards the centre of L's room
   (as ``from`` L when L has no room or stands at its centre);
b. the robot's pose sent with the request (:class:`ViewerPose`);
c. the camera of the keyframe that saw most of the group (SEEN_IN records): the
   objects as the robot saw them;
d. a view from the centre of the group's room towards the group's centroid (+y when
   they coincide, or when the group has no room).
"""

from __future__ import annotations

import math
import numbers
import threading
from collections import Counter, defaultdict
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from inherit_sg.errors import InputError
from inherit_sg.model import ObjectNode, Pose
from inherit_sg.retrieval.constraints import Viewpoint

if TYPE_CHECKING:
    from inherit_sg.retrieval.graph_checks import Landmarks
    from inherit_sg.retrieval.snapshot import MapSnapshot

# A viewer coordinate farther than this from the map origin (metres) is refused.
MAX_COORDINATE = 1.0e6
# facing L: the viewer stands this far (m) behind the group's farthest member.
FACING_BACKOFF = 1.0
# Landmark candidates within this quality of the best count as equally good; the one
# nearest the group is taken.
LANDMARK_TIE = 0.02
# Points closer than this (m) give no direction.
COINCIDENT = 0.05
# A camera axis whose horizontal part is shorter than this looks (almost) straight
# down: its image "up" gives the heading instead.
LEVEL_AXIS = 0.2
# What the speaker looks at counts only when the map has it this well (a "headboard" is
# not the first frame on the wall that text similarity offers).
TOWARD_QUALITY = 0.5
SOURCES = ("viewpoint", "robot", "keyframe", "room")


def _number(value: Any, name: str) -> float:
    """``value`` as a finite float; :class:`InputError` naming ``name`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"{name} must be a number, got {value!r}")
    out = float(value)
    if not math.isfinite(out):
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return out


@dataclass(frozen=True)
class ViewerPose:
    """The robot's pose sent with a request: ``position`` (x, y, z) in metres and
    ``yaw_deg``, the heading in the world frame (z up), counter-clockwise from +x."""

    position: tuple[float, float, float]
    yaw_deg: float

    def __post_init__(self) -> None:
        pos = self.position
        if isinstance(pos, str) or not isinstance(pos, Sequence) or len(pos) != 3:
            raise InputError(f"viewer position must be three numbers [x, y, z], got {pos!r}")
        coords = tuple(_number(v, f"viewer position[{i}]") for i, v in enumerate(pos))
        if max(abs(v) for v in coords) > MAX_COORDINATE:
            raise InputError(f"viewer position {list(coords)} is beyond {MAX_COORDINATE:g} m")
        object.__setattr__(self, "position", coords)
        object.__setattr__(self, "yaw_deg", _number(self.yaw_deg, "viewer yaw_deg"))

    @property
    def forward(self) -> tuple[float, float]:
        """Unit heading in the floor plane."""
        yaw = math.radians(math.fmod(self.yaw_deg, 360.0))
        return (math.cos(yaw), math.sin(yaw))

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form (the REST ``viewer`` object)."""
        return {"position": list(self.position), "yaw_deg": self.yaw_deg}

    @classmethod
    def from_dict(cls, data: Any) -> ViewerPose:
        """From ``{"position": [x, y, z], "yaw_deg": number}``."""
        if not isinstance(data, dict) or set(data) != {"position", "yaw_deg"}:
            raise InputError(
                'viewer must be an object {"position": [x, y, z], "yaw_deg": number}, '
                f"got {data!r}"
            )
        pos = data["position"]
        if not isinstance(pos, list | tuple):
            raise InputError(f"viewer position must be three numbers [x, y, z], got {pos!r}")
        return cls(tuple(pos), data["yaw_deg"])

    @classmethod
    def parse(cls, text: str) -> ViewerPose:
        """From ``"X,Y,Z,YAW"`` (the CLI's ``--viewer``)."""
        parts = [p.strip() for p in text.split(",")]
        if len(parts) != 4:
            raise InputError(f"viewer {text!r}: expected X,Y,Z,YAW (four numbers)")
        try:
            values = [float(p) for p in parts]
        except ValueError:
            raise InputError(f"viewer {text!r}: expected X,Y,Z,YAW (four numbers)") from None
        return cls((values[0], values[1], values[2]), values[3])


@dataclass(frozen=True)
class View:
    """A viewer in the floor plane: ``position`` (x, y), unit ``forward``, which source
    chose it (``SOURCES``), a trace phrase and, for a viewpoint, the landmark node it
    stands at or faces (``anchor``)."""

    position: tuple[float, float]
    forward: tuple[float, float]
    source: str
    why: str
    anchor: str | None = None

    @property
    def right(self) -> tuple[float, float]:
        """Unit vector to the viewer's right (z up, right-handed)."""
        return (self.forward[1], -self.forward[0])

    def lateral(self, xy: np.ndarray) -> np.ndarray:
        """Lateral coordinates of (n, 2) points: positive to the viewer's right."""
        return (np.asarray(xy, float).reshape(-1, 2) - self.position) @ np.asarray(self.right)

    def depth(self, xy: np.ndarray) -> np.ndarray:
        """Depth of (n, 2) points along the viewing direction."""
        return (np.asarray(xy, float).reshape(-1, 2) - self.position) @ np.asarray(self.forward)

    def distance(self, xy: np.ndarray) -> np.ndarray:
        """Horizontal distance of (n, 2) points from the viewer."""
        d = np.asarray(xy, float).reshape(-1, 2) - self.position
        return np.hypot(d[:, 0], d[:, 1])


def _unit(v: np.ndarray) -> tuple[float, float] | None:
    n = float(np.hypot(v[0], v[1]))
    return None if n < COINCIDENT else (float(v[0] / n), float(v[1] / n))


def camera_heading(pose: Pose) -> tuple[float, float]:
    """Horizontal heading of an OpenCV camera (forward = +z of the camera); a camera
    looking straight down heads where its image "up" (-y) points."""
    rot = pose.matrix[:3, :3]
    axis = rot[:2, 2]
    if float(np.hypot(axis[0], axis[1])) < LEVEL_AXIS:
        axis = -rot[:2, 1]
    n = float(np.hypot(axis[0], axis[1]))
    return (float(axis[0] / n), float(axis[1] / n)) if n > 1e-9 else (0.0, 1.0)


class KeyframeViews:
    """Which keyframes saw which objects (SEEN_IN) and the keyframes' camera poses, for
    one snapshot: the index is built and poses are read (through ``load``) on first
    use, then cached. Safe to share between threads."""

    def __init__(self, snap: MapSnapshot, load: Callable[[str], Pose | None]) -> None:
        self.snap = snap
        self._load = load
        self._seen: dict[str, set[str]] | None = None
        self._poses: dict[str, Pose | None] = {}
        self._lock = threading.Lock()

    def seen_by(self, node_id: str) -> set[str]:
        """Keyframes that saw ``node_id``."""
        with self._lock:
            if self._seen is None:
                seen: dict[str, set[str]] = defaultdict(set)
                for obj, kf in self.snap.seen_in:
                    seen[obj].add(kf)
                self._seen = dict(seen)
            return self._seen.get(node_id, set())

    def pose(self, keyframe_id: str) -> Pose | None:
        """The keyframe's camera pose (None when the map does not hold it)."""
        with self._lock:
            if keyframe_id not in self._poses:
                self._poses[keyframe_id] = self._load(keyframe_id)
            return self._poses[keyframe_id]


class ViewFinder:
    """Chooses the view for one scoring of a spec (see the module docstring); views are
    remembered per group, and every choice is explained in :attr:`notes`."""

    def __init__(
        self,
        snap: MapSnapshot,
        *,
        viewpoint: Viewpoint | None = None,
        viewpoint_marks: Landmarks = (),
        toward_marks: Landmarks = (),
        robot: ViewerPose | None = None,
        keyframes: KeyframeViews | None = None,
    ) -> None:
        self.snap = snap
        self.viewpoint = viewpoint
        self.marks = viewpoint_marks
        self.toward = toward_marks
        self.robot = robot
        self.keyframes = keyframes
        self._views: dict[tuple[str, ...], View | None] = {}

    def view(self, group: Sequence[str]) -> View | None:
        """The view for ranking ``group`` (None when none of its nodes has a position)."""
        key = tuple(sorted(set(group)))
        if key not in self._views:
            self._views[key] = self._choose(key)
        return self._views[key]

    # ------------------------------------------------------------ sources
    def _choose(self, group: tuple[str, ...]) -> View | None:
        pts = [p for n in group if (p := self.snap.position(n)) is not None]
        if not pts:
            return None
        xy = np.asarray(pts, float)[:, :2]
        centroid = xy.mean(axis=0)
        spread = float(np.max(np.hypot(*(xy - centroid).T)))
        missed = ""
        if self.viewpoint is not None:
            found, missed = self._from_viewpoint(group, centroid, spread)
            if found is not None:
                return found
        if self.robot is not None:
            x, y, _ = self.robot.position
            why = f"robot pose at ({x:.2f}, {y:.2f}), heading {self.robot.yaw_deg:.0f}°"
            return View((x, y), self.robot.forward, "robot", missed + why)
        found = self._from_keyframe(group)
        if found is not None:
            return View(
                found.position, found.forward, found.source, missed + found.why, found.anchor
            )
        room = self._from_room(group, centroid, spread)
        return View(room.position, room.forward, room.source, missed + room.why)

    def _landmark(
        self, group: tuple[str, ...], centroid: np.ndarray, marks: Landmarks | None = None
    ) -> str | None:
        """The best viewpoint landmark candidate (of ``marks``, by default the
        standpoint's), nearest the group among equals (on the group's floor when one
        there is as good). A standpoint in a room with something the speaker says they
        look at beats one without ("on the settee in the den looking at the telly": the
        den with the telly)."""
        standpoint = marks is None
        marks = self.marks if marks is None else marks
        if not marks:
            return None
        best = max(q for _, q in marks)
        levels = Counter(self.snap.level_of(n) for n in group)
        level = levels.most_common(1)[0][0]
        seen_rooms = self._toward_rooms() if standpoint else set()
        ranked: list[tuple[int, int, float, str]] = []
        for lid, q in marks:
            pos = self.snap.position(lid)
            if q < best - LANDMARK_TIE or pos is None or lid in group:
                continue
            other_floor = int(level is not None and self.snap.level_of(lid) != level)
            unseen = int(bool(seen_rooms) and self.snap.room_of.get(lid) not in seen_rooms)
            ranked.append((other_floor, unseen, math.dist(pos[:2], centroid), lid))
        return min(ranked)[3] if ranked else None

    def _toward_rooms(self) -> set[str]:
        """Rooms holding a good candidate for what the speaker looks at (none when the
        request says nothing about it)."""
        if self.viewpoint is None or self.viewpoint.toward is None:
            return set()
        rooms = (self.snap.room_of.get(i) for i, q in self.toward if q >= TOWARD_QUALITY)
        return {r for r in rooms if r is not None}

    def _from_viewpoint(
        self, group: tuple[str, ...], centroid: np.ndarray, spread: float
    ) -> tuple[View | None, str]:
        vp = self.viewpoint
        assert vp is not None
        name = vp.landmark.target.describe()
        kind = vp.kind.replace("_", " ")
        lid = self._landmark(group, centroid)
        if lid is None:
            return None, f"(viewpoint '{kind} {name}': no {name} found in the map) "
        there = np.asarray(self.snap.position(lid), float)[:2]
        towards = _unit(there - centroid)
        if towards is None:
            return None, f"(viewpoint '{kind} {name}': {lid} stands among the candidates) "
        label = getattr(self.snap.node(lid), "label", "") or name
        looked = self._looking_at(vp, lid, label, there)
        if looked is not None:
            return looked, ""
        inward = self._into_room(lid, there) if vp.kind == "seated" else None
        if inward is not None:
            why = f"seated on {label} {lid}, looking into its room"
            return View((float(there[0]), float(there[1])), inward, "viewpoint", why, lid), ""
        if vp.kind == "facing":
            pos = centroid - np.asarray(towards) * (spread + FACING_BACKOFF)
            view = View((float(pos[0]), float(pos[1])), towards, "viewpoint", "")
        elif vp.kind in ("from", "seated"):
            away = (-towards[0], -towards[1])
            view = View((float(there[0]), float(there[1])), away, "viewpoint", "")
        else:  # back_to
            away = (-towards[0], -towards[1])
            view = View((float(centroid[0]), float(centroid[1])), away, "viewpoint", "")
        return View(view.position, view.forward, view.source, f"{kind} {label} {lid}", lid), ""

    def _looking_at(self, vp: Viewpoint, lid: str, label: str, there: np.ndarray) -> View | None:
        """Standing (or seated) at ``lid`` (called ``label``) and looking at what the
        request says the speaker looks at ("… looking at the bar"): its best candidate
        nearest the standpoint. None when the request says none or the map has none."""
        if vp.toward is None or vp.kind not in ("from", "seated"):
            return None
        marks = [(i, q) for i, q in self.toward if q >= TOWARD_QUALITY]
        seen = self._landmark((lid,), there, marks)
        pos = self.snap.position(seen) if seen is not None else None
        heading = _unit(np.asarray(pos, float)[:2] - there) if pos is not None else None
        if seen is None or heading is None:
            return None
        what = getattr(self.snap.node(seen), "label", "") or seen
        why = f"at {label} {lid}, looking at {what} {seen}"
        return View((float(there[0]), float(there[1])), heading, "viewpoint", why, lid)

    def _into_room(self, lid: str, there: np.ndarray) -> tuple[float, float] | None:
        """The way a seat or bed at ``there`` faces: towards the centre of its room
        (furniture stands with its back to a wall); None without a room."""
        rid = self.snap.room_of.get(lid)
        room = self.snap.rooms.get(rid) if rid is not None else None
        if room is None:
            return None
        return _unit(np.asarray(room.position, float)[:2] - there)

    def _from_keyframe(self, group: tuple[str, ...]) -> View | None:
        if self.keyframes is None:
            return None
        counts: Counter[str] = Counter()
        for node in group:
            counts.update(self.keyframes.seen_by(node))
        best_of = Counter(
            n.best_keyframe
            for i in group
            if isinstance(n := self.snap.node(i), ObjectNode) and n.best_keyframe
        )
        order = sorted(counts, key=lambda k: (-counts[k], -best_of.get(k, 0), k))
        for kf in order:
            pose = self.keyframes.pose(kf)
            if pose is None:
                continue
            t = pose.translation
            why = f"keyframe {kf}, which saw {counts[kf]} of {len(group)} candidates"
            return View((float(t[0]), float(t[1])), camera_heading(pose), "keyframe", why)
        return None

    def _from_room(self, group: tuple[str, ...], centroid: np.ndarray, spread: float) -> View:
        rooms = Counter(r for n in group if (r := self.snap.room_of.get(n)) in self.snap.rooms)
        c = (float(centroid[0]), float(centroid[1]))
        if not rooms:
            pos = (c[0], c[1] - spread - FACING_BACKOFF)
            return View(pos, (0.0, 1.0), "room", "no room known; looking along +y")
        rid = rooms.most_common(1)[0][0]
        room = self.snap.rooms[rid]
        here = np.asarray(room.position, float)[:2]
        towards = _unit(centroid - here)
        label = room.label or rid
        if towards is None:
            return View(c, (0.0, 1.0), "room", f"centre of {label} {rid}, looking along +y")
        pos = (float(here[0]), float(here[1]))
        return View(pos, towards, "room", f"centre of {label} {rid}, looking at the candidates")
