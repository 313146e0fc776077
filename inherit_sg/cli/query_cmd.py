"""``inherit-sg query``: answer natural-language requests on a map.

One request: ``inherit-sg query --map DIR "the mug on the kitchen table" [--json]
[--no-verify] [--explain] [--top-k K] [--conversation FILE] [--viewer X,Y,Z,YAW]
[--rerun FILE.rrd|URL]``.
Many requests in one process: ``inherit-sg query --map DIR --batch IN.jsonl --out
OUT.jsonl``; each input line is ``{"id", "text"}`` (a ``queries.jsonl`` line works too)
and may carry the robot's pose as ``"viewer": {"position": [x, y, z], "yaw_deg": a}``
(else ``--viewer`` applies); each output line is the result JSON plus ``id`` (or
``{"id", "error": {...}}`` for a line that cannot be answered).

Register on the main app with ``app.command("query")(query_cmd.query)``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from inherit_sg.cli.output import (
    ConfigFileOption,
    OverridesOption,
    handle_errors,
    print_json,
    print_table,
)
from inherit_sg.errors import InheritSGError, InputError

if TYPE_CHECKING:
    import numpy as np

    from inherit_sg.facade import MapService
    from inherit_sg.retrieval.result import QueryResult
    from inherit_sg.retrieval.viewer import ViewerPose

app = typer.Typer(add_completion=False, pretty_exceptions_enable=False)


def _answer_line(result: QueryResult) -> str:
    a = result.answer
    if a is None:
        return "no answer"
    pos = ", ".join(f"{v:.2f}" for v in a["position"] or [])
    where = ", ".join(
        x
        for x in (
            f"room {a['room']}" if a["room"] else "",
            f"floor {a['floor']}" if a["floor"] is not None else "",
        )
        if x
    )
    return f"answer: {a['id']} {a['label']} at ({pos}){'  ' + where if where else ''}  S={a['score']:.2f}"


def print_result(result: QueryResult, top_k: int) -> None:
    """Human-readable result: plan (when asked), answer, candidates and trace."""
    if result.explain:
        typer.echo(result.explain)
    typer.secho(_answer_line(result), bold=True)
    rows = [
        [
            i,
            c["id"],
            c["label"],
            c["room"] or "",
            c["floor"] if c["floor"] is not None else "",
            f"{c['score']:.2f}",
        ]
        for i, c in enumerate(result.candidates[:top_k], start=1)
    ]
    if rows:
        print_table(["#", "id", "label", "room", "floor", "score"], rows, title="candidates")
    for line in result.trace:
        typer.secho(f"  {line}", dim=True)
    t = result.timings_ms
    typer.echo(", ".join(f"{k} {t[k]:.1f} ms" for k in ("parse", "retrieve", "verify", "total")))


def read_image(path: Path) -> np.ndarray:
    """RGB uint8 pixels of an image file; InputError naming the file otherwise."""
    import cv2
    import numpy as np

    pixels = cv2.imread(str(path), cv2.IMREAD_COLOR) if path.is_file() else None
    if pixels is None:
        raise InputError(f"query image {path}: not found or not an image")
    return np.ascontiguousarray(pixels[..., ::-1])


def parse_viewer(text: str) -> ViewerPose:
    """``--viewer X,Y,Z,YAW`` as a pose; InputError naming the value otherwise."""
    from inherit_sg.retrieval.viewer import ViewerPose

    return ViewerPose.parse(text)


def _line_viewer(data: dict[str, Any], default: ViewerPose | None) -> ViewerPose | None:
    """The pose a batch line carries (``"viewer"``), else ``default``."""
    from inherit_sg.retrieval.viewer import ViewerPose

    value = data.get("viewer")
    return default if value is None else ViewerPose.from_dict(value)


def _requests(path: Path) -> list[tuple[int, dict[str, Any] | None, str | None]]:
    """(line number, request, problem) for every non-empty line of a JSON-lines file."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"batch file {path}: cannot read it as UTF-8 text ({exc})") from None
    out: list[tuple[int, dict[str, Any] | None, str | None]] = []
    for number, line in enumerate(lines, start=1):
        if not line.strip():
            continue
        try:
            data = json.loads(line)
        except json.JSONDecodeError as exc:
            out.append((number, None, f"{path}:{number}: invalid JSON ({exc.msg})"))
            continue
        if not isinstance(data, dict) or not isinstance(data.get("text"), str):
            out.append((number, None, f"{path}:{number}: expected an object with 'text'"))
            continue
        out.append((number, data, None))
    return out


