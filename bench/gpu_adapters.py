"""Speed, memory and plumbing of the DINOv3 and SAM3 adapters on a GPU (or the CPU).

No pretrained weights are available, so the models are random-init with the official
sizes: DINOv3 ViT-S/16 and ViT-B/16 (384/768 wide, 12 layers, 4 register tokens) and
SAM3 at ``transformers.Sam3Config()``'s defaults (ViT-L/14 1008 px vision backbone,
24-layer CLIP text encoder, 200 DETR queries). Each is saved with ``save_pretrained`` to
a temp dir (SAM3 with a CLIP tokenizer built offline) and loaded through the project's
own adapters (:class:`DinoV3Encoder`, :class:`Sam3Segmenter`) on ``--device``; then they
run on 640x480 frames of the toy renderer (``tests/toy_scene.py``). Only latency, GPU
memory and the shape / finiteness / norm of the outputs mean anything here: random
weights say nothing about accuracy.

Per frame: DINOv3 encodes every ground-truth instance mask (one batch) and the whole
image; SAM3 segments with one prompt, with the default 50-prompt vocabulary and no
detection kept (model cost), and with the vocabulary at a score threshold calibrated
so that about ``--sam3-keep`` queries pass (adds mask upsampling and suppression).
Latency is wall time with ``torch.cuda.synchronize()`` after each call, after
``--warmup`` calls, over ``--iters`` calls (p50 / p95). The JSON is rewritten after
every model, so a failure further on leaves the earlier results.

    python bench/gpu_adapters.py --device cuda [--out bench/results/gpu_adapters.json]
    python bench/gpu_adapters.py --device cpu --small   # tiny configs, a smoke test
    python bench/gpu_adapters.py --save-frames frames.npz  # render once, reuse with --frames
"""

from __future__ import annotations

import argparse
import datetime as dt
import gc
import json
import platform
import sys
import tempfile
import time
import traceback
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the toy renderer is a test helper (tests/toy_scene.py)

from inherit_sg.model import Frame  # noqa: E402
from inherit_sg.perception.dinov3 import DinoV3Encoder  # noqa: E402
from inherit_sg.perception.sam3 import DEFAULT_PROMPTS, Sam3Segmenter  # noqa: E402

WIDTH, HEIGHT = 640, 480
MODELS = ("dinov3_vits16", "dinov3_vitb16", "sam3")

# Official DINOv3 sizes (facebook/dinov3-vit{s,b}16-pretrain-lvd1689m); the rest of the
# architecture is DINOv3ViTConfig's defaults (patch 16, RoPE theta 100, plain MLP).
DINOV3_SIZES: dict[str, dict[str, Any]] = {
    "dinov3_vits16": {
        "hidden_size": 384,
        "intermediate_size": 1536,
        "num_hidden_layers": 12,
        "num_attention_heads": 6,
    },
    "dinov3_vitb16": {
        "hidden_size": 768,
        "intermediate_size": 3072,
        "num_hidden_layers": 12,
        "num_attention_heads": 12,
    },
}
DINOV3_COMMON: dict[str, Any] = {
    "patch_size": 16,
    "image_size": 224,
    "num_register_tokens": 4,
    "layerscale_value": 1e-5,
}
DINOV3_SMALL: dict[str, Any] = {
    "patch_size": 8,
    "hidden_size": 32,
    "intermediate_size": 64,
    "num_hidden_layers": 2,
    "num_attention_heads": 2,
    "image_size": 32,
    "num_register_tokens": 2,
}
# Official SAM3 sizes, as Sam3Config() gives them; asserted after building the config.
SAM3_EXPECTED = {
    "vision_hidden_size": 1024,
    "vision_layers": 32,
    "image_size": 1008,
    "text_hidden_size": 1024,
    "text_layers": 24,
    "num_queries": 200,
}
CLIP_BOS, CLIP_EOS = 49406, 49407  # CLIP's <|startoftext|> / <|endoftext|> ids


class CudaUnavailableError(RuntimeError):
    """A CUDA device was asked for but torch sees none."""


# ------------------------------------------------------------------------- frames


