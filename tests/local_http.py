"""A real HTTP server on loopback for tests of clients of external endpoints (the
OpenAI-compatible chat protocol): start it, yield its /v1 base URL, stop it."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer


@contextmanager
def serve_on_loopback(
    handler: type[BaseHTTPRequestHandler],
) -> Iterator[tuple[ThreadingHTTPServer, str]]:
    """Serve ``handler`` on 127.0.0.1 (a free port) in a daemon thread."""
    httpd = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    httpd.daemon_threads = True
    thread = threading.Thread(
        target=httpd.serve_forever, kwargs={"poll_interval": 0.02}, daemon=True
    )
    thread.start()
    try:
        yield httpd, f"http://127.0.0.1:{httpd.server_address[1]}/v1"
    finally:
        httpd.shutdown()
        httpd.server_close()
