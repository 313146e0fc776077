"""The semantic stream's per-keyframe work (paper §III-B "Semantic Stream"): segment,
back-project, encode, associate and fuse, then describe the nodes that are new.

Backends are injected (see :mod:`inherit_sg.perception.registry`), so the same code runs
with the offline defaults, SAM3/DINOv3 adapters or a VLM describer.
"""

from __future__ import annotations

import logging
from collections import Counter
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from inherit_sg.mapping.backproject import Observation, observe
from inherit_sg.mapping.object_map import ObjectMap
from inherit_sg.model import Frame
from inherit_sg.perception.auto_segmenter import UNNAMED_WARNING
from inherit_sg.perception.base import (
    Describer,
    Detection,
    ObjectObservation,
    Segmenter,
    VisualEncoder,
)
from inherit_sg.perception.colour_names import colour_name_in_frame
from inherit_sg.perception.describer import UNNAMED, is_round_footprint
from inherit_sg.perception.material import (
    TextureStats,
    classify,
    frame_noise,
    fuse_votes,
    texture_stats,
)

log = logging.getLogger(__name__)

# Building parts the segmenter may report that are not objects of the map.
BACKGROUND_LABELS = frozenset({"wall", "floor", "ceiling", "background", "unlabeled", "void"})
# Keyframes (with detections) between two samples of the camera noise floor (materials).
NOISE_EVERY = 8


class LabelEmbedder(Protocol):
    """Anything that embeds short texts into unit vectors (the text embedder)."""

    def embed(self, texts: list[str]) -> np.ndarray:
        """(n, dim) unit vectors."""
        ...


class LabelSimilarity:
    """Cosine similarity of label embeddings, cached per label."""

    def __init__(self, embedder: LabelEmbedder) -> None:
        self._embedder = embedder
        self._vectors: dict[str, np.ndarray] = {}

    def _vec(self, label: str) -> np.ndarray:
        if label not in self._vectors:
            self._vectors[label] = self._embedder.embed([label])[0]
        return self._vectors[label]

    def __call__(self, a: str, b: str) -> float:
        return 1.0 if a == b else float(self._vec(a) @ self._vec(b))


@dataclass
class KeyframeStats:
    """What the semantic stream did with one keyframe."""

    detections: int = 0
    observations: int = 0
    created: int = 0
    matched: int = 0
    by_stage: Counter[int] = field(default_factory=Counter)


@dataclass
class Perceived:
    """What one keyframe shows, worked out without the map: its detections turned into
    3D observations with visual features, each detection's colour name and texture
    statistics, and (on every ``NOISE_EVERY``-th keyframe with detections) a sample of
    the camera's noise floor."""

    observations: list[Observation]
    detections: list[Detection]
    colours: list[str]
    textures: list[TextureStats | None]
    noise_sample: float | None = None
    # segmented by a fallback that cannot name things, for want of instance masks
    unmasked: bool = False


@dataclass
class KeyframePerceiver:
    """The part of the semantic stream that does not read the map: segment,
    back-project, encode, name colours and measure textures (its only state is the
    count of keyframes for noise sampling). Most of the stream's time goes here (house
    811 at 640×480: ~100 ms of the ~125 ms a keyframe takes, global updates aside)."""

    segmenter: Segmenter
    encoder: VisualEncoder
    # small things (books, bottles, laptops) cover only ~60–150 px in a 320×240 view
    min_pixels: int = 60
    keyframes_seen: int = 0  # keyframes with detections so far (noise sampling)

    def __call__(self, frame: Frame) -> Perceived:
        """What ``frame`` shows (see :class:`Perceived`)."""
        kept: list[Detection] = []
        observations: list[Observation] = []
        for det in self.segmenter.segment(frame):
            if det.label in BACKGROUND_LABELS or det.area < self.min_pixels:
                continue
            obs = observe(frame, det.mask, det.label, det.score)
            if obs is not None:
                observations.append(obs)
                kept.append(det)
        if observations:
            feats = self.encoder.encode(frame.rgb, [d.mask for d in kept])
            for obs, feat in zip(observations, feats, strict=True):
                obs.visual_feature = feat
        sample = None
        if kept:
            if self.keyframes_seen % NOISE_EVERY == 0:
                sample = frame_noise(frame.rgb)
            self.keyframes_seen += 1
        return Perceived(
            observations=observations,
            detections=kept,
            colours=[colour_name_in_frame(frame.rgb, d.mask) for d in kept],
            textures=[texture_stats(frame.rgb, d.mask) for d in kept],
            noise_sample=sample,
            unmasked=frame.instances is None and bool(getattr(self.segmenter, "falls_back", False)),
        )


