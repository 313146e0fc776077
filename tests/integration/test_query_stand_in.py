"""A thing the map does not hold, placed on or in one it does: the robot goes to the
place ("leave my glasses on the nightstand", "my keys are on the sofa, grab them"), on a
real map (Kuzu + LanceDB, MiniLM embeddings); a thing the map holds is still the answer."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from inherit_sg.retrieval.engine import QueryEngine
from inherit_sg.store import MapStore
from tests.unit.retrieval_fixtures import write_small_map


@pytest.fixture(scope="module")
def engine(tmp_path_factory: pytest.TempPathFactory) -> Iterator[QueryEngine]:
    path: Path = write_small_map(tmp_path_factory.mktemp("stand_in") / "map")
    with MapStore.open(path) as store:
        yield QueryEngine(store)


@pytest.mark.parametrize(
    ("text", "place"),
    [
        ("Could you leave my glasses on the nightstand?", "obj:n1"),
        ("my keys are on the sofa, grab them", "obj:s1"),
        ("put my glasses on the nightstand", "obj:n1"),
    ],
)
def test_an_unmapped_thing_is_found_where_it_is_put(
    engine: QueryEngine, text: str, place: str
) -> None:
    result = engine.query(text)
    assert result.answer_id == place
    assert any("answering where the request places it" in line for line in result.trace)


def test_a_mapped_thing_is_still_the_answer(engine: QueryEngine) -> None:
    result = engine.query("the vase on the coffee table")
    assert result.answer_id == "obj:v1"
    assert not any("answering where the request places it" in line for line in result.trace)


def test_a_place_the_map_lacks_keeps_the_first_answer(engine: QueryEngine) -> None:
    # no piano in the map: nothing to stand in for the glasses
    result = engine.query("my glasses are on the piano")
    assert not any("answering where the request places it" in line for line in result.trace)


def test_the_floor_is_no_place_to_go_to(engine: QueryEngine) -> None:
    # "my glasses are on the floor": no stand-in (the floor is everywhere)
    result = engine.query("my glasses are on the floor")
    assert not any("answering where the request places it" in line for line in result.trace)


def test_what_is_inside_a_thing_goes_to_the_thing(engine: QueryEngine) -> None:
    # the map holds nothing inside the refrigerator: the refrigerator is where to go
    result = engine.query("what's inside the refrigerator?")
    assert result.answer_id == "obj:f1"
    assert any("nothing mapped is in or on" in line for line in result.trace)
