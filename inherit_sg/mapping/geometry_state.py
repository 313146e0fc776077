"""Persist the geometric stream between sessions, so that a later session on the same
map continues its occupancy grids, floors and room ids instead of starting over.

The state lives in ``<map>/geometry.pkl`` with a format header; a file written by an
incompatible version is ignored (a fresh stream starts, and the map stays usable).
"""

from __future__ import annotations

import logging
import os
import pickle
from pathlib import Path

from inherit_sg.config import Config
from inherit_sg.geometry.gating import KeyframeQueue
from inherit_sg.geometry.stream import GeometricStream

log = logging.getLogger(__name__)

STATE_FILE = "geometry.pkl"
STATE_FORMAT = 1
# the keyframe gate compares frame indices and features of this session only
_TRANSIENT = ("queue", "keyframes", "stats", "_pending", "lock", "image_feature", "gate")


def save_geometry(stream: GeometricStream, map_dir: str | Path) -> Path:
    """Write the stream's persistent state atomically (write + rename)."""
    state = {k: v for k, v in vars(stream).items() if k not in _TRANSIENT}
    path = Path(map_dir) / STATE_FILE
    tmp = path.with_suffix(".tmp")
    with open(tmp, "wb") as fh:
        pickle.dump({"format": STATE_FORMAT, "state": state}, fh, protocol=pickle.HIGHEST_PROTOCOL)
        fh.flush()
        os.fsync(fh.fileno())
    tmp.replace(path)
    return path


def load_geometry(map_dir: str | Path, config: Config, session_id: str) -> GeometricStream:
    """The stream of earlier sessions (or a new one), ready for ``session_id``."""
    path = Path(map_dir) / STATE_FILE
    fresh = GeometricStream(
        config, session_id=session_id, image_feature_dim=config.store.image_feature_dim
    )
    if not path.is_file():
        return fresh
    try:
        with open(path, "rb") as fh:
            data = pickle.load(fh)
        if data.get("format") != STATE_FORMAT:
            raise ValueError(f"format {data.get('format')}")
    except Exception as exc:  # an unreadable state must not make the map unusable
        log.warning("ignoring geometry state %s (%s); starting a fresh geometric stream", path, exc)
        return fresh
    stream = GeometricStream.__new__(GeometricStream)
    vars(stream).update(data["state"])
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
