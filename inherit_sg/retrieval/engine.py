"""QueryEngine: parse → conversation → plan → candidates → score → graph checks →
verify → answer, with a human-readable trace and timings per stage.

One engine serves one open map. It keeps a :class:`MapSnapshot` of the map in memory and
reloads it only when the map's files change, so a request costs one or two Cypher calls
plus in-memory work. Engines are safe to share between threads.
"""

from __future__ import annotations

import dataclasses
import gc
import threading
import time
from collections.abc import Callable, Sequence
from typing import Protocol

import numpy as np

from inherit_sg.config import Config
from inherit_sg.errors import InheritSGError, NodeNotFoundError
from inherit_sg.model import ObjectNode, Pose
from inherit_sg.perception.base import Segmenter, VisualEncoder, check_image
from inherit_sg.retrieval.candidates import CandidateGenerator
from inherit_sg.retrieval.conversation import Conversation
from inherit_sg.retrieval.graph_checks import GraphChecker
from inherit_sg.retrieval.placement import PlacementMeter
from inherit_sg.retrieval.plan import Compiler, NodeSpec, QueryPlan
from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.retrieval.ranking import rank_spec
from inherit_sg.retrieval.result import QueryResult, candidate_dict, node_summary
from inherit_sg.retrieval.scoring import Scored, Scorer
from inherit_sg.retrieval.similarity import Embedder, PhraseSimilarity
from inherit_sg.retrieval.snapshot import MapSnapshot, load_snapshot, map_version
from inherit_sg.retrieval.stand_in import absent, place_found, said_place
from inherit_sg.retrieval.trace import describe_query, explain_ranking
from inherit_sg.retrieval.verify import (
    Evidence,
    OfflineVerifier,
    Verifier,
    decode_jpeg,
    graph_failures,
    ground,
    skip_grounding,
)
from inherit_sg.retrieval.viewer import KeyframeViews, ViewerPose
from inherit_sg.store import MapStore


class Parser(Protocol):
    """The rule parser or the LLM parser."""

    name: str

    def parse(self, text: str) -> ParsedQuery:
        """Parse a request (QueryTextError for bad text)."""
        ...


def _ms(start: float) -> float:
    return (time.perf_counter() - start) * 1000.0


def _frozen(load: Callable[[], MapSnapshot]) -> MapSnapshot:
    """``load()`` with its result kept out of the cyclic garbage collector's passes.

    A snapshot is hundreds of thousands of long-lived objects; each request's
    short-lived ones trigger collections that walk all of them (0.1-0.5 s at 100k
    objects). ``gc.freeze`` moves every object alive now into the permanent generation,
    which collections skip; ``gc.unfreeze`` first hands the previous snapshot back to
    the collector so a reload frees it. Both are O(1)."""
    gc.unfreeze()
    snap = load()
    gc.freeze()
    return snap


def _answerable(spec: NodeSpec, ranked: Sequence[Scored]) -> bool:
    """Whether the best candidate meets something: a positive score, or — for requests
    made only of negations ("something not in the kitchen") — no penalty."""
    if not ranked:
        return False
    if any(not c.negated for c in spec.scored()):
        return ranked[0].score > 0.0
    return ranked[0].score >= 0.0


def verification_candidates(ranked: Sequence[Scored], depth: int, max_gap: float) -> list[Scored]:
    """The candidates visual verification may try, best first: the top ``depth`` that
    score at most ``max_gap`` below the best (the best always)."""
    if not ranked:
        return []
    floor = ranked[0].score - max_gap
    return [c for c in ranked[:depth] if c.score >= floor]


