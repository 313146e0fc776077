"""Served maps: one :class:`MapService` per map, opened once per app, and the server-side
conversation histories keyed by (map, conversation id).

A map is served read-only, except while a live mapping session runs on it: starting the
session reopens the map for writing (one writable store shared by the session's mapper
and the query engine, so requests keep working and see each flush), and finishing it
reopens the map read-only, releasing the writer lock for other processes."""

from __future__ import annotations

import logging
import re
import threading
from collections import OrderedDict
from pathlib import Path
from typing import TYPE_CHECKING, Any

from starlette.requests import Request

from inherit_sg.config import Config
from inherit_sg.errors import InheritSGError, MapError, MapNotFoundError, NotFoundError
from inherit_sg.facade import MapService
from inherit_sg.retrieval.conversation import Conversation

if TYPE_CHECKING:
    from inherit_sg.mapping.live import LiveSession

MAP_NAME = re.compile(r"^[A-Za-z0-9_.-]+$")
MAX_CONVERSATIONS = 1000
MAX_FINISHED_SESSIONS = 100
log = logging.getLogger(__name__)


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
            # hidden folders are skipped: build-many's maps in the making (.NAME.*.partial)
            named = {
                p.name: p
                for p in sorted(root.iterdir())
                if (p / "map.json").is_file() and not p.name.startswith(".")
            }
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
    """One open map; ``lock`` serialises use of its service and query engine."""

    def __init__(self, name: str, path: Path, config: Config) -> None:
        self.name = name
        self.path = path
        self.config = config
        self.lock = threading.Lock()
        self.service: MapService | None = None
        self.error: InheritSGError | None = None
        self.live: LiveSession | None = None
        self.finished: OrderedDict[str, dict[str, Any]] = OrderedDict()
        self._live_lock = threading.Lock()  # starting and ending live sessions
        self._reopen(write=False)

    def _reopen(self, *, write: bool) -> None:
        """Close the service and open the map again (caller holds ``lock`` once served)."""
        if self.service is not None:
            self.service.close()
            self.service = None
        try:
            self.service = MapService.open(self.path, write=write, config=self.config)
            self.error = None
        except InheritSGError as exc:
            self.error = exc

    @property
    def status(self) -> str:
        """'ok' when the map is open, else the reason it is not."""
        if self.service is not None:
            return "ok"
        return self.error.message if self.error is not None else "closed"

    def require(self) -> MapService:
        """The open service, or the error that kept the map from opening."""
        if self.service is None:
            assert self.error is not None
            raise self.error
        return self.service

    # ----------------------------------------------------------- live sessions
    def start_live(
        self, name: str | None = None, *, frame_queue: int = 8, flush_every: int = 20
    ) -> LiveSession:
        """Reopen the map for writing and start a live session on it; MapError (409)
        while another one runs, MapLockedError (423) when another process writes."""
        if self.config.service.workers > 1:
            raise MapError(
                f"map {self.name!r} is served read-only by {self.config.service.workers} "
                "processes: live sessions need a server with one process (serve --workers 1)"
            )
        with self._live_lock:
            if self.live is not None:
                raise MapError(f"map {self.name!r} already has a live session ({self.live.id})")
            with self.lock:
                self.require()
                self._reopen(write=True)
                try:
                    live = self.require().live_session(
                        name, frame_queue=frame_queue, flush_every=flush_every
                    )
                except BaseException:
                    self._reopen(write=False)  # the map stays served read-only
                    raise
            self.live = live
            return live

    def active(self, session_id: str) -> LiveSession:
        """The running (or finishing) live session ``session_id``; MapError (409) when it
        has finished, NotFoundError (404) when there is none."""
        live = self.live
        if live is not None and live.id == session_id:
            return live
        if session_id in self.finished:
            state = self.finished[session_id]["state"]
            raise MapError(f"live session {session_id} of map {self.name!r} has {state}")
        raise NotFoundError(f"map {self.name!r} has no live session {session_id!r}")

    def live_status(self, session_id: str) -> dict[str, Any]:
        """Counters of a running or finished session; NotFoundError (404) otherwise."""
        live = self.live
        if live is not None and live.id == session_id:
            return {**live.status(), "map": self.name}
        if session_id in self.finished:
            return self.finished[session_id]
        raise NotFoundError(f"map {self.name!r} has no live session {session_id!r}")

    def finish_live(self, session_id: str) -> dict[str, Any]:
        """Finish a live session (its mapping summary) and serve the map read-only again;
        a finished session's summary is answered again."""
        done = self.finished.get(session_id)
        if done is not None and done.get("summary") is not None:
            return dict(done["summary"])
        live = self.active(session_id)
        try:
            return live.finish()
        finally:
            if live.ended:
                self._end_live(live)

    def _end_live(self, live: LiveSession) -> None:
        with self._live_lock:
            if self.live is not live:
                return
            self.finished[live.id] = {**live.status(), "map": self.name}
            while len(self.finished) > MAX_FINISHED_SESSIONS:
                self.finished.popitem(last=False)
            with self.lock:
                self.live = None
                self._reopen(write=False)

    def close(self) -> None:
        """Finish a live session left open (best effort), then release the map."""
        live = self.live
        if live is not None:
            try:
                self.finish_live(live.id)
            except InheritSGError as exc:
                log.error("map %s: live session %s not finished: %s", self.name, live.id, exc)
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


def served_map(request: Request, name: str) -> ServedMap:
    """The map called ``name`` served by the app handling ``request`` (404 otherwise)."""
    registry: Registry = request.app.state.registry
    return registry.get(name)
