"""Ground-truth files written beside a generated dataset, for evaluation only:

* ``visibility.json`` — per object: frames it appears in with at least
  :data:`MIN_PIXELS` pixels and its largest pixel count; an object the camera never saw
  well cannot be expected in a map (mapping recall is measured over seen objects);
* ``walk.json`` — per frame: the true floor index and room id of the camera;
* ``queries.jsonl`` and ``conversations.jsonl`` — the SQR-style request set.

Nothing in mapping or retrieval reads these files.
"""

from __future__ import annotations

import json
from collections import defaultdict
from pathlib import Path

from inherit_sg.ingest.synthetic.queries import (
    generate_conversations,
    generate_queries,
    write_conversations,
    write_queries,
)
from inherit_sg.ingest.synthetic.scene import Scene

MIN_PIXELS = 0.002  # share of the image: about 600 px at 640×480
VISIBILITY_FILE = "visibility.json"
WALK_FILE = "walk.json"


class VisibilityLog:
    """Accumulates per-instance pixel counts over rendered frames."""

    def __init__(self, image_pixels: int) -> None:
        self.min_pixels = max(1, int(MIN_PIXELS * image_pixels))
        self.frames: dict[int, int] = defaultdict(int)
        self.max_pixels: dict[int, int] = defaultdict(int)

    def add(self, pixels: dict[int, int]) -> None:
        """Record one frame's ``instance id -> pixel count``."""
        for inst, n in pixels.items():
            if n >= self.min_pixels:
                self.frames[inst] += 1
            self.max_pixels[inst] = max(self.max_pixels[inst], n)

    def by_object(self, instance_to_object: dict[int, str]) -> dict[str, dict[str, int]]:
        """Per object id: frames seen well and the largest pixel count."""
        return {
            instance_to_object[inst]: {"frames": self.frames.get(inst, 0), "max_pixels": n}
            for inst, n in sorted(self.max_pixels.items())
            if inst in instance_to_object
        }


def write_ground_truth_extras(
    out: Path,
    scene: Scene,
    seed: int,
    *,
    visibility: dict[str, dict[str, int]],
    frame_floors: list[int],
    frame_rooms: list[str | None],
) -> None:
    """Write visibility, per-frame truth, queries and conversations into ``out``."""
    (out / VISIBILITY_FILE).write_text(json.dumps(visibility, indent=1), encoding="utf-8")
    walk = {"floors": frame_floors, "rooms": frame_rooms}
    (out / WALK_FILE).write_text(json.dumps(walk), encoding="utf-8")
    write_queries(out, generate_queries(scene, seed))
    write_conversations(out, generate_conversations(scene, seed))


def seen_objects(folder: str | Path, min_frames: int = 2) -> set[str]:
    """Ids of objects seen well in at least ``min_frames`` frames of a generated dataset."""
    data = json.loads((Path(folder) / VISIBILITY_FILE).read_text(encoding="utf-8"))
    return {oid for oid, v in data.items() if v["frames"] >= min_frames}
