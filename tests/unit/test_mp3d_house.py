"""MP3D .house parsing into a ground-truth scene."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from ingest.mp3d_house import parse_house
from inherit_sg.errors import DatasetError


def test_real_house(real_data: Path) -> None:
    house = parse_house(real_data / "mp3d" / "example_mp3d_scene.house")
    scene = house.scene
    assert len(scene.floors) == 1
    assert len(scene.rooms) == 10
    types = {r.type for r in scene.rooms}
    assert {"bedroom", "bathroom", "kitchen", "living room", "dining room"} <= types
    # every room polygon comes from the floor surface and encloses the room's objects' centres mostly
    for room in scene.rooms:
        assert len(room.polygon) >= 3
    labels = {o.label for o in scene.objects}
    assert {"bed", "toilet", "sink", "tv", "couch"} <= labels
    assert not labels & {"wall", "floor", "ceiling", "remove"}
    # boxes are consistent with centres and kept in the file's own (z-up) coordinates
    bed = next(o for o in scene.objects if o.label == "bed")
    assert np.all(np.array(bed.bbox_min) <= bed.centroid) and np.all(
        np.array(bed.bbox_max) >= bed.centroid
    )
    assert bed.room_id is not None and scene.room(bed.room_id).type == "bedroom"
    assert -0.5 < bed.centroid[2] < 2.0
    doors = [o for o in scene.objects if o.label == "door"]
    assert doors and all(o.structural for o in doors)
    box = house.boxes[bed.id]
    assert np.allclose(box.corners().mean(axis=0), bed.centroid)


def test_malformed_house(tmp_path: Path) -> None:
    bad = tmp_path / "x.house"
    bad.write_text("hello\n")
    with pytest.raises(DatasetError, match="not an MP3D"):
        parse_house(bad)
    bad.write_text("ASCII 1.1\nR 0 0 0 0 b 1 2\n")
    with pytest.raises(DatasetError, match=":2: malformed 'R' line"):
        parse_house(bad)
    with pytest.raises(DatasetError, match="not found"):
        parse_house(tmp_path / "none.house")
