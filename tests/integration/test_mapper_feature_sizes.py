"""A map keeps one visual feature size: mapping with an encoder of another size is refused
with a message naming both sizes, and the map is left as it was."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.config import Config
from inherit_sg.errors import ConfigError
from inherit_sg.mapping.orchestrator import Mapper
from inherit_sg.model import Session
from inherit_sg.store import MapStore


def test_encoder_of_another_size_is_refused(tmp_path: Path) -> None:
    small = Config.model_validate({"store": {"visual_dim": 128, "image_feature_dim": 128}})
    MapStore.create(tmp_path / "m", small).close()
    with MapStore.open(tmp_path / "m", write=True, config=Config()) as store:
        session = Session(id="session:1", name="s", started=0.0, dataset="none")
        with pytest.raises(ConfigError, match=r"128-d object .* gives 256-d"):
            Mapper(store, Config(), session)
        assert store.sessions() == []
        assert store.info.visual_dim == 128
