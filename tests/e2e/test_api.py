"""The REST service end to end on a real map imported from a generated house: every route,
the error mapping, paging and a server-side conversation follow-up."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import typer
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from inherit_sg.api.app import create_app
from inherit_sg.cli.serve_cmd import serve
from inherit_sg.errors import MapNotFoundError
from tests.e2e.oracle_maps import oracle_map

NAME = "house3"


@pytest.fixture(scope="module")
def map_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return oracle_map(tmp_path_factory.mktemp("api"), NAME, 3)


@pytest.fixture(scope="module")
def client(map_dir: Path) -> Iterator[TestClient]:
    with TestClient(create_app(map_dir)) as c:
        yield c


def cypher(client: TestClient, query: str, **extra: object) -> dict:
    resp = client.post(f"/v1/maps/{NAME}/cypher", json={"query": query, **extra})
    assert resp.status_code == 200, resp.text
    return resp.json()


def test_health_and_ready(client: TestClient) -> None:
    assert client.get("/healthz").json() == {"status": "ok", "maps": {}}
    ready = client.get("/readyz")
    assert ready.status_code == 200 and ready.json()["maps"] == {NAME: "ok"}


def test_stats(client: TestClient, map_dir: Path) -> None:
    stats = client.get(f"/v1/maps/{NAME}").json()
    assert stats["path"] == str(map_dir)
    assert stats["nodes"]["Floor"] == 1 and stats["nodes"]["Room"] == 4
    assert stats["nodes"]["Object"] > 0 and stats["bytes"]["total"] > 0


@pytest.mark.parametrize("name", ["nope", "..", "a%2F..%2Fb", "bad name!"])
def test_unknown_or_bad_map_name(client: TestClient, name: str) -> None:
    resp = client.get(f"/v1/maps/{name}")
    assert resp.status_code == 404
    assert resp.json()["error"] in {"map_not_found", "not_found"} and resp.json()["message"]


def test_cypher_and_limits(client: TestClient) -> None:
    data = cypher(client, "MATCH (o:Object) RETURN o.id ORDER BY o.id", max_rows=2)
    assert data["columns"] == ["o.id"] and len(data["rows"]) == 2 and data["truncated"]
    data = cypher(client, "MATCH (f:Floor) WHERE f.level = $lvl RETURN f.id", params={"lvl": 0})
    assert data["rows"] and not data["truncated"]
    too_many = client.post(f"/v1/maps/{NAME}/cypher", json={"query": "RETURN 1", "max_rows": 10001})
    assert too_many.status_code == 400 and too_many.json()["error"] == "bad_input"


def test_cypher_write_refused(client: TestClient) -> None:
    resp = client.post(
        f"/v1/maps/{NAME}/cypher", json={"query": "MATCH (o:Object) SET o.label = 'x'"}
    )
    assert resp.status_code == 403 and resp.json()["error"] == "read_only"
    syntax = client.post(f"/v1/maps/{NAME}/cypher", json={"query": "MATCH (o:Nope) RETURN o"})
    assert syntax.status_code == 400 and syntax.json()["error"] == "cypher_error"


def test_objects_paging_and_filters(client: TestClient) -> None:
    ids = [r[0] for r in cypher(client, "MATCH (o:Object) RETURN o.id ORDER BY o.id")["rows"]]
    first = client.get(f"/v1/maps/{NAME}/objects", params={"limit": 3}).json()
    second = client.get(f"/v1/maps/{NAME}/objects", params={"limit": 3, "offset": 3}).json()
    assert first["total"] == len(ids)
    assert [o["id"] for o in first["objects"] + second["objects"]] == ids[:6]
    one = first["objects"][0]
    by_room = client.get(f"/v1/maps/{NAME}/objects", params={"room": one["room_id"]}).json()
    assert by_room["total"] >= 1
    assert all(o["room_id"] == one["room_id"] for o in by_room["objects"])
    by_label = client.get(
        f"/v1/maps/{NAME}/objects", params={"label": one["label"].upper(), "limit": 1000}
    ).json()
    assert one["id"] in [o["id"] for o in by_label["objects"]]
    none = client.get(f"/v1/maps/{NAME}/objects", params={"floor": "floor:99"}).json()
    assert none["total"] == 0 and none["objects"] == []
    assert client.get(f"/v1/maps/{NAME}/objects", params={"limit": 0}).status_code == 400


def test_object_detail(client: TestClient) -> None:
    rel = cypher(
        client, "MATCH (a:Object)-[e:RELATION]->(b:Object) RETURN a.id, e.predicate, b.id LIMIT 1"
    )["rows"]
    oid = rel[0][0] if rel else cypher(client, "MATCH (o:Object) RETURN o.id LIMIT 1")["rows"][0][0]
    detail = client.get(f"/v1/maps/{NAME}/objects/{oid}").json()
    assert detail["id"] == oid
    assert [h["layer"] for h in detail["hierarchy"]][-2:] == ["room", "floor"]
    assert detail["hierarchy"][-1]["id"] == detail["floor_id"]
    if rel:
        out = [
            (r["predicate"], r["other_id"]) for r in detail["relations"] if r["direction"] == "out"
        ]
        assert (rel[0][1], rel[0][2]) in out
    missing = client.get(f"/v1/maps/{NAME}/objects/obj:does-not-exist")
    assert missing.status_code == 404 and missing.json()["error"] == "node_not_found"


def test_query_and_errors(client: TestClient) -> None:
    label = cypher(client, "MATCH (o:Object) RETURN o.label ORDER BY o.id LIMIT 1")["rows"][0][0]
    resp = client.post(f"/v1/maps/{NAME}/query", json={"text": f"the {label}", "top_k": 2})
    assert resp.status_code == 200, resp.text
    data = resp.json()
    assert data["answer"]["label"] == label and len(data["candidates"]) <= 2
    assert set(data["timings_ms"]) == {"parse", "retrieve", "verify", "total"}
    empty = client.post(f"/v1/maps/{NAME}/query", json={"text": "   "})
    assert empty.status_code == 400 and empty.json()["error"] == "bad_query"
    missing = client.post(f"/v1/maps/{NAME}/query", json={})
    assert missing.status_code == 400
    assert client.post("/v1/maps/nope/query", json={"text": "a chair"}).status_code == 404


def test_query_with_the_robots_pose(client: TestClient) -> None:
    label = cypher(client, "MATCH (o:Object) RETURN o.label ORDER BY o.id LIMIT 1")["rows"][0][0]
    url = f"/v1/maps/{NAME}/query"
    viewer = {"position": [1.0, 2.0, 0.0], "yaw_deg": 90}
    resp = client.post(url, json={"text": f"the {label}", "viewer": viewer})
    assert resp.status_code == 200, resp.text
    assert "robot pose given: (1.00, 2.00, 0.00), heading 90°" in resp.json()["trace"]
    assert client.post(url, json={"text": f"the {label}", "viewer": None}).status_code == 200


@pytest.mark.parametrize(
    ("viewer", "field"),
    [
        ({"position": [1.0, 2.0, 0.0], "yaw_deg": "x"}, "viewer.yaw_deg"),
        ({"position": [1.0, 2.0], "yaw_deg": 0}, "viewer.position"),
        ({"position": [1.0, 2.0, 3.0, 4.0], "yaw_deg": 0}, "viewer.position"),
        ({"position": [1.0, "a", 0.0], "yaw_deg": 0}, "viewer.position.1"),
        ({"position": [1.0, 2.0, 1e9], "yaw_deg": 0}, "viewer.position.2"),
        ({"position": [1.0, 2.0, 0.0]}, "viewer.yaw_deg"),
        ({"position": [1.0, 2.0, 0.0], "yaw_deg": 0, "pitch": 3}, "viewer.pitch"),
        ("1,2,0,90", "viewer"),
    ],
)
def test_query_viewer_is_validated(client: TestClient, viewer: object, field: str) -> None:
    resp = client.post(f"/v1/maps/{NAME}/query", json={"text": "a chair", "viewer": viewer})
    assert resp.status_code == 400, resp.text
    body = resp.json()
    assert body["error"] == "bad_input" and f"body.{field}" in body["message"]


def test_query_viewer_is_documented(client: TestClient) -> None:
    schemas = client.get("/openapi.json").json()["components"]["schemas"]
    viewer = schemas["QueryRequest"]["properties"]["viewer"]
    assert "robot's pose" in viewer["description"]
    assert schemas["ViewerIn"]["properties"]["position"]["minItems"] == 3


def test_conversation_follow_up(client: TestClient) -> None:
    rows = cypher(
        client,
        "MATCH (o:Object) WITH o.label AS l, count(*) AS n WHERE n >= 2 RETURN l ORDER BY l LIMIT 1",
    )["rows"]
    assert rows, "the generated house has a label seen twice"
    label = rows[0][0]
    url = f"/v1/maps/{NAME}/query"
    first = client.post(url, json={"text": f"the {label}", "conversation_id": "c1"}).json()
    other = client.post(url, json={"text": "the other one", "conversation_id": "c1"}).json()
    assert first["answer"]["label"] == label and other["answer"]["label"] == label
    assert other["answer"]["id"] != first["answer"]["id"]
    assert other["conversation_id"] == "c1"
    again = client.post(url, json={"text": "the other one", "conversation_id": "c1"}).json()
    assert again["answer"] is None or again["answer"]["id"] != other["answer"]["id"]


def test_several_maps_and_not_ready(map_dir: Path, tmp_path: Path) -> None:
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "map.json").write_text("{not json")
    app = create_app({"a": map_dir, "b": broken})
    with TestClient(app) as c:
        ready = c.get("/readyz")
        assert ready.status_code == 503 and ready.json()["maps"]["a"] == "ok"
        assert ready.json()["maps"]["b"] != "ok"
        assert c.get("/v1/maps/a").json()["nodes"]["Room"] == 4
        assert c.get("/v1/maps/b").status_code >= 400
        assert c.get(f"/v1/maps/{NAME}").status_code == 404


def test_root_folder_and_bad_root(map_dir: Path, tmp_path: Path) -> None:
    with TestClient(create_app(map_dir.parent)) as c:
        assert c.get(f"/v1/maps/{NAME}").status_code == 200
    with pytest.raises(MapNotFoundError):
        create_app(tmp_path / "absent")


def test_serve_command_help() -> None:
    app = typer.Typer()
    app.command("serve")(serve)
    out = CliRunner().invoke(app, ["--help"]).output
    assert "--map" in out and "--host" in out and "8765" in out
    missing = CliRunner().invoke(app, ["--map", "/nonexistent/map"])
    assert missing.exit_code == 2 and "not found" in missing.output


def test_unexpected_error_answers_json_500(map_dir: Path) -> None:
    app = create_app(map_dir)

    @app.get("/boom")
    def boom() -> None:
        raise RuntimeError("a bug")

    with TestClient(app, raise_server_exceptions=False) as c:
        resp = c.get("/boom")
    assert resp.status_code == 500
    assert resp.json() == {
        "error": "internal_error",
        "message": "GET /boom: RuntimeError (see server log)",
    }


SLOW_CYPHER = (
    "UNWIND range(1, 3000) AS a UNWIND range(1, 3000) AS b UNWIND range(1, 3000) AS x "
    "WITH a, b, x WHERE (a * b + x) % 7 = 3 RETURN count(*)"
)


def test_cypher_time_limit_answers_408_and_the_map_keeps_working(client: TestClient) -> None:
    resp = client.post(f"/v1/maps/{NAME}/cypher", json={"query": SLOW_CYPHER, "timeout_s": 0.2})
    assert resp.status_code == 408
    assert resp.json()["error"] == "query_timeout" and "0.2 s" in resp.json()["message"]
    assert cypher(client, "MATCH (f:Floor) RETURN count(f)")["rows"] == [[1]]


# Kuzu 0.11.3 may end its process with a segmentation fault on this read-only statement (a
# computed SKIP gets past the text guard); it runs in the map's Cypher worker.
CRASHING_CYPHER = "MATCH (o:Object) RETURN o.id ORDER BY o.id SKIP (20000) LIMIT 5"


def _worker_pid(client: TestClient) -> int:
    registry = client.app.state.registry  # type: ignore[attr-defined]
    service = registry.get(NAME).require()
    worker = service._cypher_worker
    assert worker is not None and worker.pid is not None
    return int(worker.pid)


def test_a_statement_that_crashes_the_engine_leaves_the_service_up(client: TestClient) -> None:
    import os
    import signal
    import threading
    import time

    # the real statement crashes Kuzu on some runs and not on others: either way, no harm
    resp = client.post(f"/v1/maps/{NAME}/cypher", json={"query": CRASHING_CYPHER})
    assert resp.status_code in (200, 400), resp.text
    if resp.status_code == 400:
        assert resp.json()["error"] == "cypher_crashed"
    # a crash made certain: the engine dies of SIGSEGV in the middle of a statement
    assert cypher(client, "MATCH (f:Floor) RETURN count(f)")["rows"] == [[1]]
    pid = _worker_pid(client)
    answers: list[Any] = []
    slow = threading.Thread(
        target=lambda: answers.append(
            client.post(f"/v1/maps/{NAME}/cypher", json={"query": SLOW_CYPHER, "timeout_s": 60})
        )
    )
    slow.start()
    time.sleep(0.5)
    os.kill(pid, signal.SIGSEGV)
    slow.join(timeout=30)
    (crashed,) = answers
    assert crashed.status_code == 400, crashed.text
    assert crashed.json()["error"] == "cypher_crashed" and "SIGSEGV" in crashed.json()["message"]
    # the service answers the next statement and the next request
    assert cypher(client, "MATCH (f:Floor) RETURN count(f)")["rows"] == [[1]]
    assert _worker_pid(client) != pid
    found = client.post(f"/v1/maps/{NAME}/query", json={"text": "the bed"})
    assert found.status_code == 200 and found.json()["answer"] is not None
    assert client.get("/readyz").json()["maps"] == {NAME: "ok"}
