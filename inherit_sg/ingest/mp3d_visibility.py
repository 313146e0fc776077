"""How well the walk of an MP3D house shows each object: per object, the pixels its
instance mask covers in every rendered frame of the walk.

The written isg frames renumber instance ids per frame (nothing downstream may link
frames through them), so this module renders the walk again with the true ids: the
same world, lights, intrinsics and poses as :func:`inherit_sg.ingest.mp3d_dataset.write_house_dataset`
(clean masks; the perception noise model only drops, splits and merges masks).

Run ``python -m inherit_sg.ingest.mp3d_visibility HOUSE [--min-pixels 61 ...]`` for a table of the
objects with the number of frames in which each has a mask of at least N pixels, and
the objects never visible at all. Ground truth for evaluation only.
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from inherit_sg.ingest.synthetic.generate import make_intrinsics
from inherit_sg.ingest.synthetic.render import Renderer

# The mapper's dataset segmenter keeps masks of at least max(50 px, 0.02 % of the image)
# pixels (61 px at 640 × 480) before a 1 px erosion; 614 px is the 0.2 % of the image
# that ``visibility.json`` calls "seen well".
DEFAULT_THRESHOLDS = (61, 200, 614)


@dataclass
class ObjectSight:
    """Pixel counts of one object's instance mask, frame by frame (only frames > 0)."""

    object_id: str
    label: str
    room_id: str | None
    pixels: dict[int, int] = field(default_factory=dict)  # frame index -> pixels

    @property
    def max_pixels(self) -> int:
        """The largest mask over the walk (0 when never visible)."""
        return max(self.pixels.values(), default=0)

    def frames(self, min_pixels: int) -> int:
        """Frames in which the mask has at least ``min_pixels`` pixels."""
        return sum(n >= min_pixels for n in self.pixels.values())


def walk_visibility(
    house: object,
    *,
    seed: int = 0,
    width: int = 640,
    height: int = 480,
    max_frames: int | None = None,
) -> list[ObjectSight]:
    """Render the walk of ``house`` (an :class:`inherit_sg.ingest.mp3d_dataset.HouseWorld`) with true
    instance ids and count each object's pixels per frame (objects in scene order)."""
    from inherit_sg.ingest.mp3d_dataset import HouseWorld

    if not isinstance(house, HouseWorld):
        raise TypeError("walk_visibility needs a HouseWorld")
    renderer = Renderer(house.world, house.lights, make_intrinsics(width, height))
    poses = house.trajectory(seed).poses
    poses = poses[:max_frames] if max_frames is not None else poses
    sights = [ObjectSight(o.id, o.label, o.room_id) for o in house.scene.objects]
    by_instance = {o.instance_id: s for o, s in zip(house.scene.objects, sights, strict=True)}
    for index, pose in enumerate(poses):
        ids, counts = np.unique(renderer.render(pose).instances, return_counts=True)
        for inst, n in zip(ids.tolist(), counts.tolist(), strict=True):
            sight = by_instance.get(int(inst))
            if sight is not None:
                sight.pixels[index] = int(n)
    return sights


def visibility_table(
    sights: Sequence[ObjectSight], thresholds: Sequence[int] = DEFAULT_THRESHOLDS
) -> list[dict[str, object]]:
    """One JSON-able row per object: id, label, room, max pixels, frames per threshold."""
    return [
        {
            "id": s.object_id,
            "label": s.label,
            "room": s.room_id,
            "max_pixels": s.max_pixels,
            "frames": {str(t): s.frames(t) for t in thresholds},
        }
        for s in sights
    ]


def main(argv: Sequence[str] | None = None) -> None:
    """Print (and optionally write) the visibility table of a ``.house`` file's walk."""
    from inherit_sg.ingest.mp3d_dataset import load_house_world

    ap = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    ap.add_argument("house", type=Path, help="Matterport3D .house file")
    ap.add_argument("--seed", type=int, default=0, help="walk seed (default: %(default)s)")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument(
        "--min-pixels",
        type=int,
        nargs="+",
        default=list(DEFAULT_THRESHOLDS),
        help="mask sizes to count frames for (default: %(default)s)",
    )
    ap.add_argument("--out", type=Path, default=None, help="write the table as JSON here")
    args = ap.parse_args(argv)
    sights = walk_visibility(
        load_house_world(args.house), seed=args.seed, width=args.width, height=args.height
    )
    rows = visibility_table(sights, args.min_pixels)
    heads = " ".join(f"{'>=' + str(t):>7s}" for t in args.min_pixels)
    print(f"{'id':6s} {'label':20s} {'room':5s} {'max px':>8s} {heads}")
    for row in rows:
        frames = row["frames"]
        assert isinstance(frames, dict)
        cols = " ".join(f"{frames[str(t)]:7d}" for t in args.min_pixels)
        head = f"{row['id']!s:6s} {row['label']!s:20s} {row['room']!s:5s}"
        print(f"{head} {row['max_pixels']:8d} {cols}")
    never = [r for r in rows if r["max_pixels"] == 0]
    print(f"\nnever visible ({len(never)} of {len(rows)}):")
    for r in never:
        print(f"  {r['id']} {r['label']} ({r['room']})")
    if args.out is not None:
        args.out.write_text(json.dumps(rows, indent=1) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
