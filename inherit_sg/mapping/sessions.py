"""The record of a new mapping session: the next ``session:N`` id of a map and a name
no earlier session of it uses (recorded datasets and live sessions number alike)."""

from __future__ import annotations

import time

from inherit_sg.errors import InheritSGError
from inherit_sg.model import Session
from inherit_sg.store import MapStore


def new_session(
    store: MapStore,
    name: str | None,
    *,
    dataset: str,
    default_prefix: str,
    taken: type[InheritSGError],
) -> Session:
    """A session after every earlier one of ``store``, named ``name`` (default
    ``{default_prefix}-N``); ``taken`` is raised when that name is already used. The
    caller records it (``store.upsert_session``) once mapping can start."""
    earlier = store.sessions()
    index = len(earlier) + 1
    chosen = name or f"{default_prefix}-{index}"
    if any(s.name == chosen for s in earlier):
        raise taken(f"map {store.path} already has a session named {chosen!r}")
    return Session(id=f"session:{index}", name=chosen, started=time.time(), dataset=dataset)
