"""The map directory layout and ``map.json`` (the map's identity card).

A map is a directory holding ``map.json``, ``graph.kuzu`` (+ its ``.wal``; the scene
graph), ``index.kuzu`` (+ ``.wal``; vector and full-text indexes derived from the graph),
``lance/`` (keyframes) and ``map.lock``. ``map.json`` is written last when a map is created, so its presence is
what makes a directory a map; it is always replaced atomically (write, fsync, rename).
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import asdict, dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from inherit_sg import __version__
from inherit_sg.config import Config
from inherit_sg.errors import MapCorruptError, MapNotFoundError

MAP_JSON = "map.json"
GRAPH_FILE = "graph.kuzu"
INDEX_FILE = "index.kuzu"
LANCE_DIR = "lance"
LOCK_FILE = "map.lock"
MAP_FORMAT = "inherit-sg-map"


@dataclass
class MapInfo:
    """Mirror of ``map.json``: what fixes the map's shape, plus its session list."""

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
    if not path.is_dir():
        raise MapNotFoundError(f"map {path} does not exist")
    if not file.is_file():
        raise MapNotFoundError(f"{path} is not an INHerit-SG map (no {MAP_JSON})")
    try:
        data = json.loads(file.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
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
