"""``inherit-sg parse TEXT``: show the constraints a request is parsed into.

Register on the main app with ``app.command("parse")(parse)`` (or ``add_typer``).
"""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from inherit_sg.cli.output import handle_errors, print_json
from inherit_sg.retrieval.constraints import Constraint, Landmark
from inherit_sg.retrieval.query import ParsedQuery, describe

if TYPE_CHECKING:
    from rich.tree import Tree

    from inherit_sg.retrieval.llm_parser import LLMParser
    from inherit_sg.retrieval.rules.parser import RuleParser

app = typer.Typer(add_completion=False, pretty_exceptions_enable=False)


class ParserChoice(StrEnum):
    """Which parser runs."""

    rules = "rules"
    llm = "llm"


def make_parser(
    choice: str, config_path: Path | None = None, overrides: list[str] | None = None
) -> RuleParser | LLMParser:
    """The rule parser, or the LLM parser configured from ``[llm]`` (file, env, overrides)."""
    from inherit_sg.retrieval.rules.parser import RuleParser

    if choice == ParserChoice.rules:
        return RuleParser()
    from inherit_sg.config import load_config
    from inherit_sg.retrieval.llm_parser import LLMParser

    return LLMParser.from_config(load_config(config_path, overrides or []).llm)


def _add_landmark(node: Tree, lm: Landmark | None, label: str) -> None:
    if lm is None:
        return
    branch = node.add(f"[dim]{label}:[/dim] {lm.target.describe()}")
    for con in lm.constraints:
        _add_constraint(branch, con)


def _add_constraint(node: Tree, con: Constraint) -> None:
    sign = "[red]-1[/red]" if con.negated else "+1"
    branch = node.add(f"[bold]{con.id}[/bold] {describe(con)}  w={con.weight:.2f} p={sign}")
    _add_landmark(branch, getattr(con, "landmark", None), "landmark")
    _add_landmark(branch, getattr(con, "landmark2", None), "landmark 2")


def render_tree(parsed: ParsedQuery) -> None:
    """Print ``parsed`` as a readable tree."""
    from rich.console import Console
    from rich.tree import Tree

    head = parsed.no_target_reason or f"{parsed.target.describe()} ({parsed.target.layer})"
    tree = Tree(f"[bold]{parsed.text}[/bold]  [dim]parser={parsed.parser}[/dim]")
    tree.add(f"target: {head}")
    if parsed.reference != "none":
        tree.add(f"reference: {parsed.reference}")
    if parsed.viewpoint is not None:
        view = parsed.viewpoint
        _add_landmark(tree, view.landmark, f"viewpoint ({view.kind})")
    if parsed.constraints:
        cons = tree.add("constraints")
        for con in parsed.constraints:
            _add_constraint(cons, con)
    if parsed.notes:
        notes = tree.add("[dim]notes[/dim]")
        for note in parsed.notes:
            notes.add(f"[dim]{note}[/dim]")
    Console().print(tree)


@app.command("parse")
@handle_errors
def parse(
    text: Annotated[str, typer.Argument(help="The request, e.g. 'the mug on the table'.")],
    as_json: Annotated[bool, typer.Option("--json", help="Print machine-readable JSON.")] = False,
    parser: Annotated[
        ParserChoice,
        typer.Option("--parser", help="rules (offline: spaCy + vocabulary) or llm (endpoint)."),
    ] = ParserChoice.rules,
    config: Annotated[
        Path | None, typer.Option("--config", help="Config file (TOML) for the llm parser.")
    ] = None,
    override: Annotated[
        list[str] | None, typer.Option("--set", help="Config override section.field=value.")
    ] = None,
) -> None:
    """Parse a request into weighted constraints and print them."""
    parsed = make_parser(parser.value, config, override).parse(text)
    if as_json:
        print_json(parsed.to_dict())
    else:
        render_tree(parsed)
