"""Floor, room and area listings, read through Cypher on the public graph tables."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from inherit_sg.reads.models import (
    AreaItem,
    AreaPage,
    FloorItem,
    FloorPage,
    RoomItem,
    RoomPage,
    RoomTypeItem,
)
from inherit_sg.store.codec import room_types_from_json

if TYPE_CHECKING:
    from inherit_sg.facade import MapService

Filters = list[tuple[str, str, Any]]


def _where(filters: Filters) -> tuple[str, dict[str, Any]]:
    """A WHERE clause of ``column = $name`` (or ``IN`` for lists) terms, with parameters."""
    terms, params = [], {}
    for name, column, value in filters:
        if value is None:
            continue
        op = "IN" if isinstance(value, list) else "="
        terms.append(f"{column} {op} ${name}")
        params[name] = value
    return (f" WHERE {' AND '.join(terms)}" if terms else ""), params


def label_filter(value: str | None) -> str | None:
    """A label filter as compared with ``lower(x.label)`` (None: no filter)."""
    return value.lower() if value is not None else None


def page_of(
    service: MapService,
    table: str,
    var: str,
    fields: str,
    filters: Filters,
    limit: int,
    offset: int,
) -> tuple[int, list[list[Any]]]:
    """Total matching rows and one page of ``fields``, ordered by id."""
    clause, params = _where(filters)
    total = service.cypher(f"MATCH ({var}:{table}){clause} RETURN count({var})", params).rows[0][0]
    if offset >= total:
        # past the end: also keeps Kuzu 0.11.3 from ORDER BY + a large SKIP (it crashes)
        return int(total), []
    rows = service.cypher(
        f"MATCH ({var}:{table}){clause} RETURN {fields} ORDER BY {var}.id SKIP $offset LIMIT $limit",
        {**params, "offset": offset, "limit": limit},
        max_rows=None,
    ).rows
    return int(total), rows


def count_by(service: MapService, table: str, column: str, ids: list[str]) -> dict[str, int]:
    """Rows of ``table`` per value of ``column``, for the given parent ids."""
    if not ids:
        return {}
    rows = service.cypher(
        f"MATCH (n:{table}) WHERE n.{column} IN $ids RETURN n.{column}, count(n)",
        {"ids": ids},
        max_rows=None,
    ).rows
    return {str(k): int(v) for k, v in rows}


def room_floors(service: MapService) -> dict[str, str | None]:
    """Room id → floor id for every room."""
    rows = service.cypher("MATCH (r:Room) RETURN r.id, r.floor_id", max_rows=None).rows
    return {str(r): f for r, f in rows}


def list_floors(service: MapService, *, label: str | None, limit: int, offset: int) -> FloorPage:
    """A page of floors ordered by id, optionally filtered by label."""
    total, rows = page_of(
        service,
        "Floor",
        "f",
        "f.id, f.label, f.level",
        [("label", "lower(f.label)", label_filter(label))],
        limit,
        offset,
    )
    ids = [r[0] for r in rows]
    rooms = count_by(service, "Room", "floor_id", ids)
    objects = count_by(service, "Object", "floor_id", ids)
    floors = [
        FloorItem(
            id=fid,
            label=flabel or "",
            level=level,
            rooms=rooms.get(fid, 0),
            objects=objects.get(fid, 0),
        )
        for fid, flabel, level in rows
    ]
    return FloorPage(floors=floors, total=total, limit=limit, offset=offset)


def list_rooms(
    service: MapService, *, floor: str | None, label: str | None, limit: int, offset: int
) -> RoomPage:
    """A page of rooms ordered by id, filtered by floor id and label, each with its
    inferred types."""
    total, rows = page_of(
        service,
        "Room",
        "r",
        "r.id, r.label, r.summary, r.position, r.floor_id, r.best_view, r.types",
        [("floor", "r.floor_id", floor), ("label", "lower(r.label)", label_filter(label))],
        limit,
        offset,
    )
    ids = [r[0] for r in rows]
    areas = count_by(service, "Area", "room_id", ids)
    objects = count_by(service, "Object", "room_id", ids)
    rooms = [
        RoomItem(
            id=rid,
            label=rlabel or "",
            summary=summary or None,
            position=position,
            floor_id=floor_id,
            best_view=best_view,
            types=[RoomTypeItem(type=t, p=p) for t, p in room_types_from_json(types)],
            areas=areas.get(rid, 0),
            objects=objects.get(rid, 0),
        )
        for rid, rlabel, summary, position, floor_id, best_view, types in rows
    ]
    return RoomPage(rooms=rooms, total=total, limit=limit, offset=offset)


def list_areas(
    service: MapService,
    *,
    floor: str | None,
    room: str | None,
    label: str | None,
    limit: int,
    offset: int,
) -> AreaPage:
    """A page of areas ordered by id, filtered by floor id (through the area's room),
    room id and label."""
    floors = room_floors(service)
    on_floor = None if floor is None else [r for r, f in floors.items() if f == floor]
    total, rows = page_of(
        service,
        "Area",
        "a",
        "a.id, a.label, a.summary, a.position, a.room_id",
        [
            ("floor_rooms", "a.room_id", on_floor),
            ("room", "a.room_id", room),
            ("label", "lower(a.label)", label_filter(label)),
        ],
        limit,
        offset,
    )
    objects = count_by(service, "Object", "area_id", [r[0] for r in rows])
    areas = [
        AreaItem(
            id=aid,
            label=alabel or "",
            summary=summary or None,
            position=position,
            room_id=room_id,
            floor_id=floors.get(room_id) if room_id else None,
            objects=objects.get(aid, 0),
        )
        for aid, alabel, summary, position, room_id in rows
    ]
    return AreaPage(areas=areas, total=total, limit=limit, offset=offset)
