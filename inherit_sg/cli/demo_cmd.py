"""``inherit-sg demo``: generate a house, map it, answer showcase requests."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated, Any

import typer

from inherit_sg.cli.output import counting_bars, handle_errors, print_json


@handle_errors
def demo(
    out: Annotated[
        Path, typer.Option(help="Folder for the house, the map and the pictures.")
    ] = Path("inherit-sg-demo"),
    seed: Annotated[int, typer.Option(help="House seed.")] = 7,
    width: Annotated[int, typer.Option(help="Rendered image width.")] = 320,
    height: Annotated[int, typer.Option(help="Rendered image height.")] = 240,
    force: Annotated[bool, typer.Option(help="Replace an earlier demo in OUT.")] = False,
    as_json: Annotated[bool, typer.Option("--json", help="Print a JSON summary instead.")] = False,
    serve: Annotated[
        bool, typer.Option("--serve", help="Afterwards, serve the map and its web viewer.")
    ] = False,
    port: Annotated[int, typer.Option(min=1, max=65535, help="Port for --serve.")] = 8765,
) -> None:
    """Generate a two-floor house, map it with the offline defaults, answer showcase
    requests of every kind (each checked against the ground truth), write BEV pictures."""
    from rich.console import Console

    from inherit_sg import demo as demo_lib
    from inherit_sg.facade import build_map

    console = Console(stderr=as_json)
    start = time.perf_counter()
    demo_lib.prepare_out(out, force)
    with counting_bars(console=console, transient=as_json) as bars:
        render = bars.add_task("1/3 rendering the house", total=None)
        dataset = demo_lib.generate(
            out, seed, width, height, lambda d, t: bars.update(render, completed=d, total=t)
        )
        frames = bars.add_task("2/3 mapping: frames", total=dataset["frames"])
        keyframes = bars.add_task("    keyframes (semantic)", total=None)

        def progress(p: Any) -> None:
            bars.update(frames, completed=p.frames)
            bars.update(keyframes, completed=p.keyframes_done, total=max(p.keyframes, 1))

        summary = build_map(out / "house", out / "map", progress=progress)
    console.print(
        f"[bold]map[/bold] {out / 'map'}: {summary['floors']} floors, {summary['rooms']} rooms, "
        f"{summary['areas']} areas, {summary['objects']} objects, {summary['relations']} relations "
        f"from {summary['frames']} frames ({summary['keyframes']} keyframes) in {summary['seconds']:.0f} s"
    )
    console.print("[bold]3/3 answering requests[/bold] (✓ = within 1 m of a true target)")
    answers = demo_lib.run_showcase(out / "map", out / "house")
    for a in answers:
        mark = "[green]✓[/green]" if a.correct else "[red]✗[/red]"
        where = "no answer"
        if a.answer is not None:
            x, y, z = a.answer["position"]
            where = f"{a.answer['label']} {a.answer['id']} in {a.answer.get('room')} at ({x:.1f}, {y:.1f}, {z:.1f})"
        console.print(f"\n{mark} [bold]{a.kind}[/bold] ({a.category}): “{a.text}”")
        console.print(f"   → {where}   [dim]{a.total_ms:.0f} ms[/dim]")
        for line in a.trace[:4]:
            console.print(f"     [dim]{line}[/dim]")
    correct = sum(a.correct for a in answers)
    console.print(f"\n{correct}/{len(answers)} answers within 1 m of a true target.")
    for png in summary["bev"]:
        console.print(f"BEV picture: {png}")
    console.print(
        f'Next: inherit-sg query --map {out / "map"} "..." --explain   ·   '
        f'inherit-sg cypher --map {out / "map"} "MATCH (r:Room) RETURN r.label, r.summary"'
    )
    console.print(
        f"Viewer: inherit-sg serve --map {out / 'map'}  then open http://127.0.0.1:{port}/"
        + ("" if serve else "   (or run the demo with --serve)")
    )
    console.print(f"[dim]demo finished in {time.perf_counter() - start:.0f} s[/dim]")
    if as_json:
        print_json(
            {
                "map": summary,
                "answers": [vars(a) for a in answers],
                "correct": correct,
                "seconds": round(time.perf_counter() - start, 1),
            }
        )
    if serve:
        import uvicorn

        from inherit_sg.api.app import create_app

        console.print(f"serving {out / 'map'} at http://127.0.0.1:{port}/ (Ctrl-C stops)")
        uvicorn.run(create_app(out / "map"), host="127.0.0.1", port=port, log_level="warning")
