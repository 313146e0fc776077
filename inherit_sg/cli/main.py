"""Entry point of the ``inherit-sg`` command.

Commands that need no model (info, cypher, export, import) import nothing heavy: the
facade imports torch, sentence-transformers and lancedb only where they are used.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from inherit_sg import __version__
from inherit_sg.cli import (
    bench_cmd,
    demo_cmd,
    map_cmd,
    mcp_cmd,
    parse_cmd,
    query_cmd,
    reads_cmd,
    scale_cmd,
    serve_cmd,
    sim,
)
from inherit_sg.cli.output import handle_errors, print_json, print_table
from inherit_sg.vocab import TABLES

app = typer.Typer(
    name="inherit-sg",
    help="Incremental hierarchical semantic scene graphs: build, store and query robot maps.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

app.add_typer(sim.app, name="sim")
app.add_typer(map_cmd.app, name="map")
map_cmd.app.command("build-many")(scale_cmd.build_many)
app.command("parse")(parse_cmd.parse)
app.command("demo")(demo_cmd.demo)
app.command("query")(query_cmd.query)
app.command("serve")(serve_cmd.serve)
app.command("mcp")(mcp_cmd.mcp)
app.command("bench")(bench_cmd.bench)
app.command("ls")(reads_cmd.ls)
app.command("show")(reads_cmd.show)

MapOption = Annotated[Path, typer.Option("--map", "-m", help="Map directory.")]
JsonOption = Annotated[bool, typer.Option("--json", help="Print machine-readable JSON.")]


def _version(value: bool) -> None:
    if value:
        typer.echo(f"inherit-sg {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Show the version.")
    ] = False,
) -> None:
    """INHerit-SG command line."""


# Labels of the label space listed by `info` (all of them with --json).
LABELS_SHOWN = 30


def vocabulary_line(vocabulary: dict[str, Any]) -> str:
    """The ``info`` line naming the map's vocabulary: digest and file versions."""
    if not vocabulary.get("digest"):
        return "vocabulary: not recorded (map made before vocabularies were recorded)"
    versions = vocabulary.get("versions") or {}
    order = sorted(versions, key=lambda n: (TABLES.index(n) if n in TABLES else len(TABLES), n))
    listed = ", ".join(f"{name} v{versions[name]}" for name in order)
    return f"vocabulary: {vocabulary['digest']}" + (f" ({listed})" if listed else "")


def label_space_line(labels: list[str]) -> str:
    """The ``info`` line listing the map's label space (the first ``LABELS_SHOWN``)."""
    if not labels:
        return "label space: none recorded (it is recorded when a mapping session finishes)"
    shown = ", ".join(labels[:LABELS_SHOWN])
    more = (
        f", … (+{len(labels) - LABELS_SHOWN} more; --json lists all)"
        if len(labels) > LABELS_SHOWN
        else ""
    )
    return f"label space: {len(labels)} labels: {shown}{more}"


@app.command()
@handle_errors
def info(map_dir: MapOption, as_json: JsonOption = False) -> None:
    """Counts per layer and edge type, sessions, vocabulary, label space and bytes on disk
    of a map."""
    from inherit_sg.facade import MapService

    with MapService.open(map_dir) as service:
        stats = service.stats()
    if as_json:
        print_json(stats)
        return
    typer.echo(f"map {stats['path']}  (schema v{stats['schema_version']})")
    print_table(["table", "rows"], sorted(stats["nodes"].items()), title="nodes")
    print_table(["relationship", "rows"], sorted(stats["edges"].items()), title="edges")
    sessions = stats.get("sessions", [])
    if sessions:
        print_table(
            ["session", "name", "frames", "keyframes"],
            [[s["id"], s["name"], s["frames"], s["keyframes"]] for s in sessions],
            title="sessions",
        )
    typer.echo(vocabulary_line(stats.get("vocabulary") or {}))
    typer.echo(label_space_line(stats.get("label_space") or []))
    sizes = stats["bytes"]
    typer.echo("bytes on disk: " + ", ".join(f"{k} {v:,}" for k, v in sizes.items()))


