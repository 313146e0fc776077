"""The bird's-eye-view pictures a finished mapping session leaves in ``<map>/bev/``."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from inherit_sg.model import RoomNode


def write_bev_pictures(mapper: Any, map_dir: Path) -> list[Path]:
    """One BEV PNG per floor under ``<map>/bev/``."""
    out_dir = map_dir / "bev"
    out_dir.mkdir(exist_ok=True)

    labels = {
        n.id: f"{n.label} ({n.id.partition(':')[2]})"
        for n in mapper.graph.nodes()
        if isinstance(n, RoomNode)
    }
    written = []
    for floor in mapper.geometry.floors():
        level = floor.level
        try:
            written.append(
                mapper.geometry.save_bev(
                    out_dir / f"floor_{level}.png", floor.id, refined=True, labels=labels
                )
            )
        except ValueError:
            continue
    return written
