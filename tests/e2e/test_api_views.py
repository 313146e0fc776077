"""The viewer's routes: floor / room / area listings, the hierarchy tree, BEV pictures with
their world ↔ pixel transform, keyframe JPEGs and best views, and the static viewer page.

Listings run on an oracle map imported from a generated house (no keyframes, no room
masks); pictures on a small map built from rendered frames (keyframes, masks, stored BEV).
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from urllib.parse import quote

import cv2
import numpy as np
import pytest
from fastapi.testclient import TestClient

from inherit_sg.api.app import create_app
from inherit_sg.facade import build_map
from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
from inherit_sg.model import RoomMask
from inherit_sg.reads.bev import (
    BACKGROUND,
    OBJECT_DOT,
    PALETTE,
    BevObject,
    BevRoom,
    fit_transform,
    rasterise,
    render_bev,
)
from inherit_sg.reads.scene3d import mask_outlines
from tests.e2e.oracle_maps import oracle_map

ORACLE, BUILT = "oracle", "built"


@pytest.fixture(scope="module")
def maps_root(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("views")
    oracle_map(root, ORACLE, 3)
    write_dataset(generate_house(3, 1, 4), root / "house", width=128, height=96, workers=2)
    build_map(root / "house", root / "maps" / BUILT)
    return root / "maps"


@pytest.fixture(scope="module")
def client(maps_root: Path) -> Iterator[TestClient]:
    with TestClient(create_app(maps_root)) as c:
        yield c


def get_json(client: TestClient, path: str) -> dict:
    resp = client.get(path)
    assert resp.status_code == 200, resp.text
    return resp.json()


def rows(client: TestClient, name: str, query: str) -> list[list]:
    resp = client.post(f"/v1/maps/{name}/cypher", json={"query": query, "max_rows": 10000})
    assert resp.status_code == 200, resp.text
    return resp.json()["rows"]


def decode(content: bytes) -> np.ndarray:
    img = cv2.imdecode(np.frombuffer(content, np.uint8), cv2.IMREAD_COLOR)
    assert img is not None
    return img


# ------------------------------------------------------------------ listings
def test_map_list(client: TestClient) -> None:
    assert get_json(client, "/v1/maps") == {
        "maps": [{"name": BUILT, "status": "ok"}, {"name": ORACLE, "status": "ok"}]
    }


def test_floors_with_counts(client: TestClient) -> None:
    page = get_json(client, f"/v1/maps/{ORACLE}/floors")
    assert page["total"] == 1 and page["limit"] == 100 and page["offset"] == 0
    (floor,) = page["floors"]
    n_rooms = rows(client, ORACLE, "MATCH (r:Room) RETURN count(r)")[0][0]
    n_objects = rows(client, ORACLE, "MATCH (o:Object) RETURN count(o)")[0][0]
    assert floor["id"] == "floor:0" and floor["level"] == 0
    assert floor["rooms"] == n_rooms == 4 and floor["objects"] == n_objects > 0
    by_label = get_json(client, f"/v1/maps/{ORACLE}/floors?label={floor['label'].upper()}")
    assert by_label["total"] == 1
    assert get_json(client, f"/v1/maps/{ORACLE}/floors?label=attic")["floors"] == []


def test_rooms_paging_filters_and_counts(client: TestClient) -> None:
    full = get_json(client, f"/v1/maps/{ORACLE}/rooms?floor=floor:0")
    assert full["total"] == 4 and len(full["rooms"]) == 4
    ids = [r["id"] for r in full["rooms"]]
    assert ids == sorted(ids)
    first = get_json(client, f"/v1/maps/{ORACLE}/rooms?limit=3")
    rest = get_json(client, f"/v1/maps/{ORACLE}/rooms?limit=3&offset=3")
    assert [r["id"] for r in first["rooms"] + rest["rooms"]] == ids and rest["total"] == 4
    assert get_json(client, f"/v1/maps/{ORACLE}/rooms?offset=99")["rooms"] == []
    per_room = dict(rows(client, ORACLE, "MATCH (o:Object) RETURN o.room_id, count(o)"))
    per_room_areas = dict(rows(client, ORACLE, "MATCH (a:Area) RETURN a.room_id, count(a)"))
    for room in full["rooms"]:
        assert room["floor_id"] == "floor:0" and len(room["position"]) == 3
        assert room["objects"] == per_room.get(room["id"], 0)
        assert room["areas"] == per_room_areas.get(room["id"], 0)
    label = full["rooms"][0]["label"]
    same = get_json(client, f"/v1/maps/{ORACLE}/rooms?label={quote(label.title())}")
    assert same["total"] >= 1 and all(r["label"] == label for r in same["rooms"])
    assert get_json(client, f"/v1/maps/{ORACLE}/rooms?floor=floor:9")["total"] == 0


def test_areas_filters(client: TestClient) -> None:
    page = get_json(client, f"/v1/maps/{ORACLE}/areas?limit=1000")
    assert page["total"] == len(page["areas"]) > 0
    per_area = dict(rows(client, ORACLE, "MATCH (o:Object) RETURN o.area_id, count(o)"))
    for area in page["areas"]:
        assert area["floor_id"] == "floor:0" and area["room_id"]
        assert area["objects"] == per_area.get(area["id"], 0)
    room = page["areas"][0]["room_id"]
    in_room = get_json(client, f"/v1/maps/{ORACLE}/areas?room={quote(room)}")
    expected = [a["id"] for a in page["areas"] if a["room_id"] == room]
    assert [a["id"] for a in in_room["areas"]] == expected
    on_floor = get_json(client, f"/v1/maps/{ORACLE}/areas?floor=floor:0&limit=1000")
    assert on_floor["total"] == page["total"]
    assert get_json(client, f"/v1/maps/{ORACLE}/areas?floor=floor:5")["total"] == 0
    label = page["areas"][0]["label"]
    by_label = get_json(client, f"/v1/maps/{ORACLE}/areas?label={quote(label.upper())}")
    assert by_label["total"] >= 1 and {a["label"] for a in by_label["areas"]} == {label}


@pytest.mark.parametrize(
    "query", ["limit=0", "limit=1001", "offset=-1", "limit=abc"], ids=lambda q: q
)
@pytest.mark.parametrize("table", ["floors", "rooms", "areas"])
def test_listing_bad_paging(client: TestClient, table: str, query: str) -> None:
    resp = client.get(f"/v1/maps/{ORACLE}/{table}?{query}")
    assert resp.status_code == 400 and resp.json()["error"] == "bad_input"


@pytest.mark.parametrize("path", ["floors", "rooms", "areas", "hierarchy", "bev.png?floor=floor:0"])
def test_unknown_map(client: TestClient, path: str) -> None:
    resp = client.get(f"/v1/maps/nope/{path}")
    assert resp.status_code == 404 and resp.json()["error"] == "map_not_found"


def test_hierarchy_holds_every_node_once(client: TestClient) -> None:
    tree = get_json(client, f"/v1/maps/{BUILT}/hierarchy")
    seen: dict[str, tuple[str, str | None]] = {}

    def walk(node: dict, parent: str | None) -> None:
        assert node["id"] not in seen
        seen[node["id"]] = (node["layer"], parent)
        for child in node["children"]:
            walk(child, node["id"])

    for floor in tree["floors"]:
        walk(floor, None)
    for node in tree["unassigned"]:
        walk(node, None)
    objects = rows(client, BUILT, "MATCH (o:Object) RETURN o.id, o.area_id")
    areas = rows(client, BUILT, "MATCH (a:Area) RETURN a.id, a.room_id")
    rooms = rows(client, BUILT, "MATCH (r:Room) RETURN r.id, r.floor_id")
    assert len(seen) == len(objects) + len(areas) + len(rooms) + len(tree["floors"])
    for table, layer in ((objects, "object"), (areas, "area"), (rooms, "room")):
        for node_id, parent in table:
            assert seen[node_id] == (layer, parent), node_id
    (floor,) = tree["floors"]
    assert floor["id"] == "floor:0" and {c["layer"] for c in floor["children"]} == {"room"}


# ------------------------------------------------------------------ BEV
def bev_transform(headers: dict) -> tuple[float, float, float, int, int]:
    ox, oy = (float(v) for v in headers["x-bev-origin"].split(","))
    width, height = (int(v) for v in headers["x-bev-size"].split(","))
    return ox, oy, float(headers["x-bev-cell"]), width, height


def test_bev_from_graph_places_objects_exactly(client: TestClient) -> None:
    resp = client.get(f"/v1/maps/{BUILT}/bev.png", params={"floor": "floor:0"})
    assert resp.status_code == 200 and resp.headers["content-type"] == "image/png"
    ox, oy, cell, width, height = bev_transform(dict(resp.headers))
    img = decode(resp.content)
    assert img.shape[:2] == (height, width) and cell > 0
    dots = 0
    objects = rows(client, BUILT, "MATCH (o:Object) RETURN o.id, o.position")
    for _, (x, y, _z) in objects:
        col, row = int((x - ox) / cell), int((oy - y) / cell)
        assert 0 <= col < width and 0 <= row < height
        dots += tuple(img[row, col]) == OBJECT_DOT
    # labels may be drawn over a few dots; the rest sit exactly where the headers say
    assert dots >= 0.8 * len(objects)
    # room fills cover the room centroids
    for _, (x, y, _z) in rows(client, BUILT, "MATCH (r:Room) RETURN r.id, r.position"):
        col, row = int((x - ox) / cell), int((oy - y) / cell)
        assert not np.all(img[row, col] == BACKGROUND[::-1])


def test_bev_of_oracle_map(client: TestClient) -> None:
    resp = client.get(f"/v1/maps/{ORACLE}/bev.png?floor=floor:0")
    assert resp.status_code == 200
    ox, oy, cell, width, height = bev_transform(dict(resp.headers))
    img = decode(resp.content)
    assert img.shape[:2] == (height, width)
    # every room centroid sits on its drawn room (fill, outline or label, not background)
    for _, (x, y, _z) in rows(client, ORACLE, "MATCH (r:Room) RETURN r.id, r.position"):
        col, row = int((x - ox) / cell), int((oy - y) / cell)
        patch = img[row - 10 : row + 11, col - 10 : col + 11]
        assert (patch != np.array(BACKGROUND, np.uint8)).any(axis=2).mean() > 0.9


def test_bev_room_without_mask_is_a_disc() -> None:
    rooms = [BevRoom(id="room:1", label="", position=(2.0, 3.0, 0.0), mask=None)]
    img, tf = render_bev(rooms, [BevObject(id="obj:1", position=(4.0, 3.0, 0.5))])
    col, row = (int(v) for v in tf.to_pixel(2.0, 3.0))
    assert tuple(img[row, col]) == PALETTE[0]
    assert tuple(img[row, col + int(0.5 / tf.cell)]) == PALETTE[0]
    dot_col, dot_row = (int(v) for v in tf.to_pixel(4.0, 3.0))
    assert tuple(img[dot_row, dot_col]) == OBJECT_DOT
    assert tuple(img[0, 0]) == BACKGROUND


def test_bev_stored_and_errors(client: TestClient, maps_root: Path) -> None:
    stored = client.get(f"/v1/maps/{BUILT}/bev.png?floor=floor:0&source=stored")
    assert stored.status_code == 200
    assert stored.content == (maps_root / BUILT / "bev" / "floor_0.png").read_bytes()
    for name, query, status in (
        (BUILT, "floor=floor:7", 404),
        (ORACLE, "floor=floor:0&source=stored", 404),
        (BUILT, "floor=floor:0&source=other", 400),
        (BUILT, "", 400),
        (BUILT, "floor=..%2Fmap.json", 400),
    ):
        resp = client.get(f"/v1/maps/{name}/bev.png?{query}")
        assert resp.status_code == status, query
        assert resp.headers["content-type"] == "application/json" and resp.json()["message"]


def test_rasterise_matches_room_mask() -> None:
    cells = np.zeros((8, 10), bool)
    cells[2:6, 3:9] = True
    cells[0, 0] = True
    mask = RoomMask(origin_x=-1.0, origin_y=2.0, resolution=0.1, cells=cells)
    rooms = [BevRoom(id="room:1", label="", position=None, mask=mask)]
    tf = fit_transform(rooms, [BevObject(id="obj:1", position=(3.0, 1.0, 0.0))], px_per_m=37)
    grid = rasterise(mask, tf)
    for row in range(tf.height):
        for col in range(tf.width):
            x, y = tf.to_world(col + 0.5, row + 0.5)
            assert grid[row, col] == mask.contains_xy(x, y)
    fcol, frow = tf.to_pixel(3.0, 1.0)
    assert tf.to_world(fcol, frow) == pytest.approx((3.0, 1.0))
    img, _ = render_bev(rooms, [], tf)
    assert img.shape == (tf.height, tf.width, 3) and grid.sum() > 0


# ------------------------------------------------------------------ keyframes and views
def test_keyframe_jpeg(client: TestClient) -> None:
    kf_id, width, height = rows(
        client, BUILT, "MATCH (k:Keyframe) RETURN k.id, k.width, k.height ORDER BY k.id LIMIT 1"
    )[0]
    plain = client.get(f"/v1/maps/{BUILT}/keyframes/{kf_id}.jpg")
    encoded = client.get(f"/v1/maps/{BUILT}/keyframes/{quote(kf_id, safe='')}.jpg")
    assert plain.status_code == encoded.status_code == 200
    assert plain.headers["content-type"] == "image/jpeg" and plain.content == encoded.content
    assert decode(plain.content).shape[:2] == (height, width)


@pytest.mark.parametrize(
    ("kf", "status"),
    [
        ("kf:session:9:999", 404),
        ("a%20b", 400),
        ("x..y", 400),
        ("..%2F..%2Fmap.json%00", 404),
        ("%2E%2E", 400),
    ],
)
def test_keyframe_errors(client: TestClient, kf: str, status: int) -> None:
    resp = client.get(f"/v1/maps/{BUILT}/keyframes/{kf}.jpg")
    assert resp.status_code == status and resp.json()["message"]


def test_keyframe_absent_on_oracle_map(client: TestClient) -> None:
    resp = client.get(f"/v1/maps/{ORACLE}/keyframes/kf:session:1:0.jpg")
    assert resp.status_code == 404 and resp.json()["error"] == "node_not_found"


def test_best_views(client: TestClient) -> None:
    obj_id, best = rows(
        client,
        BUILT,
        "MATCH (o:Object) WHERE o.best_keyframe IS NOT NULL "
        "RETURN o.id, o.best_keyframe ORDER BY o.id LIMIT 1",
    )[0]
    resp = client.get(f"/v1/maps/{BUILT}/nodes/{obj_id}/view.jpg")
    assert resp.status_code == 200 and resp.headers["x-keyframe-id"] == best
    direct = client.get(f"/v1/maps/{BUILT}/keyframes/{best}.jpg")
    assert resp.content == direct.content
    room_id, view = rows(
        client, BUILT, "MATCH (r:Room) WHERE r.best_view IS NOT NULL RETURN r.id, r.best_view"
    )[0]
    room = client.get(f"/v1/maps/{BUILT}/nodes/{room_id}/view.jpg")
    assert room.status_code == 200 and room.headers["x-keyframe-id"] == view
    for name, node in ((BUILT, "obj:99999"), (BUILT, "floor:0"), (ORACLE, "obj:1")):
        resp = client.get(f"/v1/maps/{name}/nodes/{node}/view.jpg")
        assert resp.status_code == 404 and resp.json()["error"] == "node_not_found"


# ------------------------------------------------------------------ static viewer
def test_viewer_page_and_routes_not_shadowed(client: TestClient) -> None:
    page = client.get("/")
    assert page.status_code == 200 and page.headers["content-type"].startswith("text/html")
    assert '<script src="/static/viewer.js">' in page.text and 'id="query-input"' in page.text
    assert '<script type="module" src="/static/viewer3d.js">' in page.text
    for asset, kind in (
        ("viewer.js", "javascript"),
        ("viewer.css", "text/css"),
        ("viewer3d.js", "javascript"),
        ("vendor/three/three.module.js", "javascript"),
        ("vendor/three/three.core.js", "javascript"),
        ("vendor/three/addons/controls/OrbitControls.js", "javascript"),
    ):
        resp = client.get(f"/static/{asset}")
        assert resp.status_code == 200 and kind in resp.headers["content-type"]
    assert client.get("/static/nope.js").status_code == 404
    assert client.get("/healthz").json()["status"] == "ok"
    assert client.get("/docs").status_code == 200
    assert "/v1/maps/{map}/bev.png" in client.get("/openapi.json").json()["paths"]
    missing = client.get("/v1/nothing-here")
    assert missing.status_code == 404 and missing.json()["error"] == "not_found"
    wrong_method = client.get(f"/v1/maps/{ORACLE}/query")
    assert wrong_method.status_code == 405


def test_object_detail_lists_its_keyframes(client: TestClient) -> None:
    oid = rows(
        client,
        BUILT,
        "MATCH (o:Object)-[:SEEN_IN]->(k:Keyframe) WHERE o.label <> 'door' "
        "RETURN o.id, count(k) AS n ORDER BY n DESC, o.id LIMIT 1",
    )[0][0]
    detail = get_json(client, f"/v1/maps/{BUILT}/objects/{oid}")
    kfs = detail["keyframes"]
    assert kfs and detail["best_keyframe"] in {k["id"] for k in kfs}
    assert [k["timestamp"] for k in kfs] == sorted(k["timestamp"] for k in kfs)
    assert kfs[0]["session_id"] == "session:1" and kfs[0]["detection"]["label"]
    image = client.get(kfs[0]["image"])
    assert image.status_code == 200 and decode(image.content).shape[2] == 3
    first = rows(client, ORACLE, "MATCH (o:Object) RETURN o.id ORDER BY o.id LIMIT 1")[0][0]
    oracle = get_json(client, f"/v1/maps/{ORACLE}/objects/{first}")
    assert oracle["keyframes"] == [] and oracle["best_keyframe"] is None


def test_mask_outlines_trace_the_footprint_in_world_metres() -> None:
    cells = np.zeros((20, 30), dtype=bool)
    cells[2:12, 5:25] = True  # 2.0 m × 1.0 m at 0.1 m cells
    cells[15:18, 0:3] = True  # a small second piece on the grid's border
    mask = RoomMask(origin_x=1.0, origin_y=-2.0, resolution=0.1, cells=cells)
    big, small = mask_outlines(mask)
    xs, ys = [p[0] for p in big], [p[1] for p in big]
    # the outline runs through the centres of the boundary cells
    assert len(big) == 4
    assert (min(xs), max(xs)) == pytest.approx((1.55, 3.45))
    assert (min(ys), max(ys)) == pytest.approx((-1.75, -0.85))
    assert min(p[0] for p in small) == pytest.approx(1.05)
    assert mask_outlines(RoomMask(0.0, 0.0, 0.1, np.zeros((4, 4), dtype=bool))) == []


def test_scene3d_matches_the_graph(client: TestClient) -> None:
    scene = get_json(client, f"/v1/maps/{BUILT}/scene3d")
    objects = rows(client, BUILT, "MATCH (o:Object) RETURN o.id, o.room_id, o.bbox_min")
    assert {o["id"] for o in scene["objects"]} == {r[0] for r in objects}
    by_id = {o["id"]: o for o in scene["objects"]}
    for oid, room_id, lo in objects:
        assert by_id[oid]["room_id"] == room_id
        assert by_id[oid]["bbox_min"] == pytest.approx(lo)
    rooms = rows(client, BUILT, "MATCH (r:Room) RETURN r.id")
    assert sorted(r["id"] for r in scene["rooms"]) == sorted(r[0] for r in rooms)
    assert all(r["outlines"] and len(r["outlines"][0]) >= 3 for r in scene["rooms"])
    # each room's own position lies inside (or on) its largest outline
    for room in scene["rooms"]:
        contour = np.array(room["outlines"][0], dtype=np.float32)
        x, y = room["position"][:2]
        assert cv2.pointPolygonTest(contour, (x, y), True) > -0.3, room["id"]
    predicates = {r["predicate"] for r in scene["relations"]}
    assert predicates and "near" not in predicates
    edges = rows(
        client,
        BUILT,
        "MATCH (:Object)-[e:RELATION]->(:Object) WHERE e.predicate <> 'near' RETURN count(*)",
    )
    assert len(scene["relations"]) == edges[0][0]
    near = get_json(client, f"/v1/maps/{BUILT}/scene3d?near=true")
    assert "near" in {r["predicate"] for r in near["relations"]}
    assert {(c["source"], c["target"]) for c in scene["connections"]} == {
        (a, b)
        for a, b in rows(client, BUILT, "MATCH (a:Room)-[:CONNECTS]->(b:Room) RETURN a.id, b.id")
    }
    one = get_json(client, f"/v1/maps/{BUILT}/scene3d?floor=floor:0")
    assert [f["id"] for f in one["floors"]] == ["floor:0"]
    assert client.get(f"/v1/maps/{BUILT}/scene3d?floor=floor:9").status_code == 404
    assert client.get(f"/v1/maps/{BUILT}/scene3d?floor=bad%20id").status_code == 400
    # a room has outlines exactly when it has a mask
    oracle = get_json(client, f"/v1/maps/{ORACLE}/scene3d")
    masked = {
        r[0] for r in rows(client, ORACLE, "MATCH (r:Room) WHERE r.mask IS NOT NULL RETURN r.id")
    }
    assert oracle["objects"] and {r["id"] for r in oracle["rooms"] if r["outlines"]} == masked
