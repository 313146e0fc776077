"""``inherit-sg parse``: readable tree, JSON, bad input, parser choice."""

from __future__ import annotations

import json

import pytest
import typer
from typer.testing import CliRunner

from inherit_sg.cli.parse_cmd import app, parse
from inherit_sg.retrieval.rules import MAX_QUERY_CHARS

runner = CliRunner()


def _main() -> typer.Typer:
    """The command registered the way the main CLI does it."""
    main = typer.Typer()

    @main.callback()
    def _root() -> None:
        """test root"""

    main.command("parse")(parse)
    return main


def test_tree_output() -> None:
    result = runner.invoke(
        _main(), ["parse", "the mug on the table next to the window, not in the kitchen"]
    )
    assert result.exit_code == 0, result.output
    out = result.output
    assert "target: mug (object)" in out
    assert "c2 relation on → table" in out
    assert "c2.1 relation next_to → window" in out
    assert "c3 NOT room kitchen" in out and "p=-1" in out


def test_json_output() -> None:
    result = runner.invoke(app, ["the second chair from the left", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["parser"] == "rules"
    assert data["target"]["labels"] == ["chair"]
    sup = data["constraints"][1]
    assert (sup["kind"], sup["measure"], sup["ordinal"], sup["direction"]) == (
        "superlative", "ordinal", 2, "left",
    )  # fmt: skip


def test_global_request_says_there_is_no_target() -> None:
    result = runner.invoke(app, ["How does this space support both work and relaxation?"])
    assert result.exit_code == 0
    assert "global question" in result.output


def test_bad_text_exits_2_with_a_clear_message() -> None:
    empty = runner.invoke(app, ["   ", "--json"])
    assert empty.exit_code == 2
    assert json.loads(empty.output) == {"error": "bad_query", "message": "query text is empty"}
    long = runner.invoke(app, ["x" * (MAX_QUERY_CHARS + 1)])
    assert long.exit_code == 2
    assert f"limit is {MAX_QUERY_CHARS}" in long.output
    binary = runner.invoke(app, ["\x07\x08"])
    assert binary.exit_code == 2


def test_llm_parser_without_endpoint_falls_back(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("INHERIT_SG_LLM__ENDPOINT", raising=False)
    result = runner.invoke(app, ["a red chair", "--parser", "llm", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["parser"] == "rules"
    assert "no LLM endpoint configured" in data["notes"][0]


def test_llm_parser_with_unreachable_endpoint_falls_back() -> None:
    args = ["a red chair", "--parser", "llm", "--json", "--set", "llm.endpoint=http://127.0.0.1:9",
            "--set", "llm.retries=0", "--set", "llm.timeout_s=2"]  # fmt: skip
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["target"]["labels"] == ["chair"]
    assert "decomposer failed" in data["notes"][0] and "127.0.0.1:9" in data["notes"][0]


def test_unknown_parser_is_refused() -> None:
    result = runner.invoke(app, ["a chair", "--parser", "magic"])
    assert result.exit_code != 0
