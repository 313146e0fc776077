"""Served maps: one read-only :class:`MapService` per map, opened once per app, and the
server-side conversation histories keyed by (map, conversation id)."""

from __future__ import annotations

import re
import threading
from collections import OrderedDict
from pathlib import Path

from inherit_sg.config import Config
from inherit_sg.errors import InheritSGError, MapNotFoundError
from inherit_sg.facade import MapService
from inherit_sg.retrieval.conversation import Conversation

MAP_NAME = re.compile(r"^[A-Za-z0-9_.-]+$")
MAX_CONVERSATIONS = 1000


def resolve_maps(maps: dict[str, Path] | Path) -> dict[str, Path]:
    """Name → directory of the maps to serve: a dict as given, a map directory under its
    basename, or every map directory directly inside a root folder."""
    if isinstance(maps, dict):
        named = {name: Path(p) for name, p in maps.items()}
    else:
        root = Path(maps)
        if (root / "map.json").is_file():
            named = {root.resolve().name: root}
        elif root.is_dir():
            named = {p.name: p for p in sorted(root.iterdir()) if (p / "map.json").is_file()}
        else:
            raise MapNotFoundError(f"map directory not found: {root}")
        if not named:
            raise MapNotFoundError(f"{root} is neither a map nor a folder of maps")
    for name in named:
        if not valid_name(name):
            raise MapNotFoundError(f"map name {name!r}: use letters, digits, '_', '.', '-'")
    return named


def valid_name(name: str) -> bool:
    """True for a servable map name (no separators, not '.' or '..')."""
    return bool(MAP_NAME.match(name)) and name not in (".", "..")


class ServedMap:
    """One open map; ``lock`` serialises use of its connection and engine."""

    def __init__(self, name: str, path: Path, config: Config) -> None:
        self.name = name
        self.path = path
        self.lock = threading.Lock()
        self.service: MapService | None = None
        self.error: InheritSGError | None = None
        try:
            self.service = MapService.open(path, config=config)
        except InheritSGError as exc:
            self.error = exc

    def require(self) -> MapService:
        """The open service, or the error that kept the map from opening."""
        if self.service is None:
            assert self.error is not None
            raise self.error
        return self.service

    def close(self) -> None:
        """Release the map."""
        if self.service is not None:
            self.service.close()
            self.service = None


class Registry:
    """The maps an app serves and their conversations."""

    def __init__(self, maps: dict[str, Path], config: Config) -> None:
        self.maps = {name: ServedMap(name, path, config) for name, path in maps.items()}
        self._conversations: OrderedDict[tuple[str, str], Conversation] = OrderedDict()
        self._conv_lock = threading.Lock()

    def get(self, name: str) -> ServedMap:
        """The served map called ``name``; MapNotFoundError (404) otherwise."""
        served = self.maps.get(name) if valid_name(name) else None
        if served is None:
            raise MapNotFoundError(f"no map named {name!r} is served here")
        return served

    def conversation(self, map_name: str, conversation_id: str) -> Conversation:
        """The history of one conversation (created on first use; oldest dropped first)."""
        key = (map_name, conversation_id)
        with self._conv_lock:
            conv = self._conversations.get(key)
            if conv is None:
                conv = Conversation()
                self._conversations[key] = conv
                while len(self._conversations) > MAX_CONVERSATIONS:
                    self._conversations.popitem(last=False)
            else:
                self._conversations.move_to_end(key)
            return conv

    def close(self) -> None:
        """Close every map."""
        for served in self.maps.values():
            served.close()
