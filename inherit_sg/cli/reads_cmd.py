"""``inherit-sg ls`` and ``inherit-sg show``: the map's listings and an object's detail,
the same reads REST serves (through :class:`~inherit_sg.facade.MapService`)."""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any

import typer

from inherit_sg.cli.output import handle_errors, print_json, print_table


class Layer(StrEnum):
    """What ``ls`` lists."""

    floors = "floors"
    rooms = "rooms"
    areas = "areas"
    objects = "objects"


MapOption = Annotated[Path, typer.Option("--map", "-m", help="Map directory.")]
JsonOption = Annotated[bool, typer.Option("--json", help="Print machine-readable JSON.")]


def _xyz(position: list[float] | None) -> str:
    return "" if not position else "(" + ", ".join(f"{v:.2f}" for v in position) + ")"


def _rows(layer: Layer, page: Any) -> tuple[list[str], list[list[Any]]]:
    """Table columns and rows of one listing page."""
    if layer is Layer.floors:
        return ["id", "label", "level", "rooms", "objects"], [
            [f.id, f.label, f.level, f.rooms, f.objects] for f in page.floors
        ]
    if layer is Layer.rooms:
        return ["id", "label", "floor", "also", "areas", "objects"], [
            [
                r.id,
                r.label,
                r.floor_id,
                ", ".join(f"{t.type} {t.p:.2f}" for t in r.types[1:3]),
                r.areas,
                r.objects,
            ]
            for r in page.rooms
        ]
    if layer is Layer.areas:
        return ["id", "label", "room", "floor", "objects"], [
            [a.id, a.label, a.room_id, a.floor_id, a.objects] for a in page.areas
        ]
    return ["id", "label", "room", "floor", "position", "status"], [
        [o.id, o.label, o.room_id, o.floor_id, _xyz(o.position), o.status] for o in page.objects
    ]


@handle_errors
def ls(
    layer: Annotated[Layer, typer.Argument(help="What to list.")],
    map_dir: MapOption,
    floor: Annotated[str | None, typer.Option(help="Only on this floor id (e.g. floor:0).")] = None,
    room: Annotated[str | None, typer.Option(help="Only in this room id (areas, objects).")] = None,
    label: Annotated[str | None, typer.Option(help="Only with this label (any case).")] = None,
    limit: Annotated[int, typer.Option(min=1, max=1000, help="Rows per page.")] = 100,
    offset: Annotated[int, typer.Option(min=0, help="Rows to skip.")] = 0,
    as_json: JsonOption = False,
) -> None:
    """List the floors, rooms, functional areas or objects of a map, ordered by id."""
    from inherit_sg.errors import InputError
    from inherit_sg.facade import MapService

    if room is not None and layer in (Layer.floors, Layer.rooms):
        raise InputError(f"--room filters areas and objects, not {layer.value}")
    if floor is not None and layer is Layer.floors:
        raise InputError("--floor filters rooms, areas and objects, not floors")
    with MapService.open(map_dir) as service:
        page: Any
        if layer is Layer.floors:
            page = service.floors(label=label, limit=limit, offset=offset)
        elif layer is Layer.rooms:
            page = service.rooms(floor=floor, label=label, limit=limit, offset=offset)
        elif layer is Layer.areas:
            page = service.areas(floor=floor, room=room, label=label, limit=limit, offset=offset)
        else:
            page = service.objects(floor=floor, room=room, label=label, limit=limit, offset=offset)
    if as_json:
        print_json(page.model_dump(mode="json"))
        return
    columns, rows = _rows(layer, page)
    shown = f"{offset + 1}–{offset + len(rows)}" if rows else "none"
    print_table(columns, rows, title=f"{layer.value} {shown} of {page.total}")
    if offset + len(rows) < page.total:
        typer.echo(f"(more: --offset {offset + len(rows)})")


@handle_errors
def show(
    object_id: Annotated[str, typer.Argument(help="Object id, e.g. obj:12.")],
    map_dir: MapOption,
    as_json: JsonOption = False,
) -> None:
    """One object: label, position and box, description, its area → room → floor path,
    its relations to other objects and the keyframes it was seen in."""
    from inherit_sg.facade import MapService

    with MapService.open(map_dir) as service:
        detail = service.object(object_id)
    if as_json:
        print_json(detail.model_dump(mode="json"))
        return
    typer.echo(f"{detail.id}  {detail.label}  at {_xyz(detail.position)}  [{detail.status}]")
    if detail.bbox_min and detail.bbox_max:
        typer.echo(f"box {_xyz(detail.bbox_min)} – {_xyz(detail.bbox_max)}")
    if detail.description:
        typer.echo(detail.description)
    path = " → ".join(f"{h.layer} {h.id} ({h.label})" for h in detail.hierarchy)
    typer.echo(f"in: {path or 'no area, room or floor'}")
    if detail.relations:
        print_table(
            ["", "predicate", "other", "label", "confidence"],
            [
                [
                    "→" if r.direction == "out" else "←",
                    r.predicate,
                    r.other_id,
                    r.other_label,
                    "" if r.confidence is None else f"{r.confidence:.2f}",
                ]
                for r in detail.relations
            ],
            title="relations",
        )
    if detail.keyframes:
        best = detail.best_keyframe
        print_table(
            ["keyframe", "session", "floor", "best"],
            [
                [k.id, k.session_id, k.floor_id, "*" if k.id == best else ""]
                for k in detail.keyframes
            ],
            title=f"seen in {len(detail.keyframes)} keyframes",
        )
