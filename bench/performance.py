"""Performance benchmark: map size on disk, whole-build time and peak memory.

Builds one generated house (by default house 811, two floors, 640×480, clean: the
walk of the benchmark page) twice with ``inherit-sg map build``, once as shipped
(compacted when the build ends) and once with ``--set store.compact_on_finish=false``,
each in its own process: wall time, the build's own seconds and per-stream timings,
and the process's peak resident memory (``os.wait4``). Then the bytes of each map's
files, the real 10-node Spark-DSG apartment imported both ways, and the floor a single
table costs in plain Kuzu (why a map cannot go below ~20 MB with this schema).

Run: ``python bench/performance.py [--dataset DIR] [--work DIR]
[--out bench/results/performance.json]``
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.machine import machine_reference

ROOT = Path(__file__).resolve().parents[1]
SPARK_DSG = ROOT.parent / "shared" / "data" / "real" / "spark_dsg" / "apartment_dsg.json"


def run_measured(cmd: list[str], log: Path) -> dict[str, Any]:
    """Run ``cmd``; its wall time, exit status and peak resident memory (MB)."""
    t0 = time.perf_counter()
    with log.open("wb") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, cwd=ROOT)
        _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({proc.returncode}); see {log}")
    return {"wall_s": round(time.perf_counter() - t0, 2), "peak_rss_mb": usage.ru_maxrss / 1024}


def sizes(map_dir: Path) -> dict[str, int]:
    """Bytes per top-level entry of a map directory (folders summed)."""
    out: dict[str, int] = {}
    for entry in sorted(map_dir.iterdir()):
        files = [entry] if entry.is_file() else [p for p in entry.rglob("*") if p.is_file()]
        out[entry.name] = sum(p.stat().st_size for p in files)
    return out


def build(dataset: Path, map_dir: Path, compact: bool, log: Path) -> dict[str, Any]:
    """One ``inherit-sg map build`` in its own process."""
    cmd = [sys.executable, "-m", "inherit_sg.cli.main", "map", "build", str(dataset)]
    cmd += ["--map", str(map_dir), "--json"]
    if not compact:
        cmd += ["--set", "store.compact_on_finish=false"]
    measured = run_measured(cmd, log)
    text = log.read_text(encoding="utf-8", errors="replace")
    summary = json.loads(text[text.index("{") :])
    files = sizes(map_dir)
    return {
        **measured,
        "frames": summary["frames"],
        "keyframes": summary["keyframes"],
        "objects": summary["objects"],
        "build_s": summary["seconds"],
        "timings_s": summary["timings_s"],
        "semantic_keyframes_per_s": summary["semantic_keyframes_per_s"],
        "files": files,
        "kuzu_mb": round((files.get("graph.kuzu", 0) + files.get("index.kuzu", 0)) / 1e6, 2),
        "without_keyframes_mb": round(sum(v for k, v in files.items() if k != "lance") / 1e6, 2),
    }


def spark_dsg_sizes(work: Path) -> dict[str, Any]:
    """The real Spark-DSG apartment (10 nodes) imported as shipped and uncompacted."""
    from inherit_sg.config import load_config
    from inherit_sg.facade import import_into_new_map

    out: dict[str, Any] = {}
    for name, compact in (("compacted", True), ("uncompacted", False)):
        cfg = load_config(None, [f"store.compact_on_finish={str(compact).lower()}"])
        path = work / f"dsg-{name}"
        if path.exists():  # a kept --work directory from an earlier run
            shutil.rmtree(path)
        summary = import_into_new_map(SPARK_DSG, path, fmt="spark-dsg", config=cfg)
        files = sizes(path)
        out[name] = {"nodes": summary["nodes"], "files": files, "mb": sum(files.values()) / 1e6}
    return out


TABLES = 6


def table_floor(work: Path) -> dict[str, float]:
    """Bytes plain Kuzu adds per table (MB, after a checkpoint): the mean over
    ``TABLES`` node tables of two rows each, one node table of 1,000 rows, the mean over
    ``TABLES`` rel tables of one edge each (stored both ways, as the map's are, and one
    way only), and a full-text index over two rows. A node table's cost is its
    primary-key hash index, allocated with the first row; a rel table's is its backward
    adjacency, allocated with the first edge between two different nodes."""
    import kuzu

    path = work / "floor.kuzu"
    for stale in (path, path.with_name(path.name + ".wal")):
        stale.unlink(missing_ok=True)
    db = kuzu.Database(str(path))
    conn = kuzu.Connection(db)

    def size() -> float:
        conn.execute("CHECKPOINT")
        return path.stat().st_size / 1e6

    out: dict[str, float] = {}
    base = size()
    for t in range(TABLES):
        conn.execute(f"CREATE NODE TABLE A{t}(id STRING PRIMARY KEY, text STRING)")
        conn.execute(f"CREATE (:A{t} {{id: 'a', text: 'a red chair'}}), (:A{t} {{id: 'b'}})")
    out["node_table_mb"] = round((size() - base) / TABLES, 3)
    base = size()
    conn.execute("CREATE NODE TABLE Big(id STRING PRIMARY KEY)")
    conn.execute("UNWIND range(1, 1000) AS i CREATE (:Big {id: 'obj:' + CAST(i AS STRING)})")
    out["node_table_1000_rows_mb"] = round(size() - base, 3)
    for key, prefix, storage in (
        ("rel_table_mb", "R", ""),
        ("rel_table_forward_only_mb", "F", " WITH (storage_direction='fwd')"),
    ):
        base = size()
        for t in range(TABLES):
            conn.execute(f"CREATE REL TABLE {prefix}{t}(FROM A0 TO A0){storage}")
            link = f"CREATE (a)-[:{prefix}{t}]->(b)"
            conn.execute(f"MATCH (a:A0 {{id: 'a'}}), (b:A0 {{id: 'b'}}) {link}")
        out[key] = round((size() - base) / TABLES, 3)
    base = size()
    conn.execute("CALL CREATE_FTS_INDEX('A0', 'fts', ['text'])")
    out["fulltext_index_mb"] = round(size() - base, 3)
    db.close()
    return out


def main() -> None:
    """Measure and write the results."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dataset", type=Path, help="an isg dataset (default: house 811)")
    ap.add_argument("--work", type=Path, help="keep datasets and maps here")
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "performance.json")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-perf-") as tmp:
        work = args.work or Path(tmp)
        work.mkdir(parents=True, exist_ok=True)
        dataset = args.dataset or work / "house-811"
        if not (dataset / "scene.json").is_file():
            cmd = [sys.executable, "-m", "inherit_sg.cli.main", "sim", "generate"]
            cmd += ["--seed", "811", "--floors", "2", "--width", "640", "--height", "480"]
            cmd += ["--out", str(dataset)]
            subprocess.run(cmd, check=True, cwd=ROOT, stdout=subprocess.DEVNULL)
        builds = {}
        for name, compact in (("compacted", True), ("uncompacted", False)):
            map_dir = work / f"map-{name}"
            if map_dir.exists():
                shutil.rmtree(map_dir)
            builds[name] = build(dataset, map_dir, compact, work / f"build-{name}.log")
            b = builds[name]
            print(
                f"{name}: build {b['build_s']} s (wall {b['wall_s']} s), peak RSS "
                f"{b['peak_rss_mb']:.0f} MB, Kuzu files {b['kuzu_mb']} MB, map without "
                f"keyframes {b['without_keyframes_mb']} MB",
                flush=True,
            )
        results = {
            "dataset": str(dataset),
            "cpus": os.cpu_count(),
            "machine_reference": machine_reference(),
            "builds": builds,
            "spark_dsg": spark_dsg_sizes(work) if SPARK_DSG.is_file() else None,
            "kuzu_table_floor": table_floor(work),
        }
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(results, indent=1) + "\n", encoding="utf-8")
    print(json.dumps({k: v for k, v in results.items() if k != "builds"}, indent=1))
    print(f"→ {args.out}")


if __name__ == "__main__":
    main()
