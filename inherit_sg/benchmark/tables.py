"""Markdown table helpers and number formatting for the benchmark report."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any


def num(value: Any, digits: int = 1) -> str:
    """A number with ``digits`` decimals; "n/a" for missing or non-finite values and
    strings passed through."""
    if isinstance(value, str):
        return value
    if value is None or not isinstance(value, int | float) or not math.isfinite(value):
        return "n/a"
    return f"{value:.{digits}f}"


def pct(value: Any) -> str:
    """A percentage already in 0–100 with one decimal."""
    return num(value, 1)


def ratio_pct(value: Any) -> str:
    """A 0–1 ratio as a percentage with one decimal."""
    if isinstance(value, int | float) and math.isfinite(value):
        return f"{100.0 * value:.1f}"
    return "n/a"


def size(n_bytes: Any) -> str:
    """Bytes in B / KB / MB / GB (powers of 1024), like the paper's Table III."""
    if not isinstance(n_bytes, int | float) or not math.isfinite(n_bytes):
        return "n/a"
    value = float(n_bytes)
    for unit in ("B", "KB", "MB"):
        if abs(value) < 1024.0:
            return f"{value:.1f} {unit}" if unit != "B" else f"{value:.0f} B"
        value /= 1024.0
    return f"{value:.2f} GB"


def table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    """A GitHub-flavoured markdown table."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)
