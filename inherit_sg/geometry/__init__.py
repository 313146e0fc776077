"""Geometric stream (paper §III-B/C): BEV occupancy, rooms, floors, keyframe gating,
room-mask refinement, best viewpoints and the BEV picture.

Design in short (details in each module):

* Occupancy (:mod:`.raycast`, :mod:`.occupancy`): strided depth → world points →
  a virtual laser scan per azimuth for the obstacle band (1.2–1.9 m above the floor,
  widened to hold the camera height), log-odds in 5 cm cells; far hits weigh less
  under a range² depth-noise model. A second band above door height (2.1–2.4 m)
  records lintels and where rays crossed it (open above).
* Rooms (:mod:`.rooms`, :mod:`.regions`, :mod:`.doorways`): EDT of free space (thin
  unobserved streaks are not walls), Gaussian smoothing, watershed basins by steepest
  ascent, then basins merge unless their border is a doorway: at most
  ``door_max_width`` wide, narrower than both basins, and not open above, with a lintel
  or a known door near it or otherwise two observed walls as jambs. Known doors (from
  the semantic stream, :meth:`GeometricStream.add_door`) cut the free space.
* Persistent ids (:mod:`.room_ids`): overlap matching plus per-cell hysteresis voting.
* Floors (:mod:`.floors`): camera-height tracking with hysteresis; FloorChanged is the
  hard trigger; levels are ranks of floor heights.
* Keyframes (:mod:`.gating`): appearance (offline colour + gradient descriptor) and pose
  gates; bounded queue that never blocks the stream and drops the oldest soft keyframe.
* Refinement (:mod:`.refine`, :mod:`.lines`), best views (:mod:`.viewpoint`), the BEV
  picture (:mod:`.bev`) and the scene-graph view (:mod:`.export`).
"""

from inherit_sg.geometry.events import (
    FloorChanged,
    GeometryEvent,
    KeyframeDropped,
    KeyframeSelected,
    RoomEntered,
    RoomsUpdated,
)
from inherit_sg.geometry.floor_map import Door, FloorMap
from inherit_sg.geometry.gating import KeyframeGate, KeyframeQueue, PendingKeyframe
from inherit_sg.geometry.image_feature import global_image_feature
from inherit_sg.geometry.records import room_node_id
from inherit_sg.geometry.stream import GeometricStream

__all__ = [
    "Door",
    "FloorChanged",
    "FloorMap",
    "GeometricStream",
    "GeometryEvent",
    "KeyframeDropped",
    "KeyframeGate",
    "KeyframeQueue",
    "KeyframeSelected",
    "PendingKeyframe",
    "RoomEntered",
    "RoomsUpdated",
    "global_image_feature",
    "room_node_id",
]