@app.command()
@handle_errors
def cypher(
    map_dir: MapOption,
    query: Annotated[str, typer.Argument(help="A read-only Cypher query.")],
    param: Annotated[
        list[str] | None,
        typer.Option("--param", "-p", help="Query parameter NAME=JSON (repeatable)."),
    ] = None,
    max_rows: Annotated[int, typer.Option(min=1, help="Stop after this many rows.")] = 1000,
    timeout: Annotated[
        float | None, typer.Option(min=0.001, help="Interrupt the query after SECONDS.")
    ] = None,
    as_json: JsonOption = False,
) -> None:
    """Run a read-only Cypher query; write clauses and procedures are refused."""
    from inherit_sg.facade import MapService, parse_params

    with MapService.open(map_dir) as service:
        result = service.cypher(
            query, parse_params(param or []), max_rows=max_rows, timeout_s=timeout
        )
    if as_json:
        print_json({"columns": result.columns, "rows": result.rows, "truncated": result.truncated})
        return
    print_table(result.columns, result.rows)
    if result.truncated:
        typer.echo(f"(stopped after {max_rows} rows; use --max-rows)")


@app.command("export")
@handle_errors
def export_map(
    map_dir: MapOption,
    out: Annotated[Path, typer.Argument(help="Output JSON file.")],
    no_images: Annotated[
        bool, typer.Option("--no-images", help="Leave keyframe JPEGs out.")
    ] = False,
    fmt: Annotated[
        str,
        typer.Option(
            "--format",
            "-f",
            help="json (lossless INHerit-SG export) or spark-dsg (Hydra scene graph JSON, "
            "written by the spark-dsg package).",
        ),
    ] = "json",
    as_json: JsonOption = False,
) -> None:
    """Write a whole map (embeddings, masks, keyframes) to one lossless JSON file, or its
    scene graph as Spark-DSG JSON (--format spark-dsg; objects folded into rooms)."""
    from inherit_sg.errors import InputError
    from inherit_sg.facade import MapService

    if fmt not in ("json", "spark-dsg"):
        raise InputError(f"unknown export format {fmt!r}: use json or spark-dsg")
    with MapService.open(map_dir) as service:
        if fmt == "spark-dsg":
            summary = service.export_spark_dsg(out)
        else:
            summary = service.export_json(out, images=not no_images)
    if as_json:
        print_json(summary)
    else:
        typer.echo(
            f"exported {summary['nodes']} nodes, {summary['edges']} edges, {summary['keyframes']} keyframes to {out}"
        )


@app.command("import")
@handle_errors
def import_map(
    source: Annotated[Path, typer.Argument(help="File to import.")],
    map_dir: MapOption,
    fmt: Annotated[
        str,
        typer.Option(
            "--format",
            "-f",
            help="json (INHerit-SG export), spark-dsg (Hydra JSON) or scene "
            "(a dataset's ground-truth scene.json as an oracle map).",
        ),
    ] = "json",
    label_space: Annotated[
        Path | None, typer.Option(help="spark-dsg: JSON or CSV naming semantic label ids.")
    ] = None,
    as_json: JsonOption = False,
) -> None:
    """Create a map from an INHerit-SG JSON export, a Spark-DSG (Hydra) JSON graph or a
    ground-truth scene.json (oracle map for evaluation)."""
    from inherit_sg.facade import import_into_new_map

    summary = import_into_new_map(source, map_dir, fmt=fmt, label_space=label_space)
    if as_json:
        print_json(summary)
    else:
        typer.echo(f"imported {summary['nodes']} nodes and {summary['edges']} edges into {map_dir}")


def main() -> None:
    """Console-script entry point."""
    app()


if __name__ == "__main__":
    main()
