"""Map statistics: rows per table, sessions and bytes on disk."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import kuzu

from inherit_sg.model import EdgeKind
from inherit_sg.store.graph_read import count
from inherit_sg.store.indexes import VECTOR_INDEXES
from inherit_sg.store.mapdir import GRAPH_FILE, INDEX_FILE, LANCE_DIR, dir_bytes

NODE_TABLES = ("Floor", "Room", "Area", "Object", "Keyframe", "Session")


@dataclass
class MapStats:
    """Counts and sizes of one map."""

    nodes: dict[str, int] = field(default_factory=dict)
    edges: dict[str, int] = field(default_factory=dict)
    vectors: dict[str, int] = field(default_factory=dict)
    sessions: int = 0
    bytes_graph: int = 0  # graph.kuzu (+ wal): the scene graph and its vectors
    bytes_index: int = 0  # index.kuzu (+ wal): HNSW and full-text indexes, derived
    bytes_lance: int = 0  # lance/: keyframe images and features
    bytes_total: int = 0

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return asdict(self)


def kuzu_bytes(file: Path) -> int:
    """Size of a Kuzu database file and its WAL."""
    return dir_bytes(file) + dir_bytes(file.with_name(file.name + ".wal"))


def graph_bytes(map_path: Path) -> int:
    """Size of ``graph.kuzu`` and ``index.kuzu`` with their WALs (everything but
    keyframes)."""
    return kuzu_bytes(map_path / GRAPH_FILE) + kuzu_bytes(map_path / INDEX_FILE)


def compute_stats(conn: kuzu.Connection, map_path: Path) -> MapStats:
    """Counts from the graph (``conn`` should be in a read transaction for a consistent
    snapshot) and sizes from the directory."""
    stats = MapStats(
        nodes={t: count(conn, t) for t in NODE_TABLES},
        edges={k.value: count(conn, k.value, rel=True) for k in EdgeKind},
        vectors={name: count(conn, spec.table) for name, spec in VECTOR_INDEXES.items()},
    )
    stats.sessions = stats.nodes["Session"]
    stats.bytes_graph = kuzu_bytes(map_path / GRAPH_FILE)
    stats.bytes_index = kuzu_bytes(map_path / INDEX_FILE)
    stats.bytes_lance = dir_bytes(map_path / LANCE_DIR)
    stats.bytes_total = dir_bytes(map_path)
    return stats