@dataclass
class SemanticStream:
    """Turns keyframes into fused object nodes."""

    segmenter: Segmenter
    encoder: VisualEncoder
    describer: Describer
    objects: ObjectMap
    colour_votes: dict[str, Counter[str]] = field(default_factory=dict)
    material_votes: dict[str, Counter[str]] = field(default_factory=dict)
    # the camera's noise floor: the median of the samples the perceiver took
    noise_samples: list[float] = field(default_factory=list)
    noise_floor: float = 0.0
    unmasked_frames: int = 0  # keyframes segmented without instance masks (see Perceived)
    perceiver: KeyframePerceiver = field(init=False)

    def __post_init__(self) -> None:
        self.perceiver = KeyframePerceiver(self.segmenter, self.encoder)

    def perceive(self, frame: Frame) -> Perceived:
        """What ``frame`` shows (see :class:`KeyframePerceiver`)."""
        return self.perceiver(frame)

    def integrate(
        self, frame: Frame, seen: Perceived, floor_id: str | None
    ) -> tuple[list[tuple[str, Detection]], KeyframeStats]:
        """Associate and fuse one keyframe's observations; new nodes get a description.
        Returns each detection with the node it went to."""
        observations, detections = seen.observations, seen.detections
        if seen.unmasked:
            if self.unmasked_frames == 0:
                log.warning("frames without instance masks: %s", UNNAMED_WARNING)
            self.unmasked_frames += 1
        result = self.objects.integrate(observations, floor_id)
        stats = KeyframeStats(
            detections=len(detections),
            observations=len(observations),
            created=len(result.created),
            matched=len(result.matched),
            by_stage=Counter(m.stage for m in result.matched),
        )
        node_of = {m.observation: m.node_id for m in result.matched}
        created = iter(result.created)
        assigned: list[tuple[str, Detection]] = []
        if seen.noise_sample is not None:
            self.noise_samples.append(seen.noise_sample)
            self.noise_floor = float(np.median(self.noise_samples))
        for i, (obs, det) in enumerate(zip(observations, detections, strict=True)):
            node_id = node_of.get(i)
            if node_id is None:
                node_id = next(created)
                self._describe(node_id, frame, det, obs)
            self._vote_colour(node_id, seen.colours[i])
            self._vote_material(node_id, seen.textures[i], self.noise_floor)
            assigned.append((node_id, det))
        return assigned, stats

    def _describe(self, node_id: str, frame: Frame, det: Detection, obs: Observation) -> None:
        extent = tuple(float(v) for v in obs.bbox.size)
        round_footprint = det.label == UNNAMED and is_round_footprint(obs.points)
        crop = ObjectObservation.from_frame(
            frame, det, (extent[0], extent[1], extent[2]), round_footprint=round_footprint
        )
        self.objects.objects[node_id].node.description = self.describer.describe(crop)

    def _vote_colour(self, node_id: str, colour: str) -> None:
        votes = self.colour_votes.setdefault(node_id, Counter())
        votes[colour] += 1
        node = self.objects.objects[node_id].node
        node.attributes["colour"] = votes.most_common(1)[0][0]

    def _vote_material(self, node_id: str, texture: TextureStats | None, noise: float) -> None:
        """Material from the texture of each view (``noise``: the camera's noise floor);
        views that cannot tell do not vote, and the attribute is kept only while the
        votes agree (:func:`fuse_votes`)."""
        votes = self.material_votes.setdefault(node_id, Counter())
        seen = "unknown" if texture is None else classify(texture, noise)
        if seen != "unknown":
            votes[seen] += 1
        node = self.objects.objects[node_id].node
        fused = fuse_votes(votes)
        if fused is None:
            node.attributes.pop("material", None)
        else:
            node.attributes["material"] = fused
