"""Sets of objects as room-type evidence (``sets`` in rooms.toml): enough objects of a
kind (or of kinds of it) together say more for a type than the kind once; an open-plan
group holding such a set (chairs around an unseen table) stands as its own room.

Kinds and counts are read from ``rooms.toml``, so the tests follow the file."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

import inherit_sg.vocab as vocab
from inherit_sg.mapping.open_plan import split_room
from inherit_sg.mapping.room_semantics import infer_room_types, type_evidence
from inherit_sg.model import BBox3D, ObjectNode, RoomMask
from inherit_sg.vocab import VocabularyError, objects, rooms

RES = 0.1


def a_set() -> tuple[str, str, int, float]:
    """(type, kind, count, weight) of the first set in rooms.toml."""
    for name, rtype in rooms.room_type_table().items():
        for kind, (count, weight) in rtype.sets.items():
            return name, kind, count, weight
    raise AssertionError("rooms.toml defines no sets")


def test_set_kinds_are_object_kinds() -> None:
    for name, rtype in rooms.room_type_table().items():
        for kind, (count, weight) in rtype.sets.items():
            assert objects.canonical_label(kind) == kind, (name, kind)
            assert count >= 2 and weight != 0


def test_a_set_adds_its_weight_once_the_count_is_reached() -> None:
    name, kind, count, weight = a_set()
    below = type_evidence([kind] * (count - 1))[name]
    at = type_evidence([kind] * count)[name]
    assert np.isclose(at - below, weight)
    assert np.isclose(type_evidence([kind] * (count + 3))[name], at)


def test_kinds_of_the_set_kind_count_towards_it() -> None:
    name, kind, count, weight = a_set()
    sub = next((k for k in objects.kinds() if kind in objects.is_a(k) and k != kind), None)
    if sub is None:
        pytest.skip(f"no kind is a kind of {kind!r}")
    gain = type_evidence([sub] * count)[name] - type_evidence([sub] * (count - 1))[name]
    assert np.isclose(gain, weight)


def test_a_set_shifts_the_inferred_type() -> None:
    name, kind, count, _ = a_set()
    assert infer_room_types([kind] * count)[0][0] == name


def obj(i: int, label: str, x: float, y: float) -> ObjectNode:
    box = BBox3D((x - 0.25, y - 0.25, 0.0), (x + 0.25, y + 0.25, 0.9))
    return ObjectNode(f"obj:{i}", label, (x, y, 0.45), box)


def test_a_set_of_chairs_is_its_own_part_of_an_open_plan_room() -> None:
    """Armchairs say a living room one by one; a set of them around an unseen table at
    the far end of an open-plan room stands apart from the living group."""
    name, kind, count, _ = a_set()
    table = rooms.room_type_table()
    subs = [
        (t, k)
        for k in objects.kinds()
        if kind in objects.is_a(k)
        for t, w in type_evidence([k]).items()
        if t != name and w > type_evidence([k])[name]
    ]
    if not subs:
        pytest.skip(f"no kind of {kind!r} says another type more than {name!r}")
    other, member = subs[0]
    own = table[other].evidence
    strong = [k for k in sorted(own, key=lambda k: (-own[k], k)) if k != member][:3]
    group = [obj(k, lab, 0.6 + 0.9 * k, 2.0) for k, lab in enumerate(strong)]
    # the set around an unseen table at the east end, touching one another
    ring = [(9.5, 1.5), (10.0, 1.5), (9.5, 2.5), (10.0, 2.5), (9.0, 2.0), (10.5, 2.0)]
    chairs = [obj(10 + k, member, x, y) for k, (x, y) in enumerate(ring[: max(count, 4)])]
    mask = RoomMask(0.0, 0.0, RES, np.ones((40, 120), dtype=bool))
    split = split_room(mask, group + chairs)
    assert split is not None
    assert [p.room_type for p in split.parts] == [other, name]
    # fewer chairs than the set: one room
    assert split_room(mask, group + chairs[: count - 1]) is None


@pytest.fixture
def data_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    copy = tmp_path / "data"
    shutil.copytree(vocab.DATA_DIR, copy)
    monkeypatch.setattr(vocab, "DATA_DIR", copy)
    vocab.load_table.cache_clear()
    vocab.vocabulary_info.cache_clear()
    rooms.clear_caches()
    yield copy
    monkeypatch.undo()
    vocab.load_table.cache_clear()
    vocab.vocabulary_info.cache_clear()
    rooms.clear_caches()


@pytest.mark.parametrize("bad", ["[1, 3.0]", "[4, 0]", "[4]", '"many"', "[4.5, 1.0]"])
def test_bad_sets_are_refused(data_dir: Path, bad: str) -> None:
    path = data_dir / "rooms.toml"
    text = path.read_text(encoding="utf-8")
    _, kind, count, weight = a_set()
    old = f"sets = {{ {kind} = [{count}, {weight}] }}"
    assert old in text
    path.write_text(text.replace(old, f"sets = {{ {kind} = {bad} }}", 1), encoding="utf-8")
    vocab.load_table.cache_clear()
    vocab.vocabulary_info.cache_clear()
    rooms.clear_caches()
    with pytest.raises(VocabularyError, match=r"rooms\.toml.*'sets'"):
        rooms.room_type_table()