def run_batch(
    service: MapService,
    src: Path,
    dst: Path,
    *,
    verify: bool | None,
    top_k: int | None,
    show_progress: bool = True,
    viewer: ViewerPose | None = None,
) -> dict[str, int]:
    """Answer every request of ``src`` into ``dst`` (``viewer``: the robot's pose for
    lines that carry none); returns counts."""
    from rich.progress import Progress

    items = _requests(src)
    counts = {"requests": len(items), "answered": 0, "no_answer": 0, "errors": 0}
    dst.parent.mkdir(parents=True, exist_ok=True)
    with dst.open("w", encoding="utf-8") as fh, Progress(disable=not show_progress) as bar:
        task = bar.add_task("queries", total=len(items))
        for number, data, problem in items:
            rid = str(data.get("id", number)) if data is not None else str(number)
            if problem is not None or data is None:
                record: dict[str, Any] = {
                    "id": rid,
                    "error": {"error": "bad_input", "message": problem},
                }
                counts["errors"] += 1
            else:
                try:
                    pose = _line_viewer(data, viewer)
                    result = service.query(data["text"], verify=verify, top_k=top_k, viewer=pose)
                except InheritSGError as exc:
                    record = {"id": rid, "error": exc.to_dict()}
                    counts["errors"] += 1
                else:
                    record = {"id": rid, **result.to_dict()}
                    counts["answered" if result.answer is not None else "no_answer"] += 1
            fh.write(json.dumps(record) + "\n")
            bar.advance(task)
    return counts


@app.command("query")
@handle_errors
def query(
    map_dir: Annotated[Path, typer.Option("--map", "-m", help="Map directory.")],
    text: Annotated[
        str | None, typer.Argument(help="The request, e.g. 'the mug on the table'.")
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the result JSON.")] = False,
    no_verify: Annotated[
        bool, typer.Option("--no-verify", help="Skip visual verification.")
    ] = False,
    explain: Annotated[bool, typer.Option("--explain", help="Print the query plan.")] = False,
    top_k: Annotated[
        int | None, typer.Option("--top-k", min=1, help="Candidates to return.")
    ] = None,
    batch: Annotated[
        Path | None, typer.Option("--batch", help="JSON-lines file of requests.")
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Output JSON-lines file (--batch).")
    ] = None,
    conversation: Annotated[
        Path | None, typer.Option("--conversation", help="JSON file keeping the conversation.")
    ] = None,
    image: Annotated[
        Path | None, typer.Option("--image", help="A picture of the sought object.")
    ] = None,
    viewer: Annotated[
        str | None,
        typer.Option(
            "--viewer",
            help="The robot's pose X,Y,Z,YAW (metres; yaw in degrees counter-clockwise "
            "from +x): 'left', 'right' and ordinals are seen from it.",
        ),
    ] = None,
    config_file: ConfigFileOption = None,
    overrides: OverridesOption = None,
    rerun: Annotated[
        str | None,
        typer.Option(
            "--rerun",
            metavar="FILE.rrd|URL",
            help="Log the map, the candidates, the answer and the trace to Rerun: a .rrd "
            "file or a running viewer's URL. Needs rerun-sdk.",
        ),
    ] = None,
) -> None:
    """Answer a natural-language request on a map (or a batch of them)."""
    from inherit_sg.config import load_config
    from inherit_sg.facade import MapService

    if (text is None) == (batch is None):
        raise InputError("give either a request TEXT or --batch IN.jsonl (not both)")
    if batch is not None and out is None:
        raise InputError("--batch needs --out OUT.jsonl")
    if batch is not None and rerun is not None:
        raise InputError("--rerun logs one request: give a request TEXT, not --batch")
    pose = parse_viewer(viewer) if viewer is not None else None
    cfg = load_config(config_file, overrides or [])
    verify = False if no_verify else None
    with MapService.open(map_dir, config=cfg) as service:
        if batch is not None:
            assert out is not None
            counts = run_batch(
                service,
                batch,
                out,
                verify=verify,
                top_k=top_k,
                show_progress=not as_json,
                viewer=pose,
            )
            if as_json:
                print_json(counts)
            else:
                typer.echo(", ".join(f"{k} {v}" for k, v in counts.items()) + f" → {out}")
            return
        assert text is not None
        conv = None
        if conversation is not None:
            from inherit_sg.retrieval.history import load_conversation

            conv = load_conversation(conversation)
        picture = read_image(image) if image is not None else None
        result = service.query(
            text,
            conversation=conv,
            verify=verify,
            top_k=top_k,
            explain=explain,
            image=picture,
            viewer=pose,
        )
        if conv is not None and conversation is not None:
            from inherit_sg.retrieval.history import save_conversation

            save_conversation(conv, conversation)
        if rerun is not None:
            from inherit_sg.viz.rerun_log import RerunLog

            log = RerunLog(rerun, name=f"query {text}")
            log.query(text, result.to_dict(), service.scene3d())
            log.close()
    if as_json:
        print_json(result.to_dict())
    else:
        print_result(result, top_k or cfg.retrieval.top_k)
