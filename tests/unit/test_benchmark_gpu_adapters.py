"""The GPU adapters section of the benchmark page renders what bench/gpu_adapters.py wrote."""

from __future__ import annotations

from inherit_sg.benchmark.gpu_adapters import gpu_adapters_section
from inherit_sg.benchmark.page import render_page


def _timing(p50: float) -> dict[str, float]:
    return {"p50_ms": p50, "p95_ms": p50 * 1.5, "n": 20}


DOC = {
    "device_name": "NVIDIA H100 80GB HBM3",
    "torch": "2.11.0+cu130",
    "transformers": "5.17.0",
    "frames": {"count": 6, "width": 640, "height": 480},
    "iters": 20,
    "warmup": 3,
    "models": {
        "dinov3_vits16": {
            "params": 21_596_544,
            "masks_per_frame": 11.5,
            "weights_mb": 83.0,
            "peak_mb": 250.4,
            "encode_masks": _timing(4.0),
            "encode_image": _timing(2.0),
            "per_frame": _timing(6.0),
            "checks": {"ok": True},
        },
        "sam3": {
            "params": 840_376_374,
            "weights_mb": 3210.0,
            "peak_mb": 9000.0,
            "detections_per_frame_with_masks": 7.0,
            "segment_1_prompt": _timing(80.0),
            "segment_vocabulary_no_detections": _timing(300.0),
            "segment_vocabulary_with_masks": _timing(320.0),
            "checks": {"ok": False},
        },
    },
    "errors": {"dinov3_vitb16": "Traceback ..."},
}


def test_rows_per_call_with_memory_and_checks() -> None:
    page = gpu_adapters_section(DOC)
    assert page.startswith("NVIDIA H100 80GB HBM3, torch 2.11.0+cu130, transformers 5.17.0")
    assert (
        "| DINOv3 ViT-S/16 | 21.6 M | encode the whole image (CLS, 224×304) | 2.0 | 3.0 |" in page
    )
    assert "both, per keyframe, 11.5 masks / frame | 6.0 | 9.0 | 83 MB | 250 MB | ok |" in page
    assert "masks kept, 7.0 detections / frame | 320.0 | 480.0 | 3210 MB | 9000 MB | FAILED |" in (
        page
    )
    assert page.endswith("Failed: DINOv3 ViT-B/16.")
    assert gpu_adapters_section(None) == ""
    assert gpu_adapters_section({"models": {}}) == ""


def test_page_has_the_section_only_when_the_results_exist() -> None:
    with_gpu = render_page([], None, {}, request_sets={"gpu_adapters": DOC})
    assert "## Model adapters on a GPU" in with_gpu and "random-init" in with_gpu
    assert "## Model adapters on a GPU" not in render_page([], None, {}, request_sets={})
