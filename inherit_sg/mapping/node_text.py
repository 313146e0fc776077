"""The text each node is embedded and searched by, and batch embedding of nodes.

Objects: label plus description ("chair. a red chair, about 0.5 × 0.5 × 0.9 m ...");
areas and rooms: label plus summary. Floors carry no text embedding.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from inherit_sg.mapping.semantic import LabelEmbedder
from inherit_sg.model import AreaNode, Node, ObjectNode, RoomNode, SceneGraph


def node_text(node: Node) -> str | None:
    """Text that represents ``node`` for embedding and full-text search."""
    if isinstance(node, ObjectNode):
        return f"{node.label}. {node.description}".strip()
    if isinstance(node, AreaNode | RoomNode):
        return f"{node.label}. {node.summary}".strip()
    return None


def embed_nodes(
    graph: SceneGraph, embedder: LabelEmbedder, ids: Iterable[str] | None = None
) -> int:
    """(Re)compute text embeddings of the given nodes (default: all); returns how many."""
    nodes: Sequence[Node] = [graph.get(i) for i in ids] if ids is not None else list(graph.nodes())
    todo = [(n, t) for n in nodes if (t := node_text(n)) is not None]
    if not todo:
        return 0
    vectors = embedder.embed([t for _, t in todo])
    for (node, _), vec in zip(todo, vectors, strict=True):
        node.text_embedding = vec  # type: ignore[union-attr]
        graph.touch(node.id)
    return len(todo)
