"""Offline parser on the probe request sets: target agreement, negations and crashes.

The sets in ``bench/data/probe_requests/`` were written here in twenty styles people use
(grounding-dataset descriptions, robot requests, negations and traps that look like
negations, short speaker-relative utterances, long multi-sentence descriptions,
house-scale requests with real room names, remote embodied instructions in real homes,
situated / scene / plural references, second-language crowd-worker descriptions,
speech-recognition transcripts, chat messages, staff requests in non-home buildings,
ScanRefer-style and Nr3D-style grounding text, Sr3D / Multi3DRefer / ScanQA-style spatial
references, spoken requests to a home-care robot, chores with the object embedded in a task, grounding
descriptions typed fast with typos and the landmark named first, spoken and typed corrections and
follow-ups, ScanRefer descriptions in their natural proportions). A parse that runs longer than
:data:`PARSE_LIMIT_S` counts as a crash (reported as ``HANG``). Each line names the target's head noun
(``target``, or null where the person names no object) and whether something is ruled
out (``negated``, where annotated).

A target agrees when :func:`inherit_sg.benchmark.metrics.parse.target_right` accepts it or,
failing that, when the annotated head word occurs in the parsed labels or noun (a writer
who wrote "strip" for "power strip"). A negation is found when any constraint is negated,
a label is excluded or the request refers to "the other one". The sets were used while
fixing the parser, so they measure coverage, not held-out accuracy.

    python bench/probe_requests.py [--misses] [--sets DIR] [--out bench/results/probe_requests.json]
"""

from __future__ import annotations

import argparse
import json
import signal
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.metrics.parse import target_right
from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.retrieval.rules import parse_uncached

HERE = Path(__file__).resolve().parent
# Seconds one parse may take before it counts as a hang (a parse takes milliseconds).
PARSE_LIMIT_S = 10


class _Hang(Exception):
    """A parse ran past :data:`PARSE_LIMIT_S`."""


@contextmanager
def _time_limit(seconds: int) -> Iterator[None]:
    """Raise :class:`_Hang` in the main thread when the body runs longer than
    ``seconds`` (SIGALRM; where there is none, no limit)."""
    if not hasattr(signal, "SIGALRM"):
        yield
        return

    def _raise(signum: int, frame: object) -> None:
        raise _Hang

    previous = signal.signal(signal.SIGALRM, _raise)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


SETS = HERE / "data" / "probe_requests"


def target_agrees(parsed: ParsedQuery, target: str | None) -> bool:
    """Whether the parsed target is the annotated one (see the module docstring)."""
    if target is None:  # a place or a need: no named object, or not an object at all
        t = parsed.target
        return not t.labels or t.layer != "object" or t.function is not None
    if target_right(parsed, {"target": target, "target_also": []}):
        return True
    words = " ".join(parsed.target.labels) + " " + (parsed.target.noun or "")
    return target.split()[-1] in words


def negation_found(parsed: ParsedQuery) -> bool:
    """Whether the parse rules anything out."""
    return (
        any(c.negated for c, _ in parsed.walk())
        or bool(parsed.exclude_ids)
        or parsed.reference in ("other", "exclude_previous")
    )


def judge_set(path: Path, misses: bool) -> dict[str, Any]:
    """Counts for one set (and its misses printed when asked)."""
    n = agreed = crashes = neg_expected = neg_found = invented = 0
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.strip():
            continue
        row = json.loads(line)
        n += 1
        try:
            with _time_limit(PARSE_LIMIT_S):
                parsed = parse_uncached(row["text"])
        except _Hang:
            crashes += 1
            print(f"  HANG {row['text']!r}: no parse within {PARSE_LIMIT_S} s")
            continue
        except Exception as exc:  # a crash is what is counted here
            crashes += 1
            print(f"  CRASH {row['text']!r}: {exc}")
            continue
        ok = target_agrees(parsed, row.get("target"))
        agreed += ok
        found = negation_found(parsed)
        if "negated" in row:
            if row["negated"]:
                neg_expected += 1
                neg_found += found
            elif found:
                invented += 1
            if misses and found != bool(row["negated"]):
                print(f"  negation {row['text']!r}: expected {row['negated']}, found {found}")
        if misses and not ok:
            print(f"  target {row['text']!r}: expected {row.get('target')}, "
                  f"parsed {list(parsed.target.labels[:3])}")  # fmt: skip
    return {
        "requests": n,
        "targets_agree": round(agreed / n, 4) if n else 0.0,
        "negations_expected": neg_expected,
        "negation_recall": round(neg_found / neg_expected, 4) if neg_expected else None,
        "negations_invented": invented,
        "crashes": crashes,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--misses", action="store_true", help="list the targets that disagree")
    ap.add_argument("--out", type=Path, default=HERE / "results" / "probe_requests.json")
    ap.add_argument("--sets", type=Path, default=SETS, help="folder of *.jsonl probe sets")
    args = ap.parse_args()
    results: dict[str, Any] = {}
    for path in sorted(args.sets.glob("*.jsonl")):
        print(f"== {path.stem}")
        row = judge_set(path, args.misses)
        results[path.stem] = row
        recall = row["negation_recall"]
        print(
            f"  {row['requests']} requests: targets {100 * row['targets_agree']:.1f} %"
            + (f", negations {100 * recall:.1f} % of {row['negations_expected']}"
               f" ({row['negations_invented']} invented)" if recall is not None else "")
            + f", crashes {row['crashes']}"
        )  # fmt: skip
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(results, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
