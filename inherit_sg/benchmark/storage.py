"""Storage per node type (paper Table III): bytes of visual features, text (embeddings
and strings) and images (keyframe JPEGs) per object node and per room / area node, and
the whole map on disk with and without images.

Feature and embedding bytes are rows × vector size × 4 (float32) from the map's own
vector tables; strings are the UTF-8 bytes of the node's text fields; images are the
JPEG bytes stored in LanceDB. On-disk sizes are ``du``-style sums of the map folder.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from inherit_sg.store import MapStore
from inherit_sg.store.mapdir import GRAPH_FILE, INDEX_FILE, LANCE_DIR, dir_bytes
from inherit_sg.store.stats import kuzu_bytes

FLOAT_BYTES = 4
# text fields per node table (UTF-8 bytes are counted)
TEXT_FIELDS = {
    "Object": ("label", "description", "attributes"),
    "Room": ("label", "summary"),
    "Area": ("label", "summary"),
}
# vector tables holding each node table's embeddings: (table, kind)
VECTOR_TABLES = {
    "Object": (("ObjectVisual", "visual"), ("ObjectText", "text")),
    "Room": (("RoomText", "text"),),
    "Area": (("AreaText", "text"),),
}


def _rows(store: MapStore, query: str) -> list[list[Any]]:
    return store.cypher(query, read_only=True, max_rows=None).rows


def string_bytes(store: MapStore, table: str) -> tuple[int, int]:
    """(nodes, UTF-8 bytes of their text fields) of one node table."""
    fields = TEXT_FIELDS[table]
    cols = ", ".join(f"n.{f}" for f in fields)
    rows = _rows(store, f"MATCH (n:{table}) RETURN {cols}")
    total = sum(len(str(v).encode("utf-8")) for row in rows for v in row if v is not None)
    return len(rows), total


def vector_bytes(store: MapStore, table: str) -> int:
    """Bytes of the float32 vectors in one embedding table."""
    dims = {
        "ObjectVisual": store.info.visual_dim,
        "ObjectText": store.info.text_dim,
        "RoomText": store.info.text_dim,
        "AreaText": store.info.text_dim,
    }
    rows = _rows(store, f"MATCH (v:{table}) RETURN count(v)")
    return int(rows[0][0]) * dims[table] * FLOAT_BYTES


def keyframe_jpegs(map_dir: Path) -> dict[str, int]:
    """JPEG bytes per keyframe id as stored in LanceDB (empty when there are none)."""
    lance = map_dir / LANCE_DIR
    if not lance.is_dir() or not any(lance.iterdir()):
        return {}
    import lancedb

    try:
        stored = lancedb.connect(str(lance)).open_table("keyframes")
    except ValueError:  # no keyframe table yet
        return {}
    table = stored.to_arrow().select(["id", "jpeg"])
    return {
        str(i): len(j) if j is not None else 0
        for i, j in zip(table["id"].to_pylist(), table["jpeg"].to_pylist(), strict=True)
    }


def _per_node(store: MapStore, table: str) -> dict[str, Any]:
    nodes, strings = string_bytes(store, table)
    vectors = {kind: vector_bytes(store, vt) for vt, kind in VECTOR_TABLES[table]}
    per = (lambda b: b / nodes) if nodes else (lambda b: 0.0)
    feat = per(vectors.get("visual", 0))
    text = per(vectors.get("text", 0) + strings)
    return {
        "nodes": nodes,
        "feature_bytes": feat,
        "text_bytes": text,
        "text_string_bytes": per(strings),
        "node_bytes": feat + text,
    }


def storage_breakdown(store: MapStore) -> dict[str, Any]:
    """Per-node-type averages and whole-map sizes of an open map."""
    path = Path(store.path)
    jpegs = keyframe_jpegs(path)
    image_total = sum(jpegs.values())
    out: dict[str, Any] = {t.lower(): _per_node(store, t) for t in TEXT_FIELDS}
    obj = out["object"]
    best = [
        jpegs.get(str(r[0]), 0)
        for r in _rows(store, "MATCH (o:Object) RETURN o.best_keyframe")
        if r[0] is not None
    ]
    obj["image_bytes"] = image_total / obj["nodes"] if obj["nodes"] else 0.0
    obj["best_view_image_bytes"] = sum(best) / len(best) if best else 0.0
    obj["total_bytes"] = obj["node_bytes"] + obj["image_bytes"]
    rooms = _rows(store, "MATCH (r:Room) RETURN r.best_view")
    room_views = [jpegs.get(str(r[0]), 0) for r in rooms if r[0] is not None]
    out["room"]["image_bytes"] = sum(room_views) / len(rooms) if rooms else 0.0
    out["area"]["image_bytes"] = 0.0
    lance_bytes = dir_bytes(path / LANCE_DIR)
    total = dir_bytes(path)
    out["map"] = {
        "keyframes": len(jpegs),
        "jpeg_bytes": image_total,
        "graph_bytes": kuzu_bytes(path / GRAPH_FILE),
        "index_bytes": kuzu_bytes(path / INDEX_FILE),
        "lance_bytes": lance_bytes,
        "total_bytes": total,
        "without_images_bytes": total - lance_bytes,
    }
    return out
