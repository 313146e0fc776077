"""Offline parser: speed and accuracy.

Speed: per-request latency (p50 / p90 / p99 / max) without the result cache, over the
development set (tests/data/dev_requests), the hand-written cases (tests/data/parse_cases.jsonl)
and the 500 real requests in ../shared/data/real when present; the first parse (loading spaCy,
the vocabulary and the spelling dictionary) is reported apart.

Accuracy (``--dev``): the development set judged by :mod:`inherit_sg.benchmark.metrics.parse`: targets,
negations (recall, invented), crashes, each constraint kind's recall and targets per form;
``--misses`` lists the requests whose target or negations are wrong.

Run: ``python bench/parse.py [--rounds N] [--dev] [--misses] [--requests FILE|DIR] [--out FILE]``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.metrics.parse import Report, evaluate, load_requests
from inherit_sg.retrieval.rules import parse_uncached

ROOT = Path(__file__).resolve().parents[1]
DEV = ROOT / "tests" / "data" / "dev_requests"
CASES = ROOT / "tests" / "data" / "parse_cases.jsonl"
REAL = ROOT.parent / "shared" / "data" / "real" / "queries" / "embodied_rag_queries.jsonl"
RESULTS = ROOT / "bench" / "results" / "parse.json"


def load_texts() -> list[str]:
    """Texts to time."""
    texts = [str(r["text"]) for r in load_requests(sorted(DEV.glob("*.jsonl")))]
    texts += [json.loads(line)["text"] for line in CASES.read_text().splitlines() if line.strip()]
    if REAL.is_file():
        texts += [json.loads(line)["query"] for line in REAL.read_text().splitlines() if line]
    return texts


def time_parses(texts: list[str], rounds: int) -> dict[str, Any]:
    """Latency of parsing every text ``rounds`` times (after one warm-up parse)."""
    for text in texts:
        parse_uncached(text)
    times_ms: list[float] = []
    for _ in range(rounds):
        for text in texts:
            start = time.perf_counter()
            parse_uncached(text)
            times_ms.append((time.perf_counter() - start) * 1000.0)
    times_ms.sort()
    q = statistics.quantiles(times_ms, n=100)
    return {
        "requests": len(texts),
        "parses": len(times_ms),
        "p50_ms": round(q[49], 3),
        "p90_ms": round(q[89], 3),
        "p99_ms": round(q[98], 3),
        "max_ms": round(times_ms[-1], 3),
        "per_second": round(1000.0 * len(times_ms) / sum(times_ms)),
    }


def accuracy(report: Report) -> dict[str, Any]:
    """The development-set figures of ``report``."""
    return {
        "requests": report.n,
        "target_accuracy": round(report.target_accuracy, 4),
        "negation_recall": round(report.negation_recall, 4),
        "negation_accuracy": round(report.negation_accuracy, 4),
        "negations_expected": report.negations_expected,
        "negations_invented": report.negations_invented,
        "crashes": len(report.crashes),
        "constraint_recall": {
            k: {"found": f, "annotated": w} for k, (f, w) in report.constraint_recall().items()
        },
        "targets_by_form": {k: {"right": r, "n": n} for k, (r, n) in report.by_form().items()},
    }


def print_accuracy(acc: dict[str, Any]) -> None:
    """Human-readable accuracy table."""
    print(f"development set: {acc['requests']} requests")
    print(f"  targets right      {100 * acc['target_accuracy']:.1f} %")
    print(
        f"  negations found    {100 * acc['negation_recall']:.1f} % of "
        f"{acc['negations_expected']} ({acc['negations_invented']} invented)"
    )
    print(f"  crashes            {acc['crashes']}")
    print("  constraint recall:")
    for kind, v in acc["constraint_recall"].items():
        print(
            f"    {kind:12s} {v['found']:4d} / {v['annotated']:4d}  {100 * v['found'] / v['annotated']:5.1f} %"
        )
    print("  targets by form:")
    for form, v in acc["targets_by_form"].items():
        print(f"    {form:16s} {v['right']:4d} / {v['n']:4d}  {100 * v['right'] / v['n']:5.1f} %")


def main() -> None:
    """Time the parser and, with ``--dev``, measure it on the development set."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--rounds", type=int, default=3, help="timed passes over the texts")
    ap.add_argument("--dev", action="store_true", help="accuracy on the development set")
    ap.add_argument("--misses", action="store_true", help="list wrong targets and negations")
    ap.add_argument(
        "--requests",
        type=Path,
        default=DEV,
        help="annotated requests: a .jsonl file or a folder of them (default: the dev set)",
    )
    ap.add_argument("--out", type=Path, default=RESULTS, help=f"results JSON (default {RESULTS})")
    args = ap.parse_args()
    start = time.perf_counter()
    parse_uncached("the mug on the table")  # loads spaCy, the vocabulary, the spelling
    first_ms = (time.perf_counter() - start) * 1000.0
    results: dict[str, Any] = {}
    if args.dev or args.misses:
        files = sorted(args.requests.glob("*.jsonl")) if args.requests.is_dir() else [args.requests]
        report = evaluate(load_requests(files), parse_uncached)
        results["accuracy"] = accuracy(report)
        print_accuracy(results["accuracy"])
        if args.misses:
            for j in report.judgements:
                if not j.target_ok or not j.negations_ok:
                    got = j.parsed.target.describe() if j.parsed is not None else j.error
                    print(f"  - {j.id}: {j.text!r} -> {got}")
    texts = load_texts()
    results["latency"] = time_parses(texts, args.rounds) | {"first_parse_ms": round(first_ms, 1)}
    lat = results["latency"]
    print(f"latency: {lat['requests']} requests x {args.rounds} rounds = {lat['parses']} parses")
    print(
        f"  p50 {lat['p50_ms']:.3f} ms   p90 {lat['p90_ms']:.3f} ms   p99 {lat['p99_ms']:.3f} ms"
        f"   max {lat['max_ms']:.3f} ms   ({lat['per_second']} parses/s, one core)"
    )
    print(f"  first parse (loads spaCy, vocabulary, spelling): {lat['first_parse_ms']:.0f} ms")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(results, indent=2) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
