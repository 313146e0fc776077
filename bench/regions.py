"""Catchment basins of room segmentation: our steepest-ascent watershed against
scikit-image's priority-flood watershed.

``inherit_sg.geometry.regions.ascent_basins`` labels each free cell of a floor's smoothed
clearance map with the local maximum its steepest ascent reaches (vectorised numpy:
pointer jumping, no priority queue). ``skimage.segmentation.watershed`` of the negated
map, with its own minima as markers, computes the same partition up to plateau ties. This
script times both on generated floor grids (rooms on a grid with doorways and furniture
holes, like the occupancy the geometric stream builds) and reports how many cells fall in
the majority scikit-image basin of their own basin. scikit-image is not a dependency of
the project: install it to run this comparison.

Run: ``python bench/regions.py [--repeat 20] [--out bench/results/regions.json]``.
"""

from __future__ import annotations

import argparse
import json
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path

import numpy as np
from scipy import ndimage as ndi

from inherit_sg.geometry.regions import ascent_basins

OUT = Path(__file__).resolve().parent / "results" / "regions.json"
SIZES = ((160, 240), (320, 480), (640, 960))


def floor_grid(h: int, w: int, seed: int = 0) -> np.ndarray:
    """Free cells of a floor: 3 × 4 rooms with doorways, and furniture holes."""
    rng = np.random.default_rng(seed)
    free = np.zeros((h, w), dtype=bool)
    for i in range(3):
        for j in range(4):
            r0, r1 = i * h // 3 + 3, (i + 1) * h // 3 - 3
            c0, c1 = j * w // 4 + 3, (j + 1) * w // 4 - 3
            free[r0:r1, c0:c1] = True
            if j < 3:
                free[(r0 + r1) // 2 - h // 64 : (r0 + r1) // 2 + h // 64, c1 - 3 : c1 + 6] = True
            if i < 2:
                free[r1 - 3 : r1 + 6, (c0 + c1) // 2 - w // 96 : (c0 + c1) // 2 + w // 96] = True
    for _ in range(40):
        r, c = int(rng.integers(0, h - 20)), int(rng.integers(0, w - 20))
        free[r : r + int(rng.integers(5, 20)), c : c + int(rng.integers(5, 20))] = False
    return free


def _ms(fn: Callable[..., object], repeat: int, *args: object, **kwargs: object) -> float:
    start = time.perf_counter()
    for _ in range(repeat):
        fn(*args, **kwargs)
    return 1000.0 * (time.perf_counter() - start) / repeat


def agreement(ours: np.ndarray, theirs: np.ndarray, mask: np.ndarray) -> float:
    """Share of cells in the majority ``theirs`` basin of their ``ours`` basin."""
    pairs = Counter(zip(ours[mask].tolist(), theirs[mask].tolist(), strict=True))
    best: dict[int, int] = {}
    for (a, _), n in pairs.items():
        best[a] = max(best.get(a, 0), n)
    return sum(best.values()) / max(int(mask.sum()), 1)


def main() -> None:
    """Time both watersheds per grid size and write the JSON results."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--repeat", type=int, default=20, help="timed runs per size")
    ap.add_argument("--out", type=Path, default=OUT, help="results JSON (default: %(default)s)")
    args = ap.parse_args()
    try:
        from skimage.segmentation import watershed
    except ImportError:
        raise SystemExit("scikit-image is not installed: pip install scikit-image") from None
    rows = []
    for h, w in SIZES:
        free = floor_grid(h, w)
        smooth = ndi.gaussian_filter(ndi.distance_transform_edt(free), 1.0)
        ours = ascent_basins(smooth, free)
        theirs = watershed(-smooth, mask=free, connectivity=2)
        row = {
            "grid": f"{h}x{w}",
            "ascent_basins_ms": round(_ms(ascent_basins, args.repeat, smooth, free), 2),
            "skimage_watershed_ms": round(
                _ms(watershed, args.repeat, -smooth, mask=free, connectivity=2), 2
            ),
            "basins_ours": int(ours.max()),
            "basins_skimage": int(theirs.max()),
            "agreement": round(agreement(ours, theirs, free), 4),
        }
        rows.append(row)
        print(
            f"{row['grid']:>8}: ascent_basins {row['ascent_basins_ms']:7.2f} ms "
            f"({row['basins_ours']} basins), skimage watershed {row['skimage_watershed_ms']:7.2f} "
            f"ms ({row['basins_skimage']} basins), agreement {100 * row['agreement']:.1f} %"
        )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"sizes": rows}, indent=2) + "\n", encoding="utf-8")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
