"""Printing helpers shared by CLI commands: JSON conversion, tables, error exits."""

from __future__ import annotations

import json
import sys
from collections.abc import Callable, Sequence
from functools import wraps
from pathlib import Path
from typing import Annotated, Any, ParamSpec, TypeVar

import typer

from inherit_sg.errors import InheritSGError
from inherit_sg.json_values import jsonable

# The configuration options every command that loads a configuration takes.
ConfigFileOption = Annotated[Path | None, typer.Option("--config", help="TOML config file.")]
OverridesOption = Annotated[
    list[str] | None,
    typer.Option("--set", help="Config override section.field=value (repeatable)."),
]

P = ParamSpec("P")
R = TypeVar("R")


def print_json(data: Any) -> None:
    """Write ``data`` as indented JSON on stdout."""
    sys.stdout.write(json.dumps(jsonable(data), indent=2) + "\n")


def cell(value: Any, width: int = 60) -> str:
    """Short human-readable form of one value for a table cell."""
    value = jsonable(value)
    if isinstance(value, list) and value and all(isinstance(v, float) for v in value):
        text = "[" + ", ".join(f"{v:.3g}" for v in value[:4]) + (", …]" if len(value) > 4 else "]")
    elif isinstance(value, dict | list):
        text = json.dumps(value)
    else:
        text = "" if value is None else str(value)
    return text if len(text) <= width else text[: width - 1] + "…"


def print_table(
    columns: Sequence[str], rows: Sequence[Sequence[Any]], title: str | None = None
) -> None:
    """Render rows as a rich table."""
    from rich.console import Console
    from rich.table import Table

    table = Table(title=title)
    for col in columns:
        table.add_column(str(col))
    for row in rows:
        table.add_row(*(cell(v) for v in row))
    Console().print(table)


def counting_bars(*, transient: bool = False, console: Any = None) -> Any:
    """A rich progress display of labelled bars with done/total counts and elapsed time
    (``transient``: gone when it ends, e.g. before JSON output)."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
    )
    return Progress(*columns, console=console, transient=transient)


def handle_errors(func: Callable[P, R]) -> Callable[P, R]:
    """Turn library errors into a one-line message (or JSON with --json) and exit 2."""

    @wraps(func)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return func(*args, **kwargs)
        except InheritSGError as exc:
            if kwargs.get("as_json"):
                print_json(exc.to_dict())
            else:
                typer.secho(f"error: {exc.message}", fg=typer.colors.RED, err=True)
            raise typer.Exit(code=2) from None

    return wrapper