def render_frames(count: int) -> list[Frame]:
    """``count`` 640x480 frames of a toy room with a dozen boxes, camera sweeping."""
    from tests.toy_scene import ToyBox, look_at, render_toy_frame, toy_intrinsics

    rng = np.random.default_rng(0)
    boxes = []
    for i in range(12):
        size = (0.3 + 0.4 * rng.random(), 0.3 + 0.3 * rng.random(), 0.3 + 0.9 * rng.random())
        r, g, b = (int(c) for c in rng.integers(20, 240, 3))
        centre = (-2.2 + 0.4 * i, 1.5 + 1.5 * rng.random(), size[2] / 2)
        boxes.append(
            ToyBox(f"obj{i}", centre, size, (r, g, b), yaw=float(rng.random()), pattern=0.1)
        )
    frames = []
    for i in range(count):
        x = -1.0 + 2.0 * i / max(1, count - 1)
        pose = look_at((x, -1.0, 1.5), (0.3 * x, 2.5, 0.4))
        frames.append(
            render_toy_frame(
                boxes,
                pose,
                toy_intrinsics(WIDTH, HEIGHT),
                rgb_noise=2.0,
                depth_noise=0.002,
                seed=i,
                index=i,
            )
        )
    return frames


def save_frames(frames: Sequence[Frame], path: Path) -> None:
    """rgb, depth and instance images of ``frames`` in one compressed npz."""
    np.savez_compressed(
        path,
        rgb=np.stack([f.rgb for f in frames]),
        depth=np.stack([f.depth for f in frames]),
        instances=np.stack([f.instances for f in frames if f.instances is not None]),
    )


def load_frames(path: Path) -> list[Frame]:
    """Frames saved by :func:`save_frames` (identity poses: the adapters need none)."""
    from inherit_sg.model import Pose
    from tests.toy_scene import toy_intrinsics

    data = np.load(path)
    h, w = data["rgb"].shape[1:3]
    k = toy_intrinsics(w, h)
    return [
        Frame(
            index=i,
            frame_id=f"toy{i:04d}",
            timestamp=float(i),
            rgb=data["rgb"][i],
            depth=data["depth"][i],
            pose=Pose.from_matrix(np.eye(4)),
            intrinsics=k,
            instances=data["instances"][i],
        ).validate()
        for i in range(len(data["rgb"]))
    ]


def instance_masks(frame: Frame, min_pixels: int = 50) -> list[np.ndarray]:
    """The frame's ground-truth instance masks with at least ``min_pixels`` pixels."""
    assert frame.instances is not None
    ids = [int(i) for i in np.unique(frame.instances) if i != 0]
    masks = [frame.instances == i for i in ids]
    return [m for m in masks if int(m.sum()) >= min_pixels]


# ------------------------------------------------------------------------- timing


class Bench:
    """Device handling and timing helpers around one torch device."""

    def __init__(self, torch: Any, device: str, iters: int, warmup: int) -> None:
        self.torch = torch
        self.device = device
        self.cuda = device.startswith("cuda")
        self.iters = iters
        self.warmup = warmup

    def sync(self) -> None:
        if self.cuda:
            self.torch.cuda.synchronize()

    def reset_peak(self) -> None:
        if self.cuda:
            self.sync()
            self.torch.cuda.reset_peak_memory_stats()

    def allocated_mb(self) -> float | None:
        return self.torch.cuda.memory_allocated() / 2**20 if self.cuda else None

    def peak_mb(self) -> float | None:
        return self.torch.cuda.max_memory_allocated() / 2**20 if self.cuda else None

    def release(self) -> None:
        gc.collect()
        if self.cuda:
            self.torch.cuda.empty_cache()

    def time(self, fn: Callable[[Frame], Any], frames: Sequence[Frame]) -> dict[str, Any]:
        """Latency of ``fn`` per frame (ms): p50 / p95 / mean / min / max over ``iters``
        calls after ``warmup`` calls, frames taken in turn."""
        for i in range(self.warmup):
            fn(frames[i % len(frames)])
        self.sync()
        runs = []
        for i in range(self.iters):
            frame = frames[i % len(frames)]
            t0 = time.perf_counter()
            fn(frame)
            self.sync()
            runs.append(1000.0 * (time.perf_counter() - t0))
        a = np.asarray(runs)
        return {
            "p50_ms": round(float(np.percentile(a, 50)), 3),
            "p95_ms": round(float(np.percentile(a, 95)), 3),
            "mean_ms": round(float(a.mean()), 3),
            "min_ms": round(float(a.min()), 3),
            "max_ms": round(float(a.max()), 3),
            "n": len(runs),
        }


