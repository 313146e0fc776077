"""Visual verification: grounding on the SEEN_IN record, pixel colour checks on the
crop, graph checks, the segmenter path and the VLM verifier's offline fallback."""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np
import pytest

from inherit_sg.config import LLMConfig
from inherit_sg.llm.client import ChatClient
from inherit_sg.model import Frame, Keyframe, ObjectNode, Pose
from inherit_sg.perception.base import Detection, make_detection
from inherit_sg.retrieval import parse_rules
from inherit_sg.retrieval.graph_checks import PROXIMITY_NOTE
from inherit_sg.retrieval.plan import Compiler
from inherit_sg.retrieval.scoring import Scored, Term
from inherit_sg.retrieval.verify import (
    NAMED_MIN,
    Evidence,
    OfflineVerifier,
    central_crop,
    decode_jpeg,
    frame_from_image,
    graph_failures,
    ground,
    recorded_box,
    skip_grounding,
)
from inherit_sg.retrieval.verify_vlm import VlmVerifier, outlined
from tests.unit.retrieval_fixtures import hash_similarity, small_snapshot

EYE = Pose(tuple(float(v) for v in np.eye(4).ravel()))
RED, BLUE, GREY = (190, 40, 40), (45, 80, 185), (128, 128, 128)


def jpeg(colour: tuple[int, int, int], size: tuple[int, int] = (240, 320)) -> bytes:
    """A grey picture with a coloured rectangle at x 100–200, y 60–180 (RGB)."""
    img = np.full((*size, 3), GREY, dtype=np.uint8)
    img[60:180, 100:200] = colour
    ok, buf = cv2.imencode(".jpg", img[..., ::-1])
    assert ok
    return buf.tobytes()


def evidence(
    text: str, node_id: str, colour: tuple[int, int, int] | None, detection: dict | None = None
) -> Evidence:
    snap = small_snapshot()
    spec = Compiler(snap, hash_similarity()).compile(parse_rules(text)).target
    node = snap.objects[node_id]
    assert isinstance(node, ObjectNode)
    kf = Keyframe("kf:1", "s1", 0.0, EYE, width=320, height=240)
    ev = Evidence(node=node, spec=spec, scored=Scored(node_id), request=text, keyframe=kf)
    ev.detection = (
        detection if detection is not None else {"label": node.label, "bbox": [100, 60, 199, 179]}
    )
    if colour is not None:
        ev.image = decode_jpeg(jpeg(colour))
    return ev


def test_jpeg_decode_box_scaling_and_crop() -> None:
    img = decode_jpeg(jpeg(RED, (480, 640)))
    assert img is not None and img.shape == (480, 640, 3)
    ev = evidence("the red chair", "obj:c3", RED)
    assert ev.image is not None and ev.image.shape == (240, 320, 3)
    ev.keyframe = Keyframe("kf:1", "s1", 0.0, EYE, width=640, height=480)  # box in 640x480
    ev.detection = {"bbox": [200, 120, 398, 358]}
    assert recorded_box(ev) == (100, 60, 199, 179)
    crop = central_crop(ev.image, (100, 60, 199, 179))
    assert crop.shape[0] == pytest.approx(60, abs=2) and crop.shape[1] == pytest.approx(50, abs=2)
    assert decode_jpeg(b"not a jpeg") is None


def test_offline_verifier_checks_colour_on_the_crop() -> None:
    ev = evidence("the red chair", "obj:c3", RED)
    ok, why, box = ground(ev, None, ["chair"])
    assert ok is True and box == (100, 60, 199, 179) and "chair" in why
    assert OfflineVerifier().verify(ev, box).ok is True
    ev = evidence("the red chair", "obj:c3", BLUE)
    verdict = OfflineVerifier().verify(ev, recorded_box(ev))
    assert verdict.ok is False and "looks blue" in verdict.reason
    ev = evidence("a chair that is not red", "obj:c3", RED)
    assert OfflineVerifier().verify(ev, recorded_box(ev)).ok is False


def test_grounding_needs_a_compatible_detection() -> None:
    ev = evidence("the red chair", "obj:c3", RED, {"label": "table", "bbox": [1, 1, 5, 5]})
    ok, why, _ = ground(ev, None, ["chair"])
    assert ok is False and "table" in why
    ev = evidence("the red chair", "obj:c3", RED, {})
    assert ground(ev, None, ["chair"])[0] is None
    ev.keyframe = None
    assert ground(ev, None, ["chair"]) == (None, "no keyframe to verify against", None)


def test_graph_failures_reject_unsupported_constraints() -> None:
    ev = evidence("the chair next to the table", "obj:c2", None)
    ev.scored.terms["c2"] = Term("c2", "relation", 0.8, 1, 0.0)
    assert graph_failures(ev) == ["c2 (relation) not found in the graph"]
    ev.scored.terms["c2"] = Term("c2", "relation", 0.8, -1, 1.0, "c2 -[near]-> t1")
    assert "negated relation" in graph_failures(ev)[0]
    ev.scored.terms["c2"] = Term("c2", "relation", 0.8, 1, 1.0)
    assert graph_failures(ev) == []
    # standing near the landmark is credited in ranking, but supports no relation
    near = f"{PROXIMITY_NOTE}; 0.4 m from obj:t1"
    ev.scored.terms["c2"] = Term("c2", "relation", 0.8, 1, 0.2, near)
    assert graph_failures(ev) == ["c2 (relation) not found in the graph"]


