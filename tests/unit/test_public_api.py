"""The package's curated public API: every name in ``__all__`` resolves, lazily."""

from __future__ import annotations

import subprocess
import sys

import pytest

import inherit_sg


def test_every_public_name_resolves() -> None:
    for name in inherit_sg.__all__:
        assert getattr(inherit_sg, name) is not None, name
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        inherit_sg.nope  # noqa: B018


def test_importing_the_package_loads_nothing_heavy() -> None:
    code = (
        "import sys, inherit_sg; "
        "print(sorted(m for m in ('torch', 'lancedb', 'kuzu', 'inherit_sg.facade') "
        "if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
