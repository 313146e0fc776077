"""SceneGraph.restore_changes: a failed flush goes back into the change log."""

from __future__ import annotations

from inherit_sg.model import EdgeKind
from tests.integration.store_data import sample_graph


def test_restore_merges_with_newer_changes() -> None:
    graph = sample_graph(n_objects=3)
    graph.flush_changes()
    graph.remove("obj:2")
    graph.get("obj:1").label = "stool"
    graph.touch("obj:1")
    graph.remove_edge(EdgeKind.RELATION, "obj:0", "obj:1", "near")
    failed = graph.flush_changes()
    graph.get("obj:0").label = "bench"  # changed after the failed flush
    graph.touch("obj:0")
    graph.restore_changes(failed)
    log = graph.changes
    assert log.removed_nodes == {"obj:2"}
    assert log.updated_nodes == {"obj:0", "obj:1"}
    assert ("RELATION", "obj:0", "obj:1", "near") in log.removed_edges
    assert ("HAS_OBJECT", "area:0", "obj:2", "") in log.removed_edges


def test_restore_of_new_nodes_keeps_them_new() -> None:
    graph = sample_graph(n_objects=2)
    failed = graph.flush_changes()
    graph.restore_changes(failed)
    assert graph.changes.new_nodes == failed.new_nodes
    assert graph.changes.new_edges == failed.new_edges
    assert not graph.changes.updated_nodes and not graph.changes.removed_nodes
