"""The hostile suite as a table: inputs tried, clear errors, harmless answers, recoveries,
crashes and data lost, per surface (CLI, REST, map files, frames, live frames, Cypher).

It runs ``tests/e2e/test_hostile_suite.py`` (the catalogue lives there, so the table and
the test suite can never disagree) with ``HOSTILE_SUITE_REPORT`` set, and reads back
one record per input.

Run: ``python bench/hostile.py [--out FILE]``; writes ``bench/results/hostile.json`` and
prints a Markdown table.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from inherit_sg.benchmark.tables import table  # noqa: E402

SUITE = "tests/e2e/test_hostile_suite.py"


def run_suite() -> tuple[list[dict[str, Any]], int]:
    """The suite's records and pytest's exit status."""
    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "hostile.json"
        env = {**os.environ, "HOSTILE_SUITE_REPORT": str(report)}
        proc = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", SUITE],
            cwd=ROOT,
            env=env,
            check=False,
        )
        if not report.is_file():
            raise SystemExit(f"the suite wrote no report (pytest exit {proc.returncode})")
        return json.loads(report.read_text()), proc.returncode


def summarise(records: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """One row per surface and a total row."""
    rows = []
    surfaces = sorted({r["surface"] for r in records})
    for surface in [*surfaces, "all"]:
        mine = [r for r in records if surface in ("all", r["surface"])]
        outcomes = Counter(r["outcome"] for r in mine)
        rows.append(
            {
                "surface": surface,
                "inputs": len(mine),
                "clear errors": outcomes["clear error"],
                "answered (legal input)": outcomes["answered"],
                "recovered, with a warning": sum(
                    n for k, n in outcomes.items() if k.startswith("recovered")
                ),
                "crashes or wrong outcomes": sum(
                    n for k, n in outcomes.items() if k.startswith("FAILED")
                ),
                "data lost": sum(1 for r in mine if r.get("data_lost", 1)),
            }
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "hostile.json")
    args = parser.parse_args()
    records, status = run_suite()
    rows = summarise(records)
    args.out.write_text(
        json.dumps({"pytest_exit": status, "summary": rows, "inputs": records}, indent=1) + "\n"
    )
    print(table(list(rows[0]), [list(r.values()) for r in rows]))
    print(f"\npytest exit status {status}; records in {args.out}")


if __name__ == "__main__":
    main()
