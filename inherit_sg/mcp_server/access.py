"""Who may call which MCP tool: the REST service's key rules (:mod:`inherit_sg.api.security`)
applied to tools.

* No ``service.read_keys`` and no ``service.write_keys``: every tool but the live mapping
  ones is open (those are offered only when a write key is configured).
* Any key configured: every request needs a valid key, read or write. Over HTTP that is
  the ``Authorization: Bearer <key>`` header (a request without one answers 401 before it
  reaches MCP); over stdio the key is the ``INHERIT_SG_MCP_KEY`` environment variable of
  the server process, checked when it starts.
* The write tools need a write key, as their REST routes do: ``cypher`` (read-only, but a
  write-key route in REST) and the live mapping tools that add to a map. A caller without
  one does not see them in the tool list, and calling one answers an error naming the key
  it lacks.
"""

from __future__ import annotations

from collections.abc import Mapping

from inherit_sg.api.security import KeyRing, parse_bearer
from inherit_sg.config import ENV_PREFIX, Config
from inherit_sg.errors import InputError

KEY_ENV = f"{ENV_PREFIX}MCP_KEY"
# the scope of a caller when no key is configured at all
OPEN = "open"
WRITE = "write"
# tools that add to a map: offered only when service.write_keys is set
LIVE_TOOLS = frozenset({"start_session", "add_frame", "finish_session"})
# tools that need a write key whenever keys are configured
WRITE_TOOLS = LIVE_TOOLS | {"cypher"}


class Access:
    """The configured keys and, over stdio, the key the server process was given."""

    def __init__(self, config: Config, *, stdio_key: str | None = None) -> None:
        svc = config.service
        self.keys = KeyRing(svc.read_keys, svc.write_keys)
        self.live = bool(svc.write_keys)
        self.stdio_key = stdio_key

    def scope(self, headers: Mapping[str, str] | None) -> str | None:
        """``"open"`` (no keys configured), ``"write"``, ``"read"`` or None (no valid key)
        for a request: ``headers`` are its HTTP headers, None over stdio."""
        if not self.keys.enabled:
            return OPEN
        token = self.stdio_key if headers is None else parse_bearer(headers.get("authorization"))
        return self.keys.scope_of(token)

    def allows(self, tool: str, scope: str | None) -> bool:
        """Whether a caller with ``scope`` may see and call ``tool``."""
        if scope is None:
            return False
        if tool in LIVE_TOOLS:
            return scope == WRITE
        return tool not in WRITE_TOOLS or scope in (WRITE, OPEN)

    def refusal(self, tool: str, headers: Mapping[str, str] | None) -> str | None:
        """Why the request with ``headers`` may not call ``tool``; None when it may."""
        if self.allows(tool, self.scope(headers)):
            return None
        how = (
            f"the {KEY_ENV} environment variable"
            if headers is None
            else "Authorization: Bearer KEY"
        )
        return f"{tool} needs a write key (service.write_keys), sent as {how}"

    def check_stdio(self) -> None:
        """InputError unless the stdio server may serve: no keys configured, or a valid
        key in :data:`KEY_ENV`."""
        if self.scope(None) is None:
            given = "an unknown key" if self.stdio_key else "no key"
            raise InputError(
                f"API keys are configured (service.read_keys / service.write_keys) and "
                f"{KEY_ENV} holds {given}: set it to a read or write key"
            )
