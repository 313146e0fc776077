"""Real HTTP servers on loopback for tests: a handler-based server for clients of
external endpoints (the OpenAI-compatible chat protocol), a uvicorn server for our own
app, and free port numbers."""

from __future__ import annotations

import socket
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

import uvicorn


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


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on (at the time of the call)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextmanager
def uvicorn_on_loopback(
    app: Any, *, start_timeout_s: float = 30.0, stop_timeout_s: float = 120.0
) -> Iterator[tuple[str, uvicorn.Server, threading.Thread]]:
    """Serve the ASGI ``app`` with uvicorn in a thread on a free loopback port; yield
    (base URL, server, thread) once it accepts connections, and stop it afterwards."""
    port = free_port()
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + start_timeout_s
    while not server.started:
        assert thread.is_alive() and time.monotonic() < deadline, "uvicorn did not start"
        time.sleep(0.02)
    try:
        yield f"http://127.0.0.1:{port}", server, thread
    finally:
        server.should_exit = True
        thread.join(timeout=stop_timeout_s)
