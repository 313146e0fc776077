"""Per-keyframe cost of the offline perception backends at 640×480.

Renders a toy room with a dozen coloured boxes, then times each backend on it (median
of ``--repeat`` runs) and prints one line per backend; ``--json PATH`` also writes the
numbers to a file.

    python bench/perception.py [--repeat 20] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the toy renderer is a test helper (tests/toy_scene.py)

from inherit_sg.perception.base import ObjectObservation  # noqa: E402
from inherit_sg.perception.classical_segmenter import ClassicalSegmenter  # noqa: E402
from inherit_sg.perception.colour_names import colour_name  # noqa: E402
from inherit_sg.perception.dataset_segmenter import DatasetSegmenter, MaskNoise  # noqa: E402
from inherit_sg.perception.describer import TemplateDescriber  # noqa: E402
from inherit_sg.perception.descriptor import DescriptorEncoder  # noqa: E402
from tests.toy_scene import ToyBox, look_at, render_toy_frame, toy_intrinsics  # noqa: E402


def _scene() -> list[ToyBox]:
    rng = np.random.default_rng(0)
    boxes = []
    for i in range(12):
        x, y = -2.2 + 0.4 * i, 1.5 + 1.5 * rng.random()
        size = (0.3 + 0.4 * rng.random(), 0.3 + 0.3 * rng.random(), 0.3 + 0.9 * rng.random())
        r, g, b = (int(c) for c in rng.integers(20, 240, 3))
        boxes.append(
            ToyBox(
                f"obj{i}",
                (x, y, size[2] / 2),
                size,
                (r, g, b),
                yaw=float(rng.random()),
                pattern=0.1,
            )
        )
    return boxes


def _time(fn: Callable[[], object], repeat: int) -> dict[str, float]:
    """Median and best wall time in ms (best is the least disturbed by other load)."""
    fn()  # warm-up
    runs = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        runs.append(time.perf_counter() - t0)
    return {"median_ms": 1000.0 * statistics.median(runs), "best_ms": 1000.0 * min(runs)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()

    frame = render_toy_frame(
        _scene(),
        look_at((0.0, -1.0, 1.5), (0.0, 2.5, 0.4)),
        toy_intrinsics(640, 480),
        rgb_noise=2.0,
        depth_noise=0.002,
    )
    dataset = DatasetSegmenter()
    noisy = DatasetSegmenter(noise=MaskNoise())
    classical = ClassicalSegmenter()
    encoder = DescriptorEncoder()
    describer = TemplateDescriber()
    dets = dataset.segment(frame)
    masks = [d.mask for d in dets]
    observations = [
        ObjectObservation.from_frame(frame, d, (0.5, 0.5, 0.9), "kitchen") for d in dets
    ]

    timings = {
        "dataset_segmenter_ms": _time(lambda: dataset.segment(frame), args.repeat),
        "dataset_segmenter_noisy_ms": _time(lambda: noisy.segment(frame), args.repeat),
        "classical_segmenter_ms": _time(lambda: classical.segment(frame), args.repeat),
        "descriptor_encode_all_ms": _time(lambda: encoder.encode(frame.rgb, masks), args.repeat),
        "descriptor_encode_image_ms": _time(lambda: encoder.encode_image(frame.rgb), args.repeat),
        "colour_name_all_ms": _time(
            lambda: [colour_name(frame.rgb, m) for m in masks], args.repeat
        ),
        "template_describer_all_ms": _time(
            lambda: [describer.describe(o) for o in observations], args.repeat
        ),
    }
    print(f"perception backends, 640x480 frame, {len(dets)} objects, {args.repeat} runs")
    print(f"  {'backend (per keyframe)':32s} {'median ms':>10s} {'best ms':>10s}")
    for key, t in timings.items():
        print(f"  {key.removesuffix('_ms'):32s} {t['median_ms']:10.2f} {t['best_ms']:10.2f}")
    if args.json is not None:
        results = {"width": 640, "height": 480, "objects": len(dets), "timings": timings}
        args.json.write_text(json.dumps(results, indent=2))


if __name__ == "__main__":
    main()
