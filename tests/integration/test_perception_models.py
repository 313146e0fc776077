"""Model adapters on real (tiny, random-init) models saved to tmp dirs: SAM3 and
DINOv3 through transformers, an ONNX encoder through onnxruntime.

The torch adapters run on the CPU unless ``INHERIT_SG_PERCEPTION__DEVICE`` (the
``perception.device`` setting's own variable) names another device, e.g. ``cuda``."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

from inherit_sg.config import Config, PerceptionConfig
from inherit_sg.errors import ModelUnavailableError
from inherit_sg.model import Frame
from inherit_sg.perception import create_segmenter, create_visual_encoder
from inherit_sg.perception.base import mask_bbox
from inherit_sg.perception.preprocess import IMAGENET_MEAN, IMAGENET_STD
from tests.toy_scene import ToyBox, look_at, render_toy_frame, toy_intrinsics

torch = pytest.importorskip("torch")
transformers = pytest.importorskip("transformers")

DEVICE = os.environ.get("INHERIT_SG_PERCEPTION__DEVICE", "cpu")

BOXES = [
    ToyBox("chair", (-0.6, 2.0, 0.45), (0.5, 0.5, 0.9), (190, 40, 40)),
    ToyBox("cabinet", (0.7, 2.4, 0.6), (0.9, 0.45, 1.2), (45, 80, 185)),
]


@pytest.fixture(scope="module")
def frame() -> Frame:
    pose = look_at((0.0, -0.8, 1.4), (0.0, 2.5, 0.5))
    return render_toy_frame(BOXES, pose, toy_intrinsics(64, 64))


def _masks(frame: Frame) -> list[np.ndarray]:
    assert frame.instances is not None
    return [frame.instances == 1, frame.instances == 2]


# --------------------------------------------------------------------------- SAM3


def _tiny_sam3(path: Path) -> None:
    torch.manual_seed(0)
    small = {"num_attention_heads": 2, "intermediate_size": 64}
    cfg = transformers.Sam3Config(
        vision_config={
            "backbone_config": {
                "model_type": "sam3_vit_model",
                "hidden_size": 32,
                "num_hidden_layers": 2,
                "image_size": 56,
                "patch_size": 14,
                "window_size": 2,
                "global_attn_indexes": [1],
                "pretrain_image_size": 56,
                **small,
            },
            "fpn_hidden_size": 32,
            "backbone_feature_sizes": [[16, 16], [8, 8], [4, 4]],
        },
        text_config={
            "vocab_size": 64,
            "hidden_size": 32,
            "projection_dim": 32,
            "num_hidden_layers": 1,
            "max_position_embeddings": 32,
            "bos_token_id": 0,
            "eos_token_id": 1,
            "pad_token_id": 1,
            **small,
        },
        geometry_encoder_config={"hidden_size": 32, "num_layers": 1, **small},
        detr_encoder_config={"hidden_size": 32, "num_layers": 1, **small},
        detr_decoder_config={"hidden_size": 32, "num_layers": 1, "num_queries": 6, **small},
        mask_decoder_config={"hidden_size": 32, "num_attention_heads": 2},
    )
    transformers.Sam3Model(cfg).save_pretrained(path)
    vocab = {"<|startoftext|>": 0, "<|endoftext|>": 1}
    for c in "abcdefghijklmnopqrstuvwxyz":
        vocab[c] = len(vocab)
        vocab[c + "</w>"] = len(vocab)
    transformers.CLIPTokenizer(vocab=vocab, merges=[]).save_pretrained(path)
    processor = {
        "size": {"height": 56, "width": 56},
        "image_mean": [0.5] * 3,
        "image_std": [0.5] * 3,
    }
    (path / "processor_config.json").write_text(json.dumps({"image_processor": processor}))


@pytest.fixture(scope="module")
def model_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("models")
    _tiny_sam3(root / "sam3")
    _tiny_dinov3(root / "dinov3")
    return root


def _config(model_dir: Path, **perception: object) -> Config:
    perception.setdefault("device", DEVICE)
    return Config(perception=PerceptionConfig(model_dir=str(model_dir), **perception))


def test_sam3_prompts_flow_through_to_labels(model_dir: Path, frame: Frame) -> None:
    seg = create_segmenter(_config(model_dir, segmenter="sam3", score_threshold=0.0))
    assert seg.name == "sam3"
    prompts = ["chair", "red box", "lamp"]
    dets = seg.segment(frame, prompts)
    assert dets, "threshold 0 keeps every query that has a non-empty mask"
    assert {d.label for d in dets} <= set(prompts)
    for d in dets:
        assert d.mask.shape == (64, 64) and d.mask.dtype == bool
        assert d.bbox_xyxy == mask_bbox(d.mask)
        assert 0.0 <= d.score <= 1.0
    assert [d.score for d in dets] == sorted((d.score for d in dets), reverse=True)


def test_sam3_thresholds_and_vocabulary(model_dir: Path, frame: Frame) -> None:
    strict = create_segmenter(_config(model_dir, segmenter="sam3", score_threshold=1.0))
    assert strict.segment(frame, ["chair"]) == []
    vocab = ["mug", "kettle"]
    seg = create_segmenter(_config(model_dir, segmenter="sam3", score_threshold=0.0, prompts=vocab))
    dets = seg.segment(frame)  # no prompts: the configured vocabulary
    assert dets and {d.label for d in dets} <= set(vocab)


def test_sam3_missing_directory_is_unavailable(tmp_path: Path) -> None:
    from inherit_sg.perception.sam3 import Sam3Segmenter

    with pytest.raises(ModelUnavailableError, match=r"config\.json"):
        Sam3Segmenter(tmp_path)


# ------------------------------------------------------------------------- DINOv3


def _tiny_dinov3(path: Path) -> None:
    torch.manual_seed(0)
    cfg = transformers.DINOv3ViTConfig(
        patch_size=8,
        hidden_size=32,
        intermediate_size=64,
        num_hidden_layers=2,
        num_attention_heads=2,
        image_size=32,
        num_register_tokens=2,
    )
    transformers.DINOv3ViTModel(cfg).save_pretrained(path)


def test_dinov3_features(model_dir: Path, frame: Frame) -> None:
    enc = create_visual_encoder(_config(model_dir, visual_encoder="dinov3", encoder_input_size=32))
    assert enc.name == "dinov3" and enc.dim == 32 and enc.image_dim == 32
    feats = enc.encode(frame.rgb, _masks(frame))
    assert feats.shape == (2, 32) and feats.dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(feats, axis=1), 1.0, rtol=1e-5)
    assert float(feats[0] @ feats[1]) < 0.9999  # different crops, different features
    g = enc.encode_image(frame.rgb)
    assert g.shape == (32,) and np.linalg.norm(g) == pytest.approx(1.0, rel=1e-5)
    one = enc.encode(frame.rgb, _masks(frame)[1:])
    np.testing.assert_allclose(one[0], feats[1], atol=1e-5)  # batching does not matter


def test_dinov3_ignores_pixels_outside_the_mask(model_dir: Path, frame: Frame) -> None:
    enc = create_visual_encoder(_config(model_dir, visual_encoder="dinov3", encoder_input_size=32))
    mask = _masks(frame)[0]
    other = frame.rgb.copy()
    other[~mask] = np.random.default_rng(0).integers(0, 255, (int((~mask).sum()), 3))
    np.testing.assert_allclose(enc.encode(frame.rgb, [mask]), enc.encode(other, [mask]), atol=1e-5)
    assert float(enc.encode_image(frame.rgb) @ enc.encode_image(other)) < 0.9999


def test_dinov3_cls_pooling(model_dir: Path, frame: Frame) -> None:
    from inherit_sg.perception.dinov3 import DinoV3Encoder

    cls = DinoV3Encoder(model_dir / "dinov3", input_size=32, pooling="cls", device=DEVICE)
    mask = DinoV3Encoder(model_dir / "dinov3", input_size=32, pooling="mask", device=DEVICE)
    a, b = cls.encode(frame.rgb, _masks(frame)), mask.encode(frame.rgb, _masks(frame))
    assert a.shape == b.shape and not np.allclose(a, b)


# --------------------------------------------------------------------------- ONNX


def _onnx_model(path: Path, *, static: bool, kind: str) -> None:
    """A real ONNX graph. ``kind="conv"``: conv → relu → global pool → flatten → gemm
    (N, 16); ``kind="mean"``: per-channel global average (N, 3, 1, 1) — an exact
    reference for checking the preprocessing."""
    onnx = pytest.importorskip("onnx")
    from onnx import TensorProto, helper, numpy_helper

    rng = np.random.default_rng(0)
    hw: list[int | str] = [32, 32] if static else ["H", "W"]
    x = helper.make_tensor_value_info("pixel_values", TensorProto.FLOAT, ["N", 3, *hw])
    if kind == "mean":
        nodes = [helper.make_node("GlobalAveragePool", ["pixel_values"], ["features"])]
        inits = []
        y = helper.make_tensor_value_info("features", TensorProto.FLOAT, ["N", 3, 1, 1])
    else:
        w = numpy_helper.from_array(rng.normal(size=(8, 3, 3, 3)).astype(np.float32), "w")
        fc = numpy_helper.from_array(rng.normal(size=(16, 8)).astype(np.float32), "fc")
        bias = numpy_helper.from_array(rng.normal(size=(16,)).astype(np.float32), "b")
        nodes = [
            helper.make_node("Conv", ["pixel_values", "w"], ["c"], strides=[2, 2]),
            helper.make_node("Relu", ["c"], ["r"]),
            helper.make_node("GlobalAveragePool", ["r"], ["p"]),
            helper.make_node("Flatten", ["p"], ["f"]),
            helper.make_node("Gemm", ["f", "fc", "b"], ["features"], transB=1),
        ]
        inits = [w, fc, bias]
        y = helper.make_tensor_value_info("features", TensorProto.FLOAT, ["N", 16])
    graph = helper.make_graph(nodes, "encoder", [x], [y], initializer=inits)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    onnx.checker.check_model(model)
    onnx.save(model, str(path))


def test_onnx_encoder_features(tmp_path: Path, frame: Frame) -> None:
    _onnx_model(tmp_path / "visual_encoder.onnx", static=True, kind="conv")
    enc = create_visual_encoder(_config(tmp_path, visual_encoder="onnx"))
    assert enc.name == "onnx" and enc.dim == 16
    feats = enc.encode(frame.rgb, _masks(frame))
    assert feats.shape == (2, 16) and feats.dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(feats, axis=1), 1.0, rtol=1e-5)
    assert not np.allclose(feats[0], feats[1])
    assert enc.encode_image(frame.rgb).shape == (16,)
    assert enc.encode(frame.rgb, []).shape == (0, 16)


def test_onnx_preprocessing_matches_reference(tmp_path: Path) -> None:
    path = tmp_path / "mean.onnx"
    _onnx_model(path, static=False, kind="mean")
    (tmp_path / "mean.json").write_text(json.dumps({"size": 24}))
    enc = create_visual_encoder(
        Config(perception=PerceptionConfig(visual_encoder="onnx", onnx_path=str(path)))
    )
    assert enc.dim == 3  # (N, 3, 1, 1) feature maps are pooled to (N, 3)
    rgb = np.zeros((40, 60, 3), dtype=np.uint8)
    rgb[:] = (200, 100, 30)
    expected = (np.array([200, 100, 30]) / 255.0 - IMAGENET_MEAN) / IMAGENET_STD
    expected /= np.linalg.norm(expected)
    np.testing.assert_allclose(enc.encode_image(rgb), expected, atol=1e-5)
    mask = np.zeros((40, 60), dtype=bool)
    mask[10:20, 10:30] = True
    rgb[~mask] = (0, 255, 0)  # outside the mask: replaced by the mean, i.e. ~zero
    # (the fill colour is quantised to uint8, hence the looser tolerance)
    np.testing.assert_allclose(enc.encode(rgb, [mask])[0], expected, atol=0.01)


def test_onnx_missing_file(tmp_path: Path) -> None:
    from inherit_sg.perception.onnx_encoder import OnnxEncoder

    with pytest.raises(ModelUnavailableError, match="does not exist"):
        OnnxEncoder(tmp_path / "none.onnx")
    (tmp_path / "bad.onnx").write_bytes(b"not a model")
    with pytest.raises(ModelUnavailableError, match="cannot load"):
        OnnxEncoder(tmp_path / "bad.onnx")