def build_on_device(bench: Bench, build: Callable[[], Any]) -> Any:
    """Random init directly on the device when it can (much faster on a GPU)."""
    if bench.cuda:
        try:
            with bench.torch.device(bench.device):
                return build()
        except Exception as exc:
            print(f"  device init failed ({exc!r}); initialising on the CPU", flush=True)
    return build()


def count_params(model: Any) -> int:
    return int(sum(p.numel() for p in model.parameters()))


# ------------------------------------------------------------------------- DINOv3


def bench_dinov3(
    bench: Bench, name: str, small: bool, frames: Sequence[Frame], tmp: Path
) -> dict[str, Any]:
    import transformers

    torch = bench.torch
    sizes = DINOV3_SMALL if small else {**DINOV3_COMMON, **DINOV3_SIZES[name]}
    path = tmp / name
    t0 = time.perf_counter()
    torch.manual_seed(0)
    model = build_on_device(
        bench, lambda: transformers.DINOv3ViTModel(transformers.DINOv3ViTConfig(**sizes))
    )
    params = count_params(model)
    model.to("cpu").save_pretrained(path)  # safetensors writes from host memory
    mean, std = [0.485, 0.456, 0.406], [0.229, 0.224, 0.225]
    (path / "preprocessor_config.json").write_text(
        json.dumps({"image_mean": mean, "image_std": std, "size": {"height": 224, "width": 224}})
    )
    del model
    bench.release()
    create_s = time.perf_counter() - t0

    input_size = int(sizes["image_size"])
    bench.reset_peak()
    t0 = time.perf_counter()
    enc = DinoV3Encoder(path, input_size=input_size, device=bench.device)
    bench.sync()
    load_s = time.perf_counter() - t0
    weights_mb = bench.allocated_mb()
    bench.reset_peak()

    masks = {f.frame_id: instance_masks(f) for f in frames}
    frame = frames[0]
    feats = enc.encode(frame.rgb, masks[frame.frame_id])
    one = enc.encode(frame.rgb, masks[frame.frame_id][-1:])
    image = enc.encode_image(frame.rgb)
    norms = np.linalg.norm(feats, axis=1)
    gram = feats @ feats.T
    off_diag = gram[~np.eye(len(feats), dtype=bool)]
    checks = {
        "masks_shape": list(feats.shape),
        "masks_shape_ok": feats.shape == (len(masks[frame.frame_id]), enc.dim),
        "image_shape_ok": image.shape == (enc.dim,),
        "finite": bool(np.isfinite(feats).all() and np.isfinite(image).all()),
        "norm_min": round(float(norms.min()), 6),
        "norm_max": round(float(norms.max()), 6),
        "norms_ok": bool(np.allclose(norms, 1.0, atol=1e-4))
        and abs(float(np.linalg.norm(image)) - 1.0) < 1e-4,
        "max_cosine_between_masks": round(float(off_diag.max()), 6) if off_diag.size else None,
        "distinct_masks_ok": bool(off_diag.size == 0 or off_diag.max() < 0.99999),
        "batch_vs_single_max_abs_diff": float(np.abs(one[0] - feats[-1]).max()),
        "batch_vs_single_ok": bool(np.abs(one[0] - feats[-1]).max() < 1e-3),
    }
    checks["ok"] = all(v for k, v in checks.items() if k.endswith("_ok") or k == "finite")

    masks_t = bench.time(lambda f: enc.encode(f.rgb, masks[f.frame_id]), frames)
    image_t = bench.time(lambda f: enc.encode_image(f.rgb), frames)
    both_t = bench.time(
        lambda f: (enc.encode(f.rgb, masks[f.frame_id]), enc.encode_image(f.rgb)), frames
    )
    peak_mb = bench.peak_mb()
    result = {
        "config": sizes,
        "params": params,
        "dim": enc.dim,
        "input_size": input_size,
        "masks_per_frame": round(float(np.mean([len(m) for m in masks.values()])), 2),
        "create_and_save_s": round(create_s, 2),
        "adapter_load_s": round(load_s, 2),
        "weights_mb": None if weights_mb is None else round(weights_mb, 1),
        "peak_mb": None if peak_mb is None else round(peak_mb, 1),
        "encode_masks": masks_t,
        "encode_image": image_t,
        "per_frame": both_t,
        "checks": checks,
    }
    bench.release()
    return result


