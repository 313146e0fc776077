"""The data-only state format of map directories: what it stores, and that a hostile
file can neither run code nor create objects of classes it was not given."""

from __future__ import annotations

import io
import json
import pickle
import zipfile
from collections import deque
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.config import GeometryConfig
from inherit_sg.mapping.safe_state import StateFormatError, class_table, dump_state, load_state


@dataclass
class Cell:
    """A small class of the kind a state holds."""

    name: str
    grid: np.ndarray


class NotAllowed:
    """A class the file is not allowed to create."""

    def __init__(self) -> None:
        self.value = 1


CLASSES = class_table([Cell, GeometryConfig])


def test_round_trip_keeps_every_value_and_type(tmp_path: Path) -> None:
    value = {
        "none": None,
        "flags": [True, False],
        "numbers": (1, 2.5, float("inf"), np.float32(0.25), np.int64(7)),
        "ids": {3: "kf:1", (1, 2): {"a", "b"}},
        "recent": deque([1.0, 2.0], maxlen=4),
        "cells": [Cell("floor:0", np.arange(6, dtype=np.int32).reshape(2, 3))],
        "cfg": GeometryConfig(cell_size=0.1),
    }
    path = dump_state(value, tmp_path / "s.npz", CLASSES)
    back = load_state(path, CLASSES)
    assert back["none"] is None and back["flags"] == [True, False]
    assert back["numbers"][:3] == (1, 2.5, float("inf")) and back["numbers"][3:] == (0.25, 7)
    assert back["ids"] == {3: "kf:1", (1, 2): {"a", "b"}}
    assert isinstance(back["recent"], deque) and back["recent"].maxlen == 4
    cell = back["cells"][0]
    assert isinstance(cell, Cell) and cell.name == "floor:0"
    assert cell.grid.dtype == np.int32 and cell.grid.tolist() == [[0, 1, 2], [3, 4, 5]]
    assert isinstance(back["cfg"], GeometryConfig) and back["cfg"].cell_size == 0.1
    assert not list(tmp_path.glob("*.tmp")), "the atomic write left its temporary file"


def test_values_that_are_not_data_are_refused_when_written(tmp_path: Path) -> None:
    with pytest.raises(TypeError, match="NotAllowed"):
        dump_state({"x": NotAllowed()}, tmp_path / "s.npz", CLASSES)
    with pytest.raises(TypeError, match="objects"):
        dump_state(np.array([NotAllowed()], dtype=object), tmp_path / "s.npz", CLASSES)


def _raw_archive(text: str, **arrays: np.ndarray) -> bytes:
    """An .npz archive as np.savez writes it (arrays pickled where their dtype needs it)."""
    members = {"__structure__": np.frombuffer(text.encode("utf-8"), dtype=np.uint8), **arrays}
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as archive:
        for name, array in members.items():
            with archive.open(f"{name}.npy", "w") as out:
                np.lib.format.write_array(out, array, allow_pickle=True)
    return buf.getvalue()


def _archive(structure: object, **arrays: np.ndarray) -> bytes:
    return _raw_archive(json.dumps(structure), **arrays)


class _Payload:
    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self) -> tuple[object, tuple[Path]]:
        return (Path.touch, (self.marker,))


def test_hostile_files_are_refused_and_run_nothing(tmp_path: Path) -> None:
    marker = tmp_path / "ran"
    path = tmp_path / "s.npz"
    hostile = {
        "a pickle": pickle.dumps(_Payload(marker)),
        "an object array": _archive(
            {"$": "array", "key": "a0"}, a0=np.array([_Payload(marker)], dtype=object)
        ),
        "a class not allowed": _archive({"$": "object", "class": "NotAllowed", "fields": {}}),
        "a class given by module path": _archive(
            {"$": "object", "class": "os.system", "fields": {}}
        ),
        "an unknown element": _archive({"$": "eval", "code": "1"}),
        "a missing array": _archive({"$": "array", "key": "a9"}),
        "a bad number": _archive({"$": "float", "repr": "__import__('os')"}),
        "bad settings": _archive(
            {"$": "model", "class": "GeometryConfig", "fields": {"cell_size": "abc"}}
        ),
        "no structure": _archive({}, a0=np.zeros(2))[:0] + b"PK\x05\x06" + b"\0" * 18,
        "truncated": _archive([1, 2, 3])[:40],
        "an unhashable key": _archive({"$": "dict", "items": [[[1], 2]]}),
        "nesting too deep": _raw_archive("[" * 100_000 + "]" * 100_000),
        "random bytes": bytes(range(256)) * 4,
        "empty": b"",
    }
    for what, data in hostile.items():
        path.write_bytes(data)
        with pytest.raises(StateFormatError):
            load_state(path, CLASSES)
        assert not marker.exists(), f"{what} ran code"


def test_an_archive_without_its_structure_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "s.npz"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("a0.npy", b"not an array")
    with pytest.raises(StateFormatError):
        load_state(path, CLASSES)