def test_graph_failures_reject_a_thing_that_is_not_what_was_asked() -> None:
    ev = evidence("the chair", "obj:c2", None)
    ev.scored.terms["c1"] = Term("c1", "label", 1.0, 1, 0.12, "found by text search")
    failures = graph_failures(ev)
    assert len(failures) == 1 and "barely matches" in failures[0]
    ev.scored.terms["c1"] = Term("c1", "label", 1.0, 1, NAMED_MIN, "a kind of chair")
    assert graph_failures(ev) == []


def test_the_maps_measured_colour_outweighs_one_crop() -> None:
    """A colour the map measured over all views of the object is not overruled by one
    crop; a colour or material the map measured otherwise rejects the candidate."""
    ev = evidence("the red chair", "obj:c3", BLUE)
    c2 = next(c.id for c in ev.spec.constraints if c.kind == "attribute")
    ev.scored.terms[c2] = Term(c2, "attribute", 0.6, 1, 1.0, "colour is red")
    assert OfflineVerifier().verify(ev, recorded_box(ev)).ok is True
    ev.scored.terms[c2] = Term(c2, "attribute", 0.6, 1, 0.0, "colour is blue")
    verdict = OfflineVerifier().verify(ev, recorded_box(ev))
    assert verdict.ok is False and "contradicted by the map: colour is blue" in verdict.reason
    # an unobserved value rejects nothing by itself
    ev = evidence("the red chair", "obj:c3", None)
    ev.scored.terms[c2] = Term(c2, "attribute", 0.6, 1, 0.35, "colour not observed")
    assert graph_failures(ev) == []


class BoxSegmenter:
    """A real (if tiny) segmenter: thresholds saturated pixels of the picture."""

    name = "saturation"

    def segment(self, frame: Frame, prompts: Sequence[str] | None = None) -> list[Detection]:
        rgb = frame.rgb.astype(int)
        mask = (rgb.max(axis=2) - rgb.min(axis=2)) > 60
        det = make_detection(mask, (prompts or ["object"])[0], 0.9)
        return [det] if det is not None else []


def test_segmenter_grounding_on_the_keyframe_image() -> None:
    ev = evidence("the red chair", "obj:c3", RED)
    ok, why, box = ground(ev, BoxSegmenter(), ["chair"])
    assert ok is True and "saturation found chair" in why
    assert box is not None and abs(box[0] - 100) <= 2 and abs(box[3] - 179) <= 2
    ev = evidence("the red chair", "obj:c3", GREY)
    assert ground(ev, BoxSegmenter(), ["chair"])[0] is False
    frame = frame_from_image(np.zeros((8, 10, 3), np.uint8), "kf")
    assert frame.validate().rgb.shape == (8, 10, 3)


def test_vlm_verifier_falls_back_offline_when_the_endpoint_is_down() -> None:
    client = ChatClient.from_config(
        LLMConfig(endpoint="http://127.0.0.1:9", timeout_s=0.2, retries=0)
    )
    ev = evidence("the red chair", "obj:c3", BLUE)
    verdict = VlmVerifier(client).verify(ev, recorded_box(ev))
    assert verdict.ok is False and verdict.reason.startswith("VLM failed")
    messages = VlmVerifier(client).messages(ev, (100, 60, 199, 179))
    parts = messages[1]["content"]
    assert "the red chair" in parts[0]["text"]
    assert parts[1]["image_url"]["url"].startswith("data:image/jpeg;base64,")
    assert ev.image is not None
    drawn = outlined(ev.image, (10, 10, 50, 50))
    assert tuple(drawn[10, 30]) == (0, 255, 0) and tuple(ev.image[10, 30]) != (0, 255, 0)


def test_skipping_the_segmenter_step_keeps_the_recorded_box() -> None:
    ev = evidence("the red chair", "obj:c3", RED, {"label": "table", "bbox": [100, 60, 199, 179]})
    assert ground(ev, None, ["chair"])[0] is False  # the label does not ground
    ok, why, box = skip_grounding(ev)
    assert ok is True and "skipped" in why and box == (100, 60, 199, 179)
    assert OfflineVerifier().verify(ev, box).ok is True
    ev.keyframe = None
    assert skip_grounding(ev)[0] is None


def test_verification_never_tries_candidates_far_below_the_best() -> None:
    from inherit_sg.retrieval.engine import verification_candidates

    def scored(node_id: str, label_sim: float, colour_sim: float) -> Scored:
        cand = Scored(node_id)
        cand.terms["c1"] = Term("c1", "label", 1.0, 1, label_sim, "")
        cand.terms["c2"] = Term("c2", "attribute", 0.6, 1, colour_sim, "")
        return cand

    computer = scored("obj:pc", 1.0, 1.0)  # the white computer asked for
    grey_pc = scored("obj:pc2", 1.0, 0.0)  # another computer, colour off
    desk = scored("obj:desk", 0.13, 0.0)  # a related label only
    ranked = [computer, grey_pc, desk]
    assert verification_candidates(ranked, 3, 1.0) == [computer, grey_pc]
    assert verification_candidates(ranked, 3, 5.0) == ranked
    assert verification_candidates(ranked, 1, 5.0) == [computer]
    assert verification_candidates(ranked, 3, 0.0) == [computer]
    assert verification_candidates([], 3, 1.0) == []
