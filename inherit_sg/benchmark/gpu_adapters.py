"""The GPU section of the benchmark page: the DINOv3 and SAM3 adapters on random-init
models of the official sizes (``bench/gpu_adapters.py``)."""

from __future__ import annotations

from typing import Any

from inherit_sg.benchmark.tables import num, table

_NAMES = {
    "dinov3_vits16": "DINOv3 ViT-S/16",
    "dinov3_vitb16": "DINOv3 ViT-B/16",
    "sam3": "SAM3",
}
_CALLS = {
    "encode_masks": "encode every instance mask (one batch of 224² crops)",
    "encode_image": "encode the whole image (CLS, 224×304)",
    "per_frame": "both, per keyframe",
    "segment_1_prompt": "segment, 1 prompt",
    "segment_vocabulary_no_detections": "segment, 50-prompt vocabulary, nothing kept",
    "segment_vocabulary_with_masks": "segment, 50-prompt vocabulary, masks kept",
}


def _mb(value: Any) -> str:
    return "–" if value is None else f"{num(value, 0)} MB"


def gpu_adapters_section(doc: dict[str, Any] | None) -> str:
    """What ran where, then one row per timed call: p50 / p95 latency, the model's
    parameters, weights on the device, peak device memory and its checks."""
    if not doc or not doc.get("models"):
        return ""
    frames = doc.get("frames", {})
    lines = [
        f"{doc.get('device_name', doc.get('device', '?'))}, torch {doc.get('torch', '?')}, "
        f"transformers {doc.get('transformers', '?')}, float32; "
        f"{frames.get('count', '?')} rendered {frames.get('width', '?')}×"
        f"{frames.get('height', '?')} frames taken in turn, {doc.get('warmup', '?')} "
        f"warm-up calls then {doc.get('iters', '?')} timed calls per row."
    ]
    rows = []
    for key, model in doc["models"].items():
        name = _NAMES.get(key, key)
        checks = model.get("checks", {})
        extra = ""
        if key == "sam3":
            extra = f", {num(model.get('detections_per_frame_with_masks'), 1)} detections / frame"
        elif "masks_per_frame" in model:
            extra = f", {num(model['masks_per_frame'], 1)} masks / frame"
        for call, what in _CALLS.items():
            t = model.get(call)
            if not isinstance(t, dict):
                continue
            rows.append(
                [
                    name,
                    f"{num(model.get('params', 0) / 1e6, 1)} M",
                    what
                    + (extra if call in ("per_frame", "segment_vocabulary_with_masks") else ""),
                    num(t.get("p50_ms"), 1),
                    num(t.get("p95_ms"), 1),
                    _mb(model.get("weights_mb")),
                    _mb(model.get("peak_mb")),
                    "ok" if checks.get("ok") else "FAILED",
                ]
            )
    head = ["model", "params", "call", "p50 ms", "p95 ms", "weights", "peak memory", "checks"]
    parts = [" ".join(lines), table(head, rows)]
    errors = doc.get("errors") or {}
    if errors:
        parts.append("Failed: " + ", ".join(_NAMES.get(k, k) for k in sorted(errors)) + ".")
    return "\n\n".join(parts)