# --------------------------------------------------------------------------- SAM3


def sam3_config(transformers: Any, small: bool) -> Any:
    """``Sam3Config()`` (the official sizes), or the tiny one of the tests."""
    if not small:
        cfg = transformers.Sam3Config()
        got = {
            "vision_hidden_size": cfg.vision_config.backbone_config.hidden_size,
            "vision_layers": cfg.vision_config.backbone_config.num_hidden_layers,
            "image_size": cfg.vision_config.backbone_config.image_size,
            "text_hidden_size": cfg.text_config.hidden_size,
            "text_layers": cfg.text_config.num_hidden_layers,
            "num_queries": cfg.detr_decoder_config.num_queries,
        }
        if got != SAM3_EXPECTED:
            raise RuntimeError(f"Sam3Config() is not the official size: {got}")
        return cfg
    small_heads = {"num_attention_heads": 2, "intermediate_size": 64}
    return transformers.Sam3Config(
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
                **small_heads,
            },
            "fpn_hidden_size": 32,
            "backbone_feature_sizes": [[16, 16], [8, 8], [4, 4]],
        },
        text_config={
            "vocab_size": CLIP_EOS + 1,
            "hidden_size": 32,
            "projection_dim": 32,
            "num_hidden_layers": 1,
            "max_position_embeddings": 32,
            "bos_token_id": CLIP_BOS,
            "eos_token_id": CLIP_EOS,
            "pad_token_id": 1,
            **small_heads,
        },
        geometry_encoder_config={"hidden_size": 32, "num_layers": 1, **small_heads},
        detr_encoder_config={"hidden_size": 32, "num_layers": 1, **small_heads},
        detr_decoder_config={"hidden_size": 32, "num_layers": 1, "num_queries": 6, **small_heads},
        mask_decoder_config={"hidden_size": 32, "num_attention_heads": 2},
    )


def save_clip_tokenizer(transformers: Any, path: Path) -> None:
    """A CLIP tokenizer built offline: letters as the vocabulary, the real special-token
    ids. Prompts pad to 32 tokens either way, so the model's cost is the real one."""
    vocab: dict[str, int] = {}
    for c in "abcdefghijklmnopqrstuvwxyz":
        vocab[c] = len(vocab)
        vocab[c + "</w>"] = len(vocab)
    vocab["<|startoftext|>"] = CLIP_BOS
    vocab["<|endoftext|>"] = CLIP_EOS
    transformers.CLIPTokenizer(vocab=vocab, merges=[]).save_pretrained(path)


