"""Configuration: TOML file, environment variables and CLI overrides, in that order."""

from __future__ import annotations

from pathlib import Path

import pytest

from inherit_sg.config import Config, load_config
from inherit_sg.errors import ConfigError


def test_defaults() -> None:
    cfg = load_config(environ={})
    assert cfg == Config()
    assert cfg.store.text_dim == 384
    assert cfg.service.host == "127.0.0.1"


def test_file_then_env_then_overrides(tmp_path: Path) -> None:
    f = tmp_path / "c.toml"
    f.write_text('[store]\nvisual_dim = 512\n[llm]\nmodel = "qwen2-vl"\ntimeout_s = 9\n')
    env = {"INHERIT_SG_LLM__TIMEOUT_S": "4", "INHERIT_SG_STORE__VISUAL_DIM": "768", "OTHER": "x"}
    cfg = load_config(f, overrides=["store.visual_dim=1024"], environ=env)
    assert cfg.llm.model == "qwen2-vl"
    assert cfg.llm.timeout_s == 4.0
    assert cfg.store.visual_dim == 1024


def test_config_file_from_environment(tmp_path: Path) -> None:
    f = tmp_path / "c.toml"
    f.write_text("[retrieval]\nverify = false\n")
    assert load_config(environ={"INHERIT_SG_CONFIG": str(f)}).retrieval.verify is False


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"overrides": ["nosection.x=1"]}, "unknown config section 'nosection'"),
        ({"overrides": ["store=1"]}, "expected 'section.field'"),
        ({"overrides": ["store.visual_dim"]}, "expected section.field=value"),
        ({"overrides": ["store.visual_dim=3"]}, "store.visual_dim"),
        ({"overrides": ["store.no_such_field=3"]}, "store.no_such_field"),
        ({"environ": {"INHERIT_SG_RETRIEVAL__PARSER": "magic"}}, "retrieval.parser"),
    ],
)
def test_bad_values_are_named(kwargs: dict, message: str) -> None:
    kwargs.setdefault("environ", {})
    with pytest.raises(ConfigError, match=message.replace(".", r"\.")):
        load_config(**kwargs)


def test_bad_file(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="not found"):
        load_config(tmp_path / "missing.toml", environ={})
    bad = tmp_path / "bad.toml"
    bad.write_text("[store\n")
    with pytest.raises(ConfigError, match="invalid TOML"):
        load_config(bad, environ={})
