"""The package's layers (docs/architecture.md, "Module map"): walking every import of every
module (lazy ones inside functions included, typing-only ones left out), no module imports
a higher layer and the subpackages import each other without a cycle."""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "inherit_sg"

# Subpackage (or top-level module) → layer, lowest first.
LAYERS = {
    "errors": 0, "wording": 0, "json_values": 0,
    "model": 1, "config": 1, "nlp": 1, "schema": 1,
    "vocab": 2, "embed": 2, "llm": 2, "store": 2, "ingest": 2,
    "geometry": 3, "perception": 3,
    "mapping": 4,
    "retrieval": 5, "exchange": 5,
    "reads": 6, "facade": 6,
    "demo": 7, "benchmark": 7, "api": 7, "cli": 7, "viz": 7, "scale": 7,
    "mcp_server": 7,
}  # fmt: skip


def _group(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if parts[0] == "inherit_sg" and len(parts) > 1 else None


def _typing_only(tree: ast.Module) -> set[int]:
    """ids of the import nodes under ``if TYPE_CHECKING:``."""
    out: set[int] = set()
    for node in ast.walk(tree):
        test = node.test if isinstance(node, ast.If) else None
        if isinstance(test, ast.Name) and test.id == "TYPE_CHECKING":
            out |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return out


def import_edges() -> dict[str, set[tuple[str, str]]]:
    """Group → {(imported group, importing file)} for every run-time import."""
    edges: dict[str, set[tuple[str, str]]] = defaultdict(set)
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        source = _group(".".join(rel.parts))
        if source is None or source == "__init__":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skip = _typing_only(tree)
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            names: list[str] = []
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names = [node.module, *(f"{node.module}.{a.name}" for a in node.names)]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            for name in names:
                target = _group(name)
                if target is not None and target != source and target != "__version__":
                    edges[source].add((target, str(rel)))
    return edges


def test_every_subpackage_has_a_layer() -> None:
    groups = {p.stem if p.is_file() else p.name for p in PACKAGE.iterdir()}
    groups = {g for g in groups if not g.startswith("__") and g not in ("py",)}
    assert groups - {"static"} <= set(LAYERS), sorted(groups - set(LAYERS))


def test_no_module_imports_a_higher_layer() -> None:
    upward = [
        f"{where}: {source} (layer {LAYERS[source]}) imports {target} (layer {LAYERS[target]})"
        for source, targets in import_edges().items()
        for target, where in targets
        if LAYERS[target] > LAYERS[source]
    ]
    assert not upward, "\n".join(sorted(upward))


def test_the_subpackages_import_each_other_without_a_cycle() -> None:
    graph = {s: {t for t, _ in targets} for s, targets in import_edges().items()}
    state: dict[str, int] = {}

    def visit(node: str, path: list[str]) -> None:
        state[node] = 1
        for nxt in sorted(graph.get(node, ())):
            assert state.get(nxt) != 1, f"import cycle: {' -> '.join([*path, node, nxt])}"
            if nxt not in state:
                visit(nxt, [*path, node])
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node, [])
