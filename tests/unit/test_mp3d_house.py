"""MP3D .house parsing into a ground-truth scene."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from inherit_sg.errors import DatasetError
from inherit_sg.ingest.mp3d_house import REGION_TYPES, REGIONS, parse_house, skip_reason


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


def test_real_house_keeps_every_region_and_object_category(real_data: Path) -> None:
    path = real_data / "mp3d" / "example_mp3d_scene.house"
    house = parse_house(path)
    scene = house.scene
    r_lines = [ln.split() for ln in path.read_text().splitlines() if ln.startswith("R ")]
    assert [r.attributes["mp3d_code"] for r in scene.rooms] == [p[5] for p in r_lines]
    types = sorted(r.type for r in scene.rooms)
    assert types == [
        "bathroom", "bathroom", "bedroom", "dining room", "entryway", "family room",
        "kitchen", "living room", "toilet", "tv room",
    ]  # fmt: skip
    tv = next(r for r in scene.rooms if r.type == "tv room")
    assert tv.attributes == {"mp3d_code": "v", "mp3d_category": "tv", "mp3d_index": 4}
    assert [r.name for r in scene.rooms if r.type == "bathroom"] == ["bathroom", "bathroom 2"]
    # Every O line is an object of the ground truth or listed as skipped, with why.
    o_lines = [ln for ln in path.read_text().splitlines() if ln.startswith("O ")]
    assert len(scene.objects) + len(house.skipped) == len(o_lines) == 187
    reasons: dict[str, int] = {}
    for s in house.skipped:
        reasons[s.reason] = reasons.get(s.reason, 0) + 1
    assert reasons == {"structure": 30, "junk": 15, "unnamed": 10, "no category": 1}
    assert {s.raw for s in house.skipped if s.reason == "structure"} == {"wall", "floor", "ceiling"}
    # Objects keep their raw category and its mpcat40 class.
    by_label = {o.label: o for o in scene.objects}
    assert by_label["oven"].attributes["mpcat40"] == "appliances"
    assert by_label["dishwasher"].attributes["mpcat40"] == "appliances"
    assert by_label["pillow"].attributes["mpcat40"] == "cushion"
    assert by_label["kitchen cabinet"].attributes["mp3d_category"] == "kitchen cabinet"
    assert by_label["kitchen cabinet"].attributes["mpcat40"] == "cabinet"
    assert by_label["carpet"].attributes["mpcat40"] == "floor"  # a floor covering, kept
    assert all(
        isinstance(o.attributes["mpcat40"], str) and o.attributes["mpcat40_index"] >= 0
        for o in scene.objects
    )


def test_region_codes_and_skip_rules() -> None:
    assert REGION_TYPES["v"] == "tv room" and REGION_TYPES["e"] == "entryway"
    assert REGIONS["e"] == ("entryway", "entryway/foyer/lobby")
    assert all(REGION_TYPES[c] == t for c, (t, _) in REGIONS.items())
    assert skip_reason("wall") == "structure" and skip_reason("remove") == "junk"
    assert skip_reason("unknown") == "unnamed" and skip_reason("x", has_category=False)
    assert skip_reason("oven") is None and skip_reason("carpet") is None


def test_skipped_lines_of_a_small_file(tmp_path: Path) -> None:
    f = tmp_path / "s.house"
    f.write_text(
        "ASCII 1.1\n"
        "R  0 0  0 0  Q  1 1 0  0 0 0  2 2 2.5  2.5  0 0 0 0\n"
        "C  0  1 oven  37 appliances  0 0 0 0 0\n"
        "C  1  2 wall  1 wall  0 0 0 0 0\n"
        "O  0 0 0  1 1 0.5  1 0 0  0 1 0  0.3 0.3 0.4  0 0 0 0 0 0 0 0\n"
        "O  1 0 1  1 0 1.2  1 0 0  0 0 1  1 1.2 0.05  0 0 0 0 0 0 0 0\n"
        "O  2 0 -1  1 1 1  1 0 0  0 1 0  1 1 1  0 0 0 0 0 0 0 0\n"
        "O  3 5 0  1 1 0.5  1 0 0  0 1 0  0.3 0.3 0.4  0 0 0 0 0 0 0 0\n"
    )
    house = parse_house(f)
    assert [o.id for o in house.scene.objects] == ["o0"]
    assert house.scene.objects[0].attributes["mpcat40"] == "appliances"
    assert [(s.index, s.raw, s.reason) for s in house.skipped] == [
        (1, "wall", "structure"),
        (2, "", "no category"),
        (3, "oven", "no region"),
    ]
    room = house.scene.rooms[0]  # an unknown region code still makes a room
    assert room.type == "room" and room.attributes["mp3d_code"] == "Q"


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
