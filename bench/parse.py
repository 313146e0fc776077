"""Rule-parser speed: per-request latency (p50 / p99 / max) without the result cache.

Requests: the hand-written cases in tests/data/parse_cases.jsonl plus the 500 real
requests in ../shared/data/real when present. Run: ``python bench/parse.py [--rounds N]``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

from inherit_sg.retrieval.rules import parse_uncached

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "tests" / "data" / "parse_cases.jsonl"
REAL = ROOT.parent / "shared" / "data" / "real" / "queries" / "embodied_rag_queries.jsonl"


def load_requests() -> list[str]:
    """Texts to parse."""
    texts = [json.loads(line)["text"] for line in CASES.read_text().splitlines() if line.strip()]
    if REAL.is_file():
        texts += [json.loads(line)["query"] for line in REAL.read_text().splitlines() if line]
    return texts


def main() -> None:
    """Parse every request ``--rounds`` times and print latency percentiles."""
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    texts = load_requests()
    for text in texts:  # warm the lexicon tables
        parse_uncached(text)
    times_ms: list[float] = []
    for _ in range(args.rounds):
        for text in texts:
            start = time.perf_counter()
            parse_uncached(text)
            times_ms.append((time.perf_counter() - start) * 1000.0)
    times_ms.sort()
    q = statistics.quantiles(times_ms, n=100)
    print(f"requests: {len(texts)} x {args.rounds} rounds = {len(times_ms)} parses")
    print(
        f"p50 {q[49]:.3f} ms   p90 {q[89]:.3f} ms   p99 {q[98]:.3f} ms   max {times_ms[-1]:.3f} ms"
    )
    print(f"throughput {1000.0 * len(times_ms) / sum(times_ms):.0f} parses/s (one core)")


if __name__ == "__main__":
    main()
