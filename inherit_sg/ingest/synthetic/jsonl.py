"""JSON-lines files of the ground truth (queries, conversations): one writer and one
reader, accepting either a file path or the dataset folder holding the default file."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any, TypeVar

from inherit_sg.errors import DatasetError

T = TypeVar("T")


def _resolve(path: str | Path, default_name: str) -> Path:
    p = Path(path)
    return p / default_name if p.is_dir() else p


def write_jsonl(path: str | Path, default_name: str, records: Iterable[dict[str, Any]]) -> Path:
    """Write one JSON object per line; returns the file written."""
    out = _resolve(path, default_name)
    lines = [json.dumps(r, ensure_ascii=False) for r in records]
    out.write_text("\n".join(lines) + ("\n" if lines else ""), encoding="utf-8")
    return out


def read_jsonl(
    path: str | Path, default_name: str, parse: Callable[[dict[str, Any]], T], what: str
) -> list[T]:
    """Parse every non-blank line; DatasetError names the file and line that is wrong."""
    src = _resolve(path, default_name)
    try:
        text = src.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise DatasetError(f"no {what} file: {src} not found") from None
    out = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        try:
            out.append(parse(json.loads(line)))
        except (json.JSONDecodeError, KeyError, TypeError, ValueError) as exc:
            raise DatasetError(f"{src}:{number}: malformed {what}: {exc}") from None
    return out
