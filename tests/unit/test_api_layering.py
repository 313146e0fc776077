"""The REST and MCP layers only translate requests to MapService calls: no Cypher of their
own (the one Cypher route or tool forwards the user's statement) and no store access."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

API = Path(__file__).resolve().parents[2] / "inherit_sg" / "api"
MCP = API.parent / "mcp_server"
CYPHER = re.compile(r"\b(MATCH|MERGE|CREATE)\b.*\b(RETURN|SET|DELETE)\b|\bMATCH\s*\(", re.S)


def _docstrings(tree: ast.AST) -> set[int]:
    """ids of the docstring nodes of a module, its classes and functions."""
    out: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                out.add(id(body[0].value))
    return out


@pytest.mark.parametrize("face", [API, MCP], ids=["api", "mcp_server"])
def test_api_writes_no_cypher_and_never_touches_the_store(face: Path) -> None:
    files = sorted(face.glob("*.py"))
    assert len(files) > 5, face
    for path in files:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        docs = _docstrings(tree)
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Constant)
                and isinstance(node.value, str)
                and id(node) not in docs
            ):
                assert not CYPHER.search(node.value), f"{path.name} writes Cypher: {node.value!r}"
            if isinstance(node, ast.Attribute):
                assert node.attr != "store", f"{path.name}:{node.lineno} reaches into the store"


def test_the_check_would_see_cypher_and_store_access() -> None:
    tree = ast.parse('q = "MATCH (o:Object) RETURN o.id"\nx = service.store.path\n')
    strings = [n.value for n in ast.walk(tree) if isinstance(n, ast.Constant)]
    assert any(CYPHER.search(s) for s in strings if isinstance(s, str))
    assert any(isinstance(n, ast.Attribute) and n.attr == "store" for n in ast.walk(tree))