def bench_sam3(
    bench: Bench, small: bool, frames: Sequence[Frame], tmp: Path, keep: int
) -> dict[str, Any]:
    import transformers

    torch = bench.torch
    cfg = sam3_config(transformers, small)
    size = int(cfg.vision_config.backbone_config.image_size)
    path = tmp / "sam3"
    t0 = time.perf_counter()
    torch.manual_seed(0)
    model = build_on_device(bench, lambda: transformers.Sam3Model(cfg))
    params = count_params(model)
    model.to("cpu").save_pretrained(path)  # safetensors writes from host memory
    save_clip_tokenizer(transformers, path)
    processor = {"size": {"height": size, "width": size}, "image_mean": [0.5] * 3}
    processor["image_std"] = [0.5] * 3
    (path / "processor_config.json").write_text(json.dumps({"image_processor": processor}))
    del model
    bench.release()
    create_s = time.perf_counter() - t0

    bench.reset_peak()
    t0 = time.perf_counter()
    seg = Sam3Segmenter(path, score_threshold=2.0, device=bench.device)
    bench.sync()
    load_s = time.perf_counter() - t0
    weights_mb = bench.allocated_mb()
    bench.reset_peak()
    prompts = list(DEFAULT_PROMPTS)

    # Calibrate: capture the query scores of a full-vocabulary pass on each frame, then
    # pick the threshold that lets at most ``keep`` queries through on any frame (random
    # weights score every query alike; a fixed 0.4 could keep thousands, or none).
    scores: list[Any] = []

    def grab(_module: Any, _inputs: Any, out: Any) -> None:
        s = out.pred_logits.float().sigmoid()
        if out.presence_logits is not None:
            s = s * out.presence_logits.float().sigmoid()
        scores.append(s.flatten().cpu())

    hook = seg._model.register_forward_hook(grab)
    per_frame: list[np.ndarray] = []
    none: list[Any] = []
    try:
        for f in frames:
            scores.clear()
            none.extend(seg.segment(f))
            per_frame.append(torch.cat(scores).numpy())
    finally:
        hook.remove()
    all_scores = np.concatenate(per_frame)
    k = min(keep, per_frame[0].size)
    kth = [float(np.sort(s)[-k]) for s in per_frame]
    best = int(np.argmax(kth))
    threshold = kth[best] - 1e-6
    seg.score_threshold = threshold
    dets = seg.segment(frames[best])
    h, w = frames[best].rgb.shape[:2]
    checks: dict[str, Any] = {
        "no_detection_above_threshold_2_ok": none == [],
        "scores_finite": bool(np.isfinite(all_scores).all()),
        "score_min": round(float(all_scores.min()), 6),
        "score_max": round(float(all_scores.max()), 6),
        "queries_scored_per_frame": int(per_frame[0].size),
        "calibrated_threshold": round(threshold, 6),
        "detections": len(dets),
        "detections_ok": 0 < len(dets) <= keep,
        "masks_ok": all(
            d.mask.shape == (h, w) and d.mask.dtype == bool and d.area > 0 for d in dets
        ),
        "scores_ok": all(0.0 <= d.score <= 1.0 for d in dets)
        and [d.score for d in dets] == sorted((d.score for d in dets), reverse=True),
        "labels_ok": {d.label for d in dets} <= set(prompts),
        "mask_area_median": int(np.median([d.area for d in dets])) if dets else 0,
        "distinct_labels": len({d.label for d in dets}),
    }
    checks["ok"] = all(v for k_, v in checks.items() if k_.endswith("_ok") or k_ == "scores_finite")

    seg.score_threshold = 2.0
    one_t = bench.time(lambda f: seg.segment(f, ["chair"]), frames)
    vocab_t = bench.time(lambda f: seg.segment(f), frames)
    seg.score_threshold = threshold
    found: list[int] = []
    masks_t = bench.time(lambda f: found.append(len(seg.segment(f))), frames)
    peak_mb = bench.peak_mb()
    text = cfg.text_config
    backbone = cfg.vision_config.backbone_config
    result = {
        "config": {
            "image_size": size,
            "vision_hidden_size": backbone.hidden_size,
            "vision_layers": backbone.num_hidden_layers,
            "text_hidden_size": text.hidden_size,
            "text_layers": text.num_hidden_layers,
            "num_queries": cfg.detr_decoder_config.num_queries,
        },
        "params": params,
        "prompts": len(prompts),
        "prompt_batch": 16,
        "create_and_save_s": round(create_s, 2),
        "adapter_load_s": round(load_s, 2),
        "weights_mb": None if weights_mb is None else round(weights_mb, 1),
        "peak_mb": None if peak_mb is None else round(peak_mb, 1),
        "segment_1_prompt": one_t,
        "segment_vocabulary_no_detections": vocab_t,
        "segment_vocabulary_with_masks": masks_t,
        "detections_per_frame_with_masks": round(float(np.mean(found)), 2) if found else 0,
        "checks": checks,
    }
    bench.release()
    return result


# --------------------------------------------------------------------------- main


