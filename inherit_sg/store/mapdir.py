"""The map directory layout and ``map.json`` (the map's identity card).

A map is a directory holding ``map.json``, ``graph.kuzu`` (+ its ``.wal``; the scene
graph), ``index.kuzu`` (+ ``.wal``; vector and full-text indexes derived from the graph),
``lance/`` (keyframes) and ``map.lock``. ``map.json`` is written last when a map is
created, so its presence is what makes a directory a map; it is always replaced
atomically (write, fsync, rename).

``map.json`` also records the vocabulary the map was built with (the versions and digest
of :func:`inherit_sg.vocab.vocabulary_info`) and its label space, the distinct object
labels its mapping sessions produced (:func:`record_session_vocabulary`).
"""

from __future__ import annotations

import copy
import json
import logging
import os
import tempfile
from collections.abc import Iterable
from dataclasses import asdict, dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from inherit_sg import __version__
from inherit_sg.config import Config
from inherit_sg.errors import MapCorruptError, MapNotFoundError
from inherit_sg.vocab import vocabulary_info

MAP_JSON = "map.json"
GRAPH_FILE = "graph.kuzu"
INDEX_FILE = "index.kuzu"
LANCE_DIR = "lance"
LOCK_FILE = "map.lock"
MAP_FORMAT = "inherit-sg-map"

log = logging.getLogger(__name__)


@dataclass
class MapInfo:
    """Mirror of ``map.json``: what fixes the map's shape, plus its session list, the
    vocabulary it was last mapped with (``{"versions": {file: version}, "digest": …}``;
    empty for maps made before it was recorded) and its label space (sorted distinct
    object labels of its mapping sessions)."""

    schema_version: int
    text_embedder: str
    text_dim: int
    visual_encoder: str
    visual_dim: int
    image_feature_dim: int
    created: str = field(default_factory=lambda: datetime.now(UTC).isoformat())
    inherit_sg_version: str = __version__
    sessions: list[dict[str, Any]] = field(default_factory=list)
    format: str = MAP_FORMAT
    vocabulary: dict[str, Any] = field(default_factory=dict)
    label_space: list[str] = field(default_factory=list)

    @classmethod
    def from_config(cls, config: Config, schema_version: int) -> MapInfo:
        """Card of a new map built with ``config``."""
        return cls(
            schema_version=schema_version,
            text_embedder=config.embedder.model,
            text_dim=config.store.text_dim,
            visual_encoder=config.perception.visual_encoder,
            visual_dim=config.store.visual_dim,
            image_feature_dim=config.store.image_feature_dim,
            vocabulary=copy.deepcopy(vocabulary_info()),
        )

    @property
    def dims(self) -> dict[str, int]:
        """Vector sizes by placeholder name (as used in schema migrations)."""
        return {
            "visual_dim": self.visual_dim,
            "text_dim": self.text_dim,
            "image_feature_dim": self.image_feature_dim,
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON form written to ``map.json``."""
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any], where: Path) -> MapInfo:
        """Parse ``map.json``; MapCorruptError names the file and the bad field."""
        if data.get("format", MAP_FORMAT) != MAP_FORMAT:
            raise MapCorruptError(f"{where}: not an INHerit-SG map (format {data.get('format')!r})")
        known = set(cls.__dataclass_fields__)
        if not isinstance(data.get("vocabulary", {}), dict):
            raise MapCorruptError(f"{where}: 'vocabulary' must be an object")
        labels = data.get("label_space", [])
        if not isinstance(labels, list) or not all(isinstance(x, str) for x in labels):
            raise MapCorruptError(f"{where}: 'label_space' must be a list of strings")
        try:
            return cls(**{k: v for k, v in data.items() if k in known})
        except TypeError as exc:
            raise MapCorruptError(f"{where}: missing or bad field ({exc})") from None


def is_map_dir(path: Path) -> bool:
    """Whether ``path`` is a map directory (has a ``map.json``)."""
    return (path / MAP_JSON).is_file()


def read_map_info(path: Path) -> MapInfo:
    """Read ``<path>/map.json``; MapNotFoundError when ``path`` is not a map."""
    file = path / MAP_JSON
    if path.exists() and not path.is_dir():
        raise MapNotFoundError(f"{path} is a file, not a map directory")
    if not path.is_dir():
        raise MapNotFoundError(f"map {path} does not exist")
    if not file.is_file():
        raise MapNotFoundError(f"{path} is not an INHerit-SG map (no {MAP_JSON})")
    try:
        data = json.loads(file.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:  # JSON or UTF-8 decoding
        raise MapCorruptError(f"{file}: unreadable ({exc})") from None
    if not isinstance(data, dict):
        raise MapCorruptError(f"{file}: expected a JSON object")
    return MapInfo.from_dict(data, file)


def write_map_info(path: Path, info: MapInfo) -> None:
    """Atomically replace ``<path>/map.json``."""
    text = json.dumps(info.to_dict(), indent=2, sort_keys=True) + "\n"
    fd, tmp = tempfile.mkstemp(prefix=".map.json.", dir=path)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path / MAP_JSON)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    dir_fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def _describe(vocabulary: dict[str, Any]) -> str:
    versions = vocabulary.get("versions") or {}
    listed = ", ".join(f"{name} v{v}" for name, v in versions.items())
    return f"{vocabulary.get('digest')} ({listed})" if listed else str(vocabulary.get("digest"))


def record_session_vocabulary(path: Path, info: MapInfo, labels: Iterable[str]) -> None:
    """After a mapping session of the map at ``path``: add the session's object
    ``labels`` to ``info.label_space`` (sorted union with what was there) and record the
    vocabulary the session ran with, then rewrite ``map.json`` when either changed.

    When the recorded vocabulary digest differs from the current one, the map stays
    usable: the new vocabulary is recorded and a warning names both (labels from either
    vocabulary stay in the map and in its label space)."""
    current = copy.deepcopy(vocabulary_info())
    recorded = info.vocabulary.get("digest")
    if recorded and recorded != current["digest"]:
        log.warning(
            "map %s was mapped with vocabulary %s; this session used vocabulary %s: "
            "recording the new one (labels from both stay in the map)",
            path,
            _describe(info.vocabulary),
            _describe(current),
        )
    label_space = sorted(set(info.label_space) | {lab for lab in labels if lab})
    if info.vocabulary == current and info.label_space == label_space:
        return
    info.vocabulary = current
    info.label_space = label_space
    write_map_info(path, info)


def dir_bytes(path: Path) -> int:
    """Total size of the regular files under ``path`` (0 if absent)."""
    if path.is_file():
        return path.stat().st_size
    total = 0
    for root, _dirs, files in os.walk(path):
        for name in files:
            try:
                total += (Path(root) / name).stat().st_size
            except FileNotFoundError:
                continue  # removed while walking (e.g. lance cleanup)
    return total
