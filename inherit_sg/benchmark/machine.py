"""A machine-speed reference measured next to timing benchmarks: the same 2-core machine
has run the same build in 35 s and in 54 s on different days, so a timing is only
comparable with another taken at a similar reference."""

from __future__ import annotations

import time

import numpy as np


def machine_reference() -> dict[str, float]:
    """Seconds of two fixed workloads, to compare runs on machines of different speed
    (the same 2-core machine has measured the same build 35 to 54 s on different days):
    a pure-Python loop of 3 million additions and a 1000×1000 float64 matrix product."""
    t0 = time.perf_counter()
    total = 0
    for i in range(3_000_000):
        total += i
    loop_s = time.perf_counter() - t0
    a = np.random.default_rng(0).random((1000, 1000))
    t0 = time.perf_counter()
    for _ in range(5):
        a @ a
    return {"python_loop_s": round(loop_s, 3), "matmul_s": round((time.perf_counter() - t0) / 5, 4)}