class QueryEngine:
    """Answers natural-language requests on one map."""

    def __init__(
        self,
        store: MapStore,
        config: Config | None = None,
        *,
        parser: Parser | None = None,
        embedder: Embedder | None = None,
        verifier: Verifier | None = None,
        segmenter: Segmenter | None = None,
    ) -> None:
        self.store = store
        self.config = config or Config()
        self.parser = parser or self._default_parser()
        self._embedder = embedder
        self.verifier = verifier or self._default_verifier()
        self.segmenter = segmenter
        self._segmenter_tried = segmenter is not None
        self._encoder: VisualEncoder | None = None
        self._snap: MapSnapshot | None = None
        self._checker: GraphChecker | None = None
        self._helpers: tuple[MapSnapshot, KeyframeViews, PlacementMeter] | None = None
        self._lock = threading.Lock()

    # ----------------------------------------------------------- components
    def _default_parser(self) -> Parser:
        if self.config.retrieval.parser == "llm":
            from inherit_sg.retrieval.llm_parser import LLMParser

            return LLMParser.from_config(self.config.llm)
        from inherit_sg.retrieval.rules import RuleParser

        return RuleParser()

    def _default_verifier(self) -> Verifier:
        if self.config.llm.endpoint:
            from inherit_sg.retrieval.verify_vlm import VlmVerifier

            return VlmVerifier.from_config(self.config)
        return OfflineVerifier()

    @property
    def similarity(self) -> PhraseSimilarity:
        """Phrase similarity with the map's text embedder (loaded on first use)."""
        if self._embedder is None:
            from inherit_sg.embed import get_text_embedder

            cfg = self.config.embedder
            self._embedder = get_text_embedder(
                self.store.info.text_embedder or cfg.model,
                batch_size=cfg.batch_size,
                cache_size=cfg.cache_size,
                device=cfg.device,
                backend=cfg.backend,
            )
        return PhraseSimilarity(self._embedder)

    def _get_segmenter(self, trace: list[str]) -> Segmenter | None:
        """The configured text-prompted segmenter for verification (SAM3), if any."""
        if not self._segmenter_tried:
            self._segmenter_tried = True
            if self.config.perception.segmenter == "sam3":
                from inherit_sg.perception.registry import create_segmenter

                try:
                    self.segmenter = create_segmenter(self.config)
                except InheritSGError as exc:
                    trace.append(f"verify: SAM3 unavailable ({exc.message}); using SEEN_IN records")
        return self.segmenter

    def image_feature(self, image: np.ndarray, trace: list[str]) -> np.ndarray | None:
        """The object visual feature of a query image, made by the map's visual encoder
        (None, with a trace note, when that encoder cannot be loaded)."""
        info = self.store.info
        if self._encoder is None:
            from inherit_sg.perception.registry import create_visual_encoder

            perception = self.config.perception.model_copy(
                update={"visual_encoder": info.visual_encoder}
            )
            try:
                self._encoder = create_visual_encoder(
                    self.config.model_copy(update={"perception": perception})
                )
            except InheritSGError as exc:
                trace.append(f"query image ignored: {exc.message}")
                return None
        check_image(image, "query image")
        whole = np.ones(image.shape[:2], dtype=bool)
        feature = np.asarray(self._encoder.encode(image, [whole])[0], dtype=np.float32)
        if feature.shape[0] != info.visual_dim:
            trace.append(
                f"query image ignored: feature size {feature.shape[0]} != map's {info.visual_dim}"
            )
            return None
        trace.append(f"query image encoded by {info.visual_encoder} ({info.visual_dim}-d)")
        return feature

    def snapshot(self) -> tuple[MapSnapshot, GraphChecker]:
        """The current snapshot (reloaded when the map changed) and its graph checker."""
        version = map_version(self.store.path)
        with self._lock:
            if self._snap is None or self._snap.version != version:
                self._snap = _frozen(
                    lambda: load_snapshot(self.store, use_areas=self.config.retrieval.use_areas)
                )
                self._checker = GraphChecker(self._snap)
            assert self._checker is not None
            return self._snap, self._checker

    def _keyframe_pose(self, keyframe_id: str) -> Pose | None:
        try:
            return self.store.get_keyframe(keyframe_id).pose
        except NodeNotFoundError:
            return None

    def helpers(self, snap: MapSnapshot) -> tuple[KeyframeViews, PlacementMeter]:
        """Per-snapshot caches for scoring: keyframe poses / SEEN_IN index and the
        rooms' placement fields (kept while ``snap`` is the current snapshot)."""
        with self._lock:
            if self._helpers is not None and self._helpers[0] is snap:
                return self._helpers[1], self._helpers[2]
            made = (KeyframeViews(snap, self._keyframe_pose), PlacementMeter(snap))
            if snap is self._snap:
                self._helpers = (snap, *made)
            return made

    # ---------------------------------------------------------------- steps
    def parse(self, text: str, conversation: Conversation | None = None) -> ParsedQuery:
        """Parse ``text`` and resolve it against the conversation history."""
        parsed = self.parser.parse(text)
        return conversation.resolve(parsed) if conversation is not None else parsed

    def plan(self, parsed: ParsedQuery, snap: MapSnapshot | None = None) -> QueryPlan:
        """The compiled plan of a parsed request (on ``snap``, default the current map)."""
        snap = snap or self.snapshot()[0]
        return Compiler(snap, self.similarity).compile(parsed)

    def rank(
        self,
        plan: QueryPlan,
        trace: list[str] | None = None,
        view: tuple[MapSnapshot, GraphChecker] | None = None,
        *,
        viewer: ViewerPose | None = None,
    ) -> Sequence[Scored]:
        """Ranked target candidates of ``plan``: the viewpoint's landmark first, then
        the other landmarks, recursively; ``viewer`` is the robot's pose, if known."""
        return self._rank_spec(plan.target, trace, view, viewer)

    def _rank_spec(
        self,
        spec: NodeSpec,
        trace: list[str] | None,
        view: tuple[MapSnapshot, GraphChecker] | None,
        viewer: ViewerPose | None,
    ) -> Sequence[Scored]:
        snap, checker = view or self.snapshot()
        gen = CandidateGenerator(self.store, snap, self.similarity)
        keyframes, placement = self.helpers(snap)
        scorer = Scorer(snap, checker, robot=viewer, keyframes=keyframes, placement=placement)
        log = trace if trace is not None else []
        return rank_spec(spec, scorer, gen.generate, log)

    # --------------------------------------------------------------- query
    def query(
        self,
        text: str,
        *,
        conversation: Conversation | None = None,
        verify: bool | None = None,
        top_k: int | None = None,
        explain: bool = False,
        image: np.ndarray | None = None,
        viewer: ViewerPose | None = None,
    ) -> QueryResult:
        """Answer one request. Raises QueryTextError for empty / over-long / non-text
        input; a request with nothing to find answers null with the reason in the trace.
        ``image`` (RGB uint8) is a picture of the sought object: its visual feature joins
        the plan (object_visual index) and adds an appearance term to the score.
        ``viewer`` is the robot's pose: "left", "right", "in front", ordinals and
        "closest to you" are then seen from it (unless the request sets a viewpoint)."""
        start = time.perf_counter()
        parsed = self.parse(text, conversation)
        timings = {"parse": _ms(start), "retrieve": 0.0, "verify": 0.0}
        trace = describe_query(parsed)
        if viewer is not None:
            x, y, z = viewer.position
            trace.append(
                f"robot pose given: ({x:.2f}, {y:.2f}, {z:.2f}), heading {viewer.yaw_deg:.0f}°"
            )
        k = top_k or self.config.retrieval.top_k
        t1 = time.perf_counter()
        view = self.snapshot()
        snap = view[0]
        result = QueryResult(query=parsed.text, answer=None, constraints=parsed.to_dict())
        if not parsed.has_target:
            trace.append(f"no answer: {parsed.no_target_reason or 'the request names nothing'}")
            return self._finish(result, trace, timings, start)
        feature = self.image_feature(image, trace) if image is not None else None
        plan = Compiler(snap, self.similarity).compile(parsed, feature)
        spec = plan.target
        ranked = self.rank(plan, trace, view, viewer=viewer)
        likeness = absent(spec, ranked)
        place = said_place(spec, likeness) if likeness is not None else None
        if place is not None:
            placed = self._rank_spec(place, trace, view, viewer)
            if place_found(place, placed):
                what = (
                    f"no {parsed.target.describe()} in the map"
                    if parsed.target.labels
                    else f"nothing mapped is in or on the {place.target.describe()}"
                )
                trace.append(
                    f"{what}: answering where the request places it, the {place.target.describe()}"
                )
                spec, ranked = place, placed
        trace.extend(explain_ranking(snap, ranked, k))
        timings["retrieve"] = _ms(t1)
        t2 = time.perf_counter()
        do_verify = self.config.retrieval.verify if verify is None else verify
        live = ranked if _answerable(spec, ranked) else []
        chosen, verified = self._choose(snap, spec, live, text, do_verify, trace)
        timings["verify"] = _ms(t2)
        if chosen is not None:
            result.answer = {
                **node_summary(snap, chosen.id),
                "score": round(chosen.score, 4),
                "verified": verified,
            }
            trace.append(f"answer: {chosen.id} {result.answer['label']} (S={chosen.score:.2f})")
        elif ranked:
            trace.append("no answer: no candidate meets any of the requested constraints")
        else:
            trace.append(f"no answer: nothing in the map matches {parsed.target.describe()!r}")
        if conversation is not None:
            ids = tuple(c.id for c in ranked[:k])
            conversation.add_turn(parsed, chosen.id if chosen else None, ids)
        result.candidates = [candidate_dict(snap, c) for c in ranked[:k]]
        result.explain = plan.explain() if explain else None
        return self._finish(result, trace, timings, start)

    @staticmethod
    def _finish(
        result: QueryResult, trace: list[str], timings: dict[str, float], start: float
    ) -> QueryResult:
        result.trace = trace
        result.timings_ms = {**timings, "total": _ms(start)}
        return result

    # -------------------------------------------------------------- verify
    def _choose(
        self,
        snap: MapSnapshot,
        spec: NodeSpec,
        ranked: Sequence[Scored],
        text: str,
        verify: bool,
        trace: list[str],
    ) -> tuple[Scored | None, bool | None]:
        """The answer: the first of the top ``verify_depth`` candidates that passes
        visual verification (the top one, unverified, when verification is off or none
        passes). Only candidates within ``retrieval.verify_max_gap`` of the best score are
        tried: a crop that looks off never hands the answer to a candidate that does not
        match the request (a desk for "the white computer"). With
        ``retrieval.verify_segmenter`` off the target label is not grounded first: the
        verifier alone judges the recorded detection's crop."""
        if not ranked:
            return None, None
        if not verify:
            return ranked[0], None
        depth = self.config.retrieval.verify_depth
        use_segmenter = self.config.retrieval.verify_segmenter
        segmenter = self._get_segmenter(trace) if use_segmenter else None
        tried = verification_candidates(ranked, depth, self.config.retrieval.verify_max_gap)
        for cand in tried:
            node = snap.objects.get(cand.id)
            if node is None:
                trace.append(f"verify {cand.id}: not an object, nothing to check visually")
                return cand, None
            ev = self._evidence(snap, node, spec, cand, text)
            if use_segmenter:
                prompts = [node.label, *sorted(ev.wanted_labels() - {node.label})][:4]
                found, why, box = ground(ev, segmenter, prompts)
            else:
                found, why, box = skip_grounding(ev)
            if found is None:  # no picture to check; the graph can still contradict it
                failures = graph_failures(ev)
                if failures:
                    trace.append(
                        f"verify {cand.id}: rejected by the graph ({'; '.join(failures)}); "
                        "no picture to check"
                    )
                    continue
                trace.append(f"verify {cand.id}: unverified ({why}); kept")
                return cand, None
            if not found:
                trace.append(f"verify {cand.id}: rejected ({why}); trying the next candidate")
                continue
            verdict = self.verifier.verify(ev, box)
            if verdict.ok is False:
                trace.append(
                    f"verify {cand.id}: rejected by {self.verifier.name} ({verdict.reason})"
                )
                continue
            trace.append(f"verify {cand.id}: confirmed ({why}; {verdict.reason})")
            return cand, verdict.ok
        trace.append(
            f"verify: none of the top {len(tried)} passed; answering the "
            "best-ranked candidate unverified"
        )
        return ranked[0], False

    def _evidence(
        self, snap: MapSnapshot, node: ObjectNode, spec: NodeSpec, cand: Scored, text: str
    ) -> Evidence:
        ev = Evidence(node=node, spec=spec, scored=cand, request=text)
        kf_id = node.best_keyframe or (node.keyframe_ids[-1] if node.keyframe_ids else None)
        if kf_id is None:
            return ev
        try:
            # a keyframe's metadata does not change while the snapshot lives
            meta = snap.memo(("keyframe", kf_id), lambda: self.store.get_keyframe(kf_id))
        except NodeNotFoundError:
            return ev
        blob = self.store.keyframe_blob(kf_id)
        jpeg, feature = blob if blob is not None else (None, None)
        ev.keyframe = dataclasses.replace(meta, jpeg=jpeg, global_feature=feature)
        ev.detection = dict(snap.seen_in.get((node.id, kf_id), {}))
        if ev.keyframe.jpeg:
            ev.image = decode_jpeg(ev.keyframe.jpeg)
        return ev
