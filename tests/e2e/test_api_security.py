"""Security of the REST service on a real map: the API-key matrix (401/403/200), open
routes, body size limits (declared and streamed), CORS only when configured, map-name
traversal, and the ``serve`` command's config defaults and exposure warning."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import typer
import uvicorn
from fastapi.testclient import TestClient
from starlette.requests import Request
from starlette.responses import JSONResponse
from starlette.types import Message, Receive, Scope, Send
from typer.testing import CliRunner

from inherit_sg.api.app import create_app
from inherit_sg.api.security_body import BodyLimitMiddleware
from inherit_sg.cli.serve_cmd import exposure_warning, is_loopback, serve
from inherit_sg.config import Config, ServiceConfig, load_config
from inherit_sg.errors import ConfigError
from tests.e2e.oracle_maps import oracle_map

NAME = "secure"
READ, WRITE = "read-key-1", "write-key-1"


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return oracle_map(tmp_path_factory.mktemp("api_security"), NAME, 5)


def keyed_config(**service: Any) -> Config:
    return Config(service=ServiceConfig(read_keys=[READ], write_keys=[WRITE], **service))


@pytest.fixture(scope="module")
def client(map_dir: Path) -> Iterator[TestClient]:
    with TestClient(create_app(map_dir, keyed_config(max_body_mb=0.01))) as c:
        yield c


def auth(key: str | None) -> dict[str, str]:
    return {} if key is None else {"Authorization": f"Bearer {key}"}


QUERY = {"text": "a chair", "verify": False}
CYPHER = {"query": "MATCH (r:Room) RETURN count(*)"}
ROUTES: list[tuple[str, str, dict[str, Any] | None, bool]] = [
    ("GET", f"/v1/maps/{NAME}", None, False),
    ("GET", f"/v1/maps/{NAME}/objects?limit=2", None, False),
    ("POST", f"/v1/maps/{NAME}/query", QUERY, False),
    ("POST", f"/v1/maps/{NAME}/cypher", CYPHER, True),
]
KEYS: list[tuple[str | None, str]] = [
    (None, "none"),
    ("not-a-key", "unknown"),
    (READ + "x", "read-prefix"),
    (READ, "read"),
    (WRITE, "write"),
]


@pytest.mark.parametrize(("method", "path", "body", "write_route"), ROUTES)
@pytest.mark.parametrize(("key", "kind"), KEYS)
def test_key_matrix(
    client: TestClient,
    method: str,
    path: str,
    body: dict[str, Any] | None,
    write_route: bool,
    key: str | None,
    kind: str,
) -> None:
    resp = client.request(method, path, json=body, headers=auth(key))
    if kind in {"none", "unknown", "read-prefix"}:
        assert resp.status_code == 401, resp.text
        assert resp.json()["error"] == "unauthorized" and "Bearer" in resp.json()["message"]
        assert resp.headers["www-authenticate"].startswith("Bearer")
    elif kind == "read" and write_route:
        assert resp.status_code == 403, resp.text
        assert resp.json()["error"] == "forbidden" and "write key" in resp.json()["message"]
    else:
        assert resp.status_code == 200, resp.text


@pytest.mark.parametrize("header", ["Basic " + WRITE, "Bearer", "Bearer  ", WRITE, "bearer x"])
def test_malformed_authorization_is_unauthorized(client: TestClient, header: str) -> None:
    resp = client.get(f"/v1/maps/{NAME}", headers={"Authorization": header})
    assert resp.status_code == 401 and resp.json()["error"] == "unauthorized"


def test_scheme_is_case_insensitive(client: TestClient) -> None:
    resp = client.get(f"/v1/maps/{NAME}", headers={"Authorization": f"bearer {READ}"})
    assert resp.status_code == 200


def test_session_routes_need_write_scope(client: TestClient) -> None:
    url = f"/v1/maps/{NAME}/sessions"
    assert client.post(url, json={"name": "s"}).status_code == 401
    read = client.post(url, json={"name": "s"}, headers=auth(READ))
    assert read.status_code == 403 and read.json()["error"] == "forbidden"
    frames = client.post(f"{url}/abc/frames", headers=auth(READ))
    assert frames.status_code == 403


@pytest.mark.parametrize("path", ["/healthz", "/readyz", "/openapi.json", "/docs"])
def test_open_routes_need_no_key(client: TestClient, path: str) -> None:
    resp = client.get(path)
    assert resp.status_code == 200, resp.text
    assert "www-authenticate" not in resp.headers


def test_viewer_root_is_not_behind_keys(client: TestClient) -> None:
    assert client.get("/").status_code != 401


def test_no_keys_means_open(map_dir: Path) -> None:
    with TestClient(create_app(map_dir, Config())) as c:
        assert c.get(f"/v1/maps/{NAME}").status_code == 200
        assert c.post(f"/v1/maps/{NAME}/cypher", json=CYPHER).status_code == 200


def test_write_key_alone_enables_keys(map_dir: Path) -> None:
    cfg = Config(service=ServiceConfig(write_keys=[WRITE]))
    with TestClient(create_app(map_dir, cfg)) as c:
        assert c.get(f"/v1/maps/{NAME}").status_code == 401
        assert c.get(f"/v1/maps/{NAME}", headers=auth(WRITE)).status_code == 200


def test_keys_from_environment(map_dir: Path) -> None:
    env = {"INHERIT_SG_SERVICE__WRITE_KEYS": f'["{WRITE}"]'}
    with TestClient(create_app(map_dir, load_config(environ=env))) as c:
        assert c.get(f"/v1/maps/{NAME}").status_code == 401
        assert c.post(f"/v1/maps/{NAME}/cypher", json=CYPHER, headers=auth(WRITE)).is_success


def test_empty_key_is_a_config_error(map_dir: Path) -> None:
    with pytest.raises(ConfigError, match="read_keys"):
        create_app(map_dir, Config(service=ServiceConfig(read_keys=[" "])))


def test_declared_body_over_limit(client: TestClient) -> None:
    big = {"text": "chair " * 4000}  # ~24 kB against a 10 kB limit
    resp = client.post(f"/v1/maps/{NAME}/query", json=big, headers=auth(READ))
    assert resp.status_code == 413, resp.text
    assert resp.json()["error"] == "payload_too_large"
    assert "service.max_body_mb" in resp.json()["message"]
    small = client.post(f"/v1/maps/{NAME}/query", json=QUERY, headers=auth(READ))
    assert small.status_code == 200


def test_streamed_body_over_limit(client: TestClient) -> None:
    def chunks() -> Iterator[bytes]:
        yield b'{"text": "'
        for _ in range(40):
            yield b"x" * 1024
        yield b'"}'

    resp = client.post(
        f"/v1/maps/{NAME}/query",
        content=chunks(),
        headers={**auth(READ), "Content-Type": "application/json"},
    )
    assert resp.status_code == 413 and resp.json()["error"] == "payload_too_large"


def test_oversized_body_without_key_is_unauthorized_first(client: TestClient) -> None:
    resp = client.post(f"/v1/maps/{NAME}/query", json={"text": "x" * 20000})
    assert resp.status_code == 401


async def _echo_length(scope: Scope, receive: Receive, send: Send) -> None:
    body = await Request(scope, receive).body()
    await JSONResponse({"length": len(body)})(scope, receive, send)


async def _drive(chunks: list[bytes], headers: list[tuple[bytes, bytes]]) -> list[Message]:
    """Run the body limiter (10 bytes) over a real Starlette endpoint; return what it sent."""
    pending = [
        {"type": "http.request", "body": c, "more_body": i < len(chunks) - 1}
        for i, c in enumerate(chunks)
    ]
    pulled: list[int] = []

    async def receive() -> Message:
        pulled.append(1)
        return pending.pop(0) if pending else {"type": "http.disconnect"}

    sent: list[Message] = []

    async def send(message: Message) -> None:
        sent.append(message)

    scope = {"type": "http", "method": "POST", "path": "/x", "headers": headers}
    await BodyLimitMiddleware(_echo_length, max_bytes=10)(scope, receive, send)
    sent.append({"type": "test.pulled", "count": len(pulled)})
    return sent


@pytest.mark.anyio
async def test_limiter_stops_reading_a_chunked_body() -> None:
    sent = await _drive([b"abcd", b"efgh", b"ijkl", b"mnop", b"qrst"], [])
    starts = [m for m in sent if m["type"] == "http.response.start"]
    assert [m["status"] for m in starts] == [413]
    assert sent[-1]["count"] == 3  # stopped at the chunk that crossed 10 bytes
    body = json.loads(b"".join(m.get("body", b"") for m in sent if m["type"].endswith("body")))
    assert body["error"] == "payload_too_large"


@pytest.mark.anyio
async def test_limiter_passes_small_and_rejects_bad_length() -> None:
    sent = await _drive([b"abc", b"def"], [])
    assert sent[0]["status"] == 200 and json.loads(sent[1]["body"]) == {"length": 6}
    bad = await _drive([b"abc"], [(b"content-length", b"3x")])
    assert bad[0]["status"] == 400 and bad[-1]["count"] == 0
    declared = await _drive([b"abc"], [(b"content-length", b"11")])
    assert declared[0]["status"] == 413 and declared[-1]["count"] == 0


ORIGIN = "https://viewer.example"


def test_cors_off_by_default(client: TestClient) -> None:
    resp = client.get("/healthz", headers={"Origin": ORIGIN})
    assert "access-control-allow-origin" not in resp.headers


def test_cors_exact_origins(map_dir: Path) -> None:
    with TestClient(create_app(map_dir, keyed_config(cors_origins=[ORIGIN]))) as c:
        ok = c.get(f"/v1/maps/{NAME}", headers={"Origin": ORIGIN, **auth(READ)})
        assert ok.headers["access-control-allow-origin"] == ORIGIN
        other = c.get(f"/v1/maps/{NAME}", headers={"Origin": "https://evil.example", **auth(READ)})
        assert "access-control-allow-origin" not in other.headers
        denied = c.get(f"/v1/maps/{NAME}", headers={"Origin": ORIGIN})
        assert denied.status_code == 401
        assert denied.headers["access-control-allow-origin"] == ORIGIN
        preflight = c.options(
            f"/v1/maps/{NAME}/query",
            headers={
                "Origin": ORIGIN,
                "Access-Control-Request-Method": "POST",
                "Access-Control-Request-Headers": "authorization, content-type",
            },
        )
        assert preflight.status_code == 200
        assert preflight.headers["access-control-allow-origin"] == ORIGIN
        assert "authorization" in preflight.headers["access-control-allow-headers"].lower()


@pytest.mark.parametrize(
    "name",
    ["..", "%2E%2E", "%2e%2e%2F%2e%2e", "..%2F..%2Fetc%2Fpasswd", "a%2F..%2Fb", "..%5C..", "%00"],
)
def test_traversal_names_are_not_found(client: TestClient, name: str) -> None:
    for suffix in ("", "/objects"):
        resp = client.get(f"/v1/maps/{name}{suffix}", headers=auth(WRITE))
        assert resp.status_code == 404, (name, suffix, resp.text)
        assert resp.json()["error"] in {"map_not_found", "not_found"}


@pytest.mark.parametrize(
    ("host", "loopback"),
    [("127.0.0.1", True), ("::1", True), ("localhost", True), ("0.0.0.0", False), ("::", False)],
)
def test_loopback_detection(host: str, loopback: bool) -> None:
    assert is_loopback(host) is loopback


def test_exposure_warning() -> None:
    warning = exposure_warning("0.0.0.0", Config())
    assert warning is not None and "without API keys" in warning
    assert exposure_warning("127.0.0.1", Config()) is None
    assert exposure_warning("0.0.0.0", keyed_config()) is None


def test_serve_takes_host_and_port_from_config(
    map_dir: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls: list[dict[str, Any]] = []
    monkeypatch.setattr(uvicorn, "run", lambda app, **kw: calls.append(kw))
    app = typer.Typer()
    app.command("serve")(serve)
    runner = CliRunner()
    args = ["--map", str(map_dir), "--set", "service.host=0.0.0.0", "--set", "service.port=9123"]
    # an exposed host without keys is refused, and nothing is served
    refused = runner.invoke(app, args)
    assert refused.exit_code != 0 and not calls
    assert "refusing to start" in refused.output and "--insecure" in refused.output
    result = runner.invoke(app, [*args, "--insecure"])
    assert result.exit_code == 0, result.output
    assert calls[-1]["host"] == "0.0.0.0" and calls[-1]["port"] == 9123
    assert "without API keys" in result.output
    keyed = runner.invoke(app, [*args, "--set", f'service.read_keys=["{READ}"]', "--port", "9200"])
    assert keyed.exit_code == 0 and calls[-1]["port"] == 9200
    assert "without API keys" not in keyed.output
