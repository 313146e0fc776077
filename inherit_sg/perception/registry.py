"""Name → factory registries of the perception backends, one per role.

Factories take the whole :class:`Config` and import their heavy dependencies (torch,
transformers, onnxruntime) only when called, so importing this module stays cheap.
``register_*`` adds more backends; an unknown name raises
:class:`ModelUnavailableError` listing the known ones.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Generic, TypeVar

from inherit_sg.config import Config
from inherit_sg.errors import ModelUnavailableError
from inherit_sg.perception.base import Describer, Segmenter, VisualEncoder

T = TypeVar("T")
Factory = Callable[[Config], T]


class Registry(Generic[T]):
    """Backends of one role by name."""

    def __init__(self, role: str) -> None:
        self.role = role
        self._factories: dict[str, Factory[T]] = {}

    def register(self, name: str, factory: Factory[T], *, replace: bool = False) -> None:
        """Add ``factory`` under ``name`` (lower-cased); refuses to shadow silently."""
        key = name.strip().lower()
        if key in self._factories and not replace:
            raise ValueError(f"{self.role} backend {key!r} is already registered")
        self._factories[key] = factory

    def names(self) -> list[str]:
        """Registered names, sorted."""
        return sorted(self._factories)

    def create(self, name: str, config: Config | None = None) -> T:
        """Build the backend ``name`` from ``config`` (defaults when None)."""
        key = name.strip().lower()
        factory = self._factories.get(key)
        if factory is None:
            known = ", ".join(self.names())
            raise ModelUnavailableError(f"unknown {self.role} {name!r} (known: {known})")
        return factory(config or Config())


def model_path(config: Config, sub: str, what: str) -> Path:
    """``config.perception.model_dir / sub``; ModelUnavailableError when missing."""
    root = config.perception.model_dir
    if not root:
        raise ModelUnavailableError(
            f"{what} needs perception.model_dir (a local directory holding {sub!r})"
        )
    path = Path(root).expanduser() / sub
    if not path.exists():
        raise ModelUnavailableError(f"{what}: {path} does not exist")
    return path


def _dataset(config: Config) -> Segmenter:
    from inherit_sg.perception.dataset_segmenter import DatasetSegmenter, MaskNoise

    p = config.perception
    noise = MaskNoise(seed=p.noise_seed) if p.noise == "noisy" else None
    return DatasetSegmenter(p.min_mask_pixels, p.min_mask_fraction, p.mask_erosion_px, noise=noise)


def _classical(config: Config) -> Segmenter:
    from inherit_sg.perception.classical_segmenter import ClassicalSegmenter

    p = config.perception
    # Unlabelled fragments are noisier than dataset masks: keep a higher size floor.
    return ClassicalSegmenter(p.min_mask_pixels, max(p.min_mask_fraction, 0.0005))


def _auto(config: Config) -> Segmenter:
    from inherit_sg.perception.auto_segmenter import AutoSegmenter

    return AutoSegmenter(_dataset(config), _classical(config))


def _sam3(config: Config) -> Segmenter:
    from inherit_sg.perception.sam3 import Sam3Segmenter

    return Sam3Segmenter.from_config(config)


def _descriptor(config: Config) -> VisualEncoder:
    from inherit_sg.perception.descriptor import DescriptorEncoder

    return DescriptorEncoder(config.store.visual_dim, config.store.image_feature_dim)


def _dinov3(config: Config) -> VisualEncoder:
    from inherit_sg.perception.dinov3 import DinoV3Encoder

    return DinoV3Encoder.from_config(config)


def _onnx(config: Config) -> VisualEncoder:
    from inherit_sg.perception.onnx_encoder import OnnxEncoder

    return OnnxEncoder.from_config(config)


def _offline(config: Config) -> Describer:
    from inherit_sg.perception.describer import TemplateDescriber

    return TemplateDescriber()


def _vlm(config: Config) -> Describer:
    from inherit_sg.perception.vlm_describer import VlmDescriber

    return VlmDescriber.from_config(config)


def _vlm_or_offline(config: Config) -> Describer:
    from inherit_sg.perception.describer import FallbackDescriber, TemplateDescriber

    return FallbackDescriber(_vlm(config), TemplateDescriber())


SEGMENTERS: Registry[Segmenter] = Registry("segmenter")
VISUAL_ENCODERS: Registry[VisualEncoder] = Registry("visual encoder")
DESCRIBERS: Registry[Describer] = Registry("describer")

SEGMENTERS.register("auto", _auto)
SEGMENTERS.register("dataset", _dataset)
SEGMENTERS.register("classical", _classical)
SEGMENTERS.register("sam3", _sam3)
VISUAL_ENCODERS.register("descriptor", _descriptor)
VISUAL_ENCODERS.register("dinov3", _dinov3)
VISUAL_ENCODERS.register("onnx", _onnx)
DESCRIBERS.register("offline", _offline)
DESCRIBERS.register("vlm", _vlm)
DESCRIBERS.register("vlm+offline", _vlm_or_offline)


def register_segmenter(name: str, factory: Factory[Segmenter], *, replace: bool = False) -> None:
    """Make a segmenter available as ``perception.segmenter = name``."""
    SEGMENTERS.register(name, factory, replace=replace)


def register_visual_encoder(
    name: str, factory: Factory[VisualEncoder], *, replace: bool = False
) -> None:
    """Make a visual encoder available as ``perception.visual_encoder = name``."""
    VISUAL_ENCODERS.register(name, factory, replace=replace)


def register_describer(name: str, factory: Factory[Describer], *, replace: bool = False) -> None:
    """Make a describer available as ``perception.describer = name``."""
    DESCRIBERS.register(name, factory, replace=replace)


def create_segmenter(config: Config | None = None) -> Segmenter:
    """The segmenter named by ``config.perception.segmenter``."""
    cfg = config or Config()
    return SEGMENTERS.create(cfg.perception.segmenter, cfg)


def create_visual_encoder(config: Config | None = None) -> VisualEncoder:
    """The visual encoder named by ``config.perception.visual_encoder``."""
    cfg = config or Config()
    return VISUAL_ENCODERS.create(cfg.perception.visual_encoder, cfg)


def create_describer(config: Config | None = None) -> Describer:
    """The describer named by ``config.perception.describer``."""
    cfg = config or Config()
    return DESCRIBERS.create(cfg.perception.describer, cfg)
