"""Persist the geometric stream between sessions, so that a later session on the same
map continues its occupancy grids, floors and room ids instead of starting over.

The state lives in ``<map>/geometry.npz``, a data-only archive (:mod:`.safe_state`:
JSON structure and numpy arrays, read without pickle, creating objects only of the
geometry classes listed here), with a format number. A file that is damaged, of another
format, or inconsistent is ignored with a warning (a fresh stream starts, and the map
stays usable). Maps of earlier versions kept the state in ``geometry.pkl``, a pickle,
which could run code when read; it is never read: the warning says that the next session
starts a fresh geometric stream (:func:`legacy_state_note`).
"""

from __future__ import annotations

import logging
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.config import Config, GeometryConfig
from inherit_sg.geometry.floor_map import Door, FloorMap
from inherit_sg.geometry.floors import FloorState, FloorTracker
from inherit_sg.geometry.gating import KeyframeQueue
from inherit_sg.geometry.occupancy import LogOddsParams, OccupancyGrid
from inherit_sg.geometry.records import IdCounter, RoomTracker, StairsRecord
from inherit_sg.geometry.refine import RefineParams
from inherit_sg.geometry.room_ids import RoomIdGrid
from inherit_sg.geometry.rooms import SegmentParams
from inherit_sg.geometry.stream import GeometricStream
from inherit_sg.mapping.safe_state import StateFormatError, class_table, dump_state, load_state
from inherit_sg.model import Pose

log = logging.getLogger(__name__)

STATE_FILE = "geometry.npz"
# The pickle file of earlier versions: never read (a pickle can run code).
LEGACY_STATE_FILE = "geometry.pkl"
STATE_FORMAT = 2
# the keyframe gate compares frame indices and features of this session only
_TRANSIENT = ("queue", "keyframes", "stats", "_pending", "lock", "image_feature", "gate")


@lru_cache(maxsize=1)
def _classes() -> dict[str, type]:
    """The only classes a state file may create."""
    return class_table(
        [
            GeometryConfig, FloorTracker, FloorState, FloorMap, OccupancyGrid, LogOddsParams,
            RoomIdGrid, IdCounter, Door, SegmentParams, RefineParams, RoomTracker,
            StairsRecord, Pose,
        ]
    )  # fmt: skip


def save_geometry(stream: GeometricStream, map_dir: str | Path) -> Path:
    """Write the stream's persistent state atomically (write + rename)."""
    state = {k: v for k, v in vars(stream).items() if k not in _TRANSIENT}
    path = Path(map_dir) / STATE_FILE
    return dump_state({"format": STATE_FORMAT, "state": state}, path, _classes())


def legacy_state_note(map_dir: str | Path) -> str | None:
    """What to tell the user about a ``geometry.pkl`` of an earlier version in
    ``map_dir`` that has no ``geometry.npz`` beside it (None: nothing to say)."""
    root = Path(map_dir)
    if not (root / LEGACY_STATE_FILE).is_file() or (root / STATE_FILE).is_file():
        return None
    return (
        f"{root / LEGACY_STATE_FILE} was written by an earlier version as a pickle, which can "
        "run code when read, so it is not read: this session starts a fresh geometric stream "
        "(occupancy grids and room outlines are rebuilt from its frames; the objects, rooms "
        "and keyframes of the map are kept). Delete the file to silence this warning."
    )


def _check_stream(state: Any) -> dict[str, Any]:
    """The decoded state, when it has the parts a stream needs and its grids agree."""
    if not isinstance(state, dict):
        raise StateFormatError("the state must be a table")
    if not isinstance(state.get("tracker"), FloorTracker):
        raise StateFormatError("the state has no floor tracker")
    maps = state.get("maps")
    if not isinstance(maps, dict) or not all(isinstance(m, FloorMap) for m in maps.values()):
        raise StateFormatError("the floor maps are missing or not floor maps")
    for fid, fmap in maps.items():
        grid = getattr(fmap, "grid", None)
        rooms = getattr(fmap, "rooms", None)
        if not isinstance(grid, OccupancyGrid) or not isinstance(rooms, RoomIdGrid):
            raise StateFormatError(f"floor map {fid!r} lacks its grids")
        arrays = [getattr(grid, "logodds", None), getattr(rooms, "ids", None)]
        if not all(isinstance(a, np.ndarray) and a.ndim == 2 for a in arrays):
            raise StateFormatError(f"floor map {fid!r}: its grids are not 2-D arrays")
        shape = arrays[0].shape  # type: ignore[union-attr]
        if any(a.shape != shape for a in arrays):  # type: ignore[union-attr]
            raise StateFormatError(f"floor map {fid!r}: its grids differ in size")
    return state


def load_geometry(map_dir: str | Path, config: Config, session_id: str) -> GeometricStream:
    """The stream of earlier sessions (or a new one), ready for ``session_id``."""
    path = Path(map_dir) / STATE_FILE
    fresh = GeometricStream(
        config, session_id=session_id, image_feature_dim=config.store.image_feature_dim
    )
    note = legacy_state_note(map_dir)
    if note is not None:
        log.warning("%s", note)
    if not path.is_file():
        return fresh
    try:
        data = load_state(path, _classes())
        if not isinstance(data, dict) or data.get("format") != STATE_FORMAT:
            found = data.get("format") if isinstance(data, dict) else None
            raise StateFormatError(f"format {found!r}, expected {STATE_FORMAT}")
        state = _check_stream(data.get("state"))
    except StateFormatError as exc:  # an unreadable state must not make the map unusable
        log.warning("ignoring geometry state %s (%s); starting a fresh geometric stream", path, exc)
        return fresh
    stream = GeometricStream.__new__(GeometricStream)
    vars(stream).update(state)
    for name in _TRANSIENT:
        if hasattr(fresh, name):
            setattr(stream, name, getattr(fresh, name))
    stream.session_id = session_id
    stream.cfg = config.geometry
    return stream


def new_queue(stream: GeometricStream, capacity: int) -> KeyframeQueue:
    """Replace the stream's keyframe queue (e.g. a larger one for offline builds)."""
    stream.queue = KeyframeQueue(capacity)
    return stream.queue
