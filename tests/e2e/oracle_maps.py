"""Real maps for the REST tests without rendering: a generated house's ground truth
imported as an oracle map (Kuzu + LanceDB, real MiniLM text embeddings)."""

from __future__ import annotations

import json
from pathlib import Path

from inherit_sg.facade import import_into_new_map
from inherit_sg.ingest.synthetic.generate import generate_house


def oracle_map(root: Path, name: str, seed: int, *, floors: int = 1, rooms: int = 4) -> Path:
    """Import house ``seed`` as map ``root/maps/name``; its directory."""
    src = root / f"scene-{seed}.json"
    src.write_text(json.dumps(generate_house(seed, floors, rooms).scene.to_dict()))
    out = root / "maps" / name
    out.parent.mkdir(parents=True, exist_ok=True)
    import_into_new_map(src, out, fmt="scene")
    return out
