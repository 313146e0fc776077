"""The REST room listing shows each room's inferred types with their probabilities."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from inherit_sg.api.app import create_app
from inherit_sg.config import Config
from inherit_sg.store import MapStore
from tests.integration.test_room_types_store import TV_LIVING, room_graph

NAME = "rooms"


@pytest.fixture(scope="module")
def client(tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    path = tmp_path_factory.mktemp("room_types") / "map"
    with MapStore.create(path) as store:
        store.write_changes(room_graph())
    with TestClient(create_app({NAME: Path(path)}, Config())) as c:
        yield c


def test_rooms_list_their_alternatives(client: TestClient) -> None:
    resp = client.get(f"/v1/maps/{NAME}/rooms")
    assert resp.status_code == 200, resp.text
    rooms = {r["id"]: r for r in resp.json()["rooms"]}
    assert rooms["room:0"]["label"] == "living room"
    assert rooms["room:0"]["types"] == [{"type": t, "p": p} for t, p in TV_LIVING]
    assert rooms["room:1"]["types"] == []  # none inferred (an oracle or imported room)
    by_label = client.get(f"/v1/maps/{NAME}/rooms", params={"label": "Living Room"}).json()
    assert [r["id"] for r in by_label["rooms"]] == ["room:0"]


def test_the_types_are_documented(client: TestClient) -> None:
    doc = client.get("/openapi.json").json()
    item = doc["components"]["schemas"]["RoomItem"]["properties"]["types"]
    assert "probabilit" in item["description"]
    assert set(doc["components"]["schemas"]["RoomTypeItem"]["properties"]) == {"type", "p"}