def environment(torch: Any, device: str) -> dict[str, Any]:
    import transformers

    env: dict[str, Any] = {
        "device": device,
        "python": platform.python_version(),
        "torch": torch.__version__,
        "transformers": transformers.__version__,
        "numpy": np.__version__,
        "cuda_runtime": torch.version.cuda,
        "tf32_matmul": bool(torch.backends.cuda.matmul.allow_tf32),
        "cpu_threads": torch.get_num_threads(),
    }
    if device.startswith("cuda"):
        props = torch.cuda.get_device_properties(torch.device(device))
        env["device_name"] = props.name
        env["device_memory_mb"] = round(props.total_memory / 2**20)
        env["capability"] = f"{props.major}.{props.minor}"
    else:
        env["device_name"] = platform.processor() or platform.machine()
    return env


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--device", default="cuda", help="torch device (cuda, cuda:1, cpu)")
    parser.add_argument("--small", action="store_true", help="tiny configs (smoke test)")
    parser.add_argument("--out", type=Path, default=ROOT / "bench/results/gpu_adapters.json")
    parser.add_argument("--frames", type=Path, default=None, help="npz from --save-frames")
    parser.add_argument("--num-frames", type=int, default=4, help="frames to render")
    parser.add_argument("--save-frames", type=Path, default=None, help="render, save, exit")
    parser.add_argument("--iters", type=int, default=20)
    parser.add_argument("--warmup", type=int, default=3)
    parser.add_argument("--models", default=",".join(MODELS))
    parser.add_argument("--sam3-keep", type=int, default=32)
    args = parser.parse_args(argv)

    if args.save_frames is not None:
        save_frames(render_frames(args.num_frames), args.save_frames)
        print(f"wrote {args.num_frames} frames to {args.save_frames}")
        return 0
    models = [m.strip() for m in args.models.split(",") if m.strip()]
    unknown = sorted(set(models) - set(MODELS))
    if unknown:
        parser.error(f"unknown models {unknown}; choose from {list(MODELS)}")

    import torch

    if args.device.startswith("cuda") and not torch.cuda.is_available():
        raise CudaUnavailableError(
            f"--device {args.device}: torch {torch.__version__} sees no CUDA device "
            f"(torch.version.cuda={torch.version.cuda}); use --device cpu"
        )
    bench = Bench(torch, args.device, args.iters, args.warmup)
    t_start = time.perf_counter()
    if args.frames is not None and args.frames.is_file():
        frames, source = load_frames(args.frames), f"loaded {args.frames.name}"
    else:
        frames, source = render_frames(args.num_frames), "rendered"
    results: dict[str, Any] = {
        "script": "bench/gpu_adapters.py",
        "started": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
        "weights": "random-init (official sizes" + (", --small)" if args.small else ")"),
        "small": args.small,
        **environment(torch, args.device),
        "frames": {
            "count": len(frames),
            "width": int(frames[0].rgb.shape[1]),
            "height": int(frames[0].rgb.shape[0]),
            "source": source,
        },
        "iters": args.iters,
        "warmup": args.warmup,
        "models": {},
        "errors": {},
        "finished": False,
    }
    args.out.parent.mkdir(parents=True, exist_ok=True)

    def write() -> None:
        results["total_s"] = round(time.perf_counter() - t_start, 1)
        args.out.write_text(json.dumps(results, indent=2) + "\n")

    write()
    print(json.dumps({k: v for k, v in results.items() if k not in ("models", "errors")}))
    with tempfile.TemporaryDirectory(prefix="gpu_adapters_") as tmp:
        for name in models:
            print(f"== {name}", flush=True)
            t0 = time.perf_counter()
            try:
                if name == "sam3":
                    r = bench_sam3(bench, args.small, frames, Path(tmp), args.sam3_keep)
                else:
                    r = bench_dinov3(bench, name, args.small, frames, Path(tmp))
                r["section_s"] = round(time.perf_counter() - t0, 1)
                results["models"][name] = r
                print(json.dumps(r), flush=True)
            except Exception:
                results["errors"][name] = traceback.format_exc()
                print(results["errors"][name], flush=True)
            bench.release()
            write()
    results["finished"] = True
    write()
    failed = [n for n, r in results["models"].items() if not r["checks"]["ok"]]
    print(f"wrote {args.out}; errors: {sorted(results['errors'])}; failed checks: {failed}")
    return 1 if results["errors"] or failed else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except CudaUnavailableError as exc:
        print(f"CudaUnavailableError: {exc}", file=sys.stderr)
        sys.exit(2)
