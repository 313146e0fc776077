"""The one error hierarchy of INHerit-SG.

Every error the library raises on purpose derives from :class:`InheritSGError`. Each
class carries the HTTP status the REST API answers with, so the mapping lives here, in
one place, and the CLI and the service stay thin.
"""

from __future__ import annotations


class InheritSGError(Exception):
    """Base class of every error INHerit-SG raises on purpose."""

    http_status: int = 500
    code: str = "internal_error"

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message

    def to_dict(self) -> dict[str, str]:
        """JSON-able body used by the CLI (``--json``) and the REST API."""
        return {"error": self.code, "message": self.message}


class ConfigError(InheritSGError):
    """A configuration file, environment variable or override is invalid."""

    http_status = 500
    code = "config_error"


class InputError(InheritSGError):
    """Input supplied by the user is malformed (bad frame, bad file, bad query text)."""

    http_status = 400
    code = "bad_input"


class DatasetError(InputError):
    """A dataset folder or file is missing or malformed."""

    code = "bad_dataset"


class FrameError(InputError):
    """One RGB-D frame is malformed: wrong size, NaN pose, unreadable image."""

    code = "bad_frame"


class QueryTextError(InputError):
    """A natural-language request is empty, too long or not text."""

    code = "bad_query"


class ReadOnlyViolationError(InputError):
    """A read-only Cypher statement tried to write (CREATE, SET, DELETE, COPY, ...)."""

    http_status = 403
    code = "read_only"


class CypherError(InputError):
    """Kuzu rejected a Cypher statement (syntax or binder error)."""

    code = "cypher_error"


class CypherCrashError(CypherError):
    """A read-only Cypher statement crashed the graph database engine in its worker
    process; the map and the service are unaffected."""

    code = "cypher_crashed"


class QueryTimeoutError(CypherError):
    """A Cypher statement ran past its time limit and was interrupted."""

    http_status = 408
    code = "query_timeout"


class NotFoundError(InheritSGError):
    """Something named by the user does not exist."""

    http_status = 404
    code = "not_found"


class MapNotFoundError(NotFoundError):
    """The map directory does not exist or is not an INHerit-SG map."""

    code = "map_not_found"


class NodeNotFoundError(NotFoundError):
    """A node id is not in the map."""

    code = "node_not_found"


class MapError(InheritSGError):
    """A map exists but cannot be used as asked."""

    http_status = 409
    code = "map_error"


class MapLockedError(MapError):
    """Another process holds the map's writer lock."""

    http_status = 423
    code = "map_locked"


class SchemaVersionError(MapError):
    """The map was written by a newer INHerit-SG schema than this one understands."""

    code = "schema_version"


class MapCorruptError(MapError):
    """The map's files are inconsistent or unreadable."""

    http_status = 500
    code = "map_corrupt"


class BackPressureError(InheritSGError):
    """A bounded queue is full; the client should retry later."""

    http_status = 503
    code = "busy"

    def __init__(self, message: str, retry_after_s: float = 1.0) -> None:
        super().__init__(message)
        self.retry_after_s = retry_after_s


class IntakeFullError(BackPressureError):
    """A live session's frame intake is saturated; the client should slow down."""

    http_status = 429
    code = "too_many_frames"


class ModelUnavailableError(InheritSGError):
    """A model backend cannot be loaded (missing local path, missing package)."""

    http_status = 503
    code = "model_unavailable"


class EndpointError(ModelUnavailableError):
    """An OpenAI-compatible endpoint is down, timed out or answered garbage."""

    code = "endpoint_error"
