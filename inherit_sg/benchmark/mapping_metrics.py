"""Mapping figures of a benchmark: speed and memory of a build, or what a map's recorded
sessions say of the builds that made it, and object / room quality against the ground
truth (:mod:`inherit_sg.benchmark.metrics.mapping`)."""

from __future__ import annotations

import resource
import time
from pathlib import Path
from typing import Any

from inherit_sg.benchmark.metrics.mapping import (
    RoomMatching,
    evaluate_objects,
    match_rooms,
    room_correspondence,
)
from inherit_sg.config import Config
from inherit_sg.ingest.synthetic.ground_truth_files import seen_objects
from inherit_sg.ingest.synthetic.scene import Scene
from inherit_sg.model import EdgeKind, FloorNode, RoomNode, Session
from inherit_sg.store import MapStore


def peak_rss_mb() -> float:
    """Peak resident memory of this process so far (MiB; Linux reports KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def build_measured(dataset: Path, map_dir: Path, config: Config) -> dict[str, Any]:
    """Build ``dataset`` into ``map_dir`` and return the speed and memory figures."""
    from inherit_sg.facade import build_map

    t0 = time.perf_counter()
    summary = build_map(dataset, map_dir, config=config)
    seconds = time.perf_counter() - t0
    return {
        "source": "build",
        "frames": summary["frames"],
        "keyframes": summary["keyframes"],
        "build_s": seconds,
        "frames_per_s": summary["frames"] / seconds if seconds > 0 else float("nan"),
        "geometry_fps": summary["geometry_fps"],
        "semantic_keyframes_per_s": summary["semantic_keyframes_per_s"],
        "stage_seconds": summary["timings_s"],
        "peak_rss_mb": peak_rss_mb(),
    }


def _session_row(s: Session) -> dict[str, Any]:
    seconds = (s.finished - s.started) if s.finished else None
    return {
        "id": s.id,
        "frames": s.frames,
        "keyframes": s.keyframes,
        "build_s": seconds,
        "frames_per_s": s.frames / seconds if seconds else None,
    }


def from_sessions(store: MapStore) -> dict[str, Any]:
    """Speed figures from the map's recorded sessions ("n/a" for what was not recorded:
    per-stream rates and memory are only known when the benchmark builds the map)."""
    sessions = [_session_row(s) for s in store.sessions()]
    timed = [s for s in sessions if s["build_s"]]
    frames = sum(s["frames"] for s in sessions)
    seconds = sum(s["build_s"] for s in timed) if timed and len(timed) == len(sessions) else None
    return {
        "source": "sessions",
        "sessions": sessions,
        "frames": frames,
        "keyframes": sum(s["keyframes"] for s in sessions),
        "build_s": seconds if seconds is not None else "n/a",
        "frames_per_s": frames / seconds if seconds else "n/a",
        "geometry_fps": "n/a",
        "semantic_keyframes_per_s": "n/a",
        "peak_rss_mb": "n/a",
    }


def quality(store: MapStore, dataset: Path, scene: Scene) -> dict[str, Any]:
    """Object precision / recall (seen objects only when the dataset says which were
    seen), room assignment and room precision / recall of the map against ``scene``."""
    graph = store.load_graph()
    levels = {n.id: n.level for n in graph.nodes() if isinstance(n, FloorNode)}
    rooms = [n for n in graph.nodes() if isinstance(n, RoomNode)]
    room_map = room_correspondence(rooms, scene, levels)
    visible = seen_objects(dataset) if (dataset / "visibility.json").is_file() else None
    objects = evaluate_objects(
        list(graph.objects()),
        scene,
        visible=visible,
        room_map=room_map,
        floor_level=lambda o: levels.get(o.floor_id or ""),
        relations=graph.edges(EdgeKind.RELATION),
    )
    matching = match_rooms(rooms, scene, levels)
    return {"objects": objects.to_dict(), "rooms": room_scores(matching)}


def room_scores(matching: RoomMatching) -> dict[str, Any]:
    """Room precision and recall by the one-to-one mutual-majority rule of
    :class:`~inherit_sg.benchmark.metrics.mapping.RoomMatching`: a map room that merges several true
    rooms (an open-plan kitchen and living room found as one) or covers only part of a
    split one matches nothing."""
    return {
        "predicted": matching.predicted,
        "true_rooms": matching.true_rooms,
        "matched": matching.matched,
        "precision": matching.precision,
        "recall": matching.recall,
        "recall_seen": matching.recall_seen,
        "rule": "mutual majority, one-to-one",
    }
