"""Backend registries: defaults, unknown names, registration, lazy heavy imports."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Sequence

import numpy as np
import pytest

from inherit_sg.config import Config, PerceptionConfig
from inherit_sg.errors import ModelUnavailableError
from inherit_sg.model import Frame
from inherit_sg.perception import (
    SEGMENTERS,
    Detection,
    Segmenter,
    VisualEncoder,
    create_describer,
    create_segmenter,
    create_visual_encoder,
    register_segmenter,
)
from inherit_sg.perception.auto_segmenter import AutoSegmenter
from inherit_sg.perception.classical_segmenter import ClassicalSegmenter
from inherit_sg.perception.dataset_segmenter import DatasetSegmenter
from inherit_sg.perception.describer import FallbackDescriber, TemplateDescriber
from inherit_sg.perception.descriptor import DescriptorEncoder
from inherit_sg.perception.registry import Registry


def _config(**perception: object) -> Config:
    return Config(perception=PerceptionConfig(**perception))


def test_defaults_build_the_offline_backends() -> None:
    cfg = Config()
    seg = create_segmenter(cfg)
    enc = create_visual_encoder(cfg)
    assert isinstance(seg, AutoSegmenter) and isinstance(seg, Segmenter)
    assert isinstance(seg.with_masks, DatasetSegmenter)
    assert isinstance(seg.without_masks, ClassicalSegmenter)
    assert isinstance(enc, DescriptorEncoder) and isinstance(enc, VisualEncoder)
    assert enc.dim == cfg.store.visual_dim and enc.image_dim == cfg.store.image_feature_dim
    assert isinstance(create_describer(cfg), TemplateDescriber)
    assert isinstance(create_segmenter(_config(segmenter="classical")), ClassicalSegmenter)


def test_unknown_name_lists_known_names() -> None:
    with pytest.raises(ModelUnavailableError) as err:
        create_segmenter(_config(segmenter="mask-rcnn"))
    msg = str(err.value)
    assert "mask-rcnn" in msg and "dataset" in msg and "classical" in msg and "sam3" in msg
    with pytest.raises(ModelUnavailableError, match="descriptor"):
        create_visual_encoder(_config(visual_encoder="clip"))


def test_model_adapters_without_model_dir_fail_clearly(tmp_path) -> None:
    with pytest.raises(ModelUnavailableError, match="model_dir"):
        create_segmenter(_config(segmenter="sam3"))
    with pytest.raises(ModelUnavailableError, match="dinov3"):
        create_visual_encoder(_config(visual_encoder="dinov3", model_dir=str(tmp_path)))
    with pytest.raises(ModelUnavailableError, match=r"visual_encoder\.onnx"):
        create_visual_encoder(_config(visual_encoder="onnx", model_dir=str(tmp_path)))


def test_vlm_describer_without_endpoint_is_unavailable() -> None:
    with pytest.raises(ModelUnavailableError, match="endpoint"):
        create_describer(_config(describer="vlm"))


def test_register_more_backends() -> None:
    class Everything:
        name = "everything"

        def segment(self, frame: Frame, prompts: Sequence[str] | None = None) -> list[Detection]:
            h, w = frame.depth.shape[:2]
            mask = np.ones((h, w), dtype=bool)
            return [Detection(mask, "scene", 1.0, (0, 0, w - 1, h - 1))]

    name = "test-everything"
    register_segmenter(name, lambda cfg: Everything())
    try:
        assert name in SEGMENTERS.names()
        assert create_segmenter(_config(segmenter=name)).name == "everything"
        with pytest.raises(ValueError, match="already registered"):
            register_segmenter(name, lambda cfg: Everything())
        register_segmenter(name, lambda cfg: Everything(), replace=True)
    finally:
        SEGMENTERS._factories.pop(name, None)


def test_registry_names_are_case_insensitive() -> None:
    reg: Registry[str] = Registry("thing")
    reg.register("Alpha", lambda cfg: "a")
    assert reg.names() == ["alpha"]
    assert reg.create(" ALPHA ") == "a"


def test_fallback_describer_from_registry_wraps_offline(tmp_path) -> None:
    cfg = Config.model_validate(
        {"perception": {"describer": "vlm+offline"}, "llm": {"endpoint": "http://127.0.0.1:9/v1"}}
    )
    desc = create_describer(cfg)
    assert isinstance(desc, FallbackDescriber)
    assert isinstance(desc.fallback, TemplateDescriber)


def test_offline_modules_do_not_import_heavy_libraries() -> None:
    code = (
        "import sys\n"
        "import inherit_sg.perception, inherit_sg.perception.registry\n"
        "import inherit_sg.perception.dataset_segmenter, inherit_sg.perception.descriptor\n"
        "import inherit_sg.perception.classical_segmenter, inherit_sg.perception.describer\n"
        "from inherit_sg.perception import create_visual_encoder, create_segmenter\n"
        "create_visual_encoder(); create_segmenter()\n"
        "heavy = [m for m in ('torch', 'transformers', 'onnxruntime', 'sentence_transformers')"
        " if m in sys.modules]\n"
        "print(','.join(heavy))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
