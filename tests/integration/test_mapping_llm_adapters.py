"""The semantic stream's model-backed roles (area labeller, relation verifier, soft
trigger) against a real local HTTP server speaking OpenAI chat completions."""

from __future__ import annotations

import base64
import json
import re
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler
from typing import Any

import cv2
import numpy as np
import pytest

from inherit_sg.config import Config, LLMConfig
from inherit_sg.errors import NodeNotFoundError
from inherit_sg.llm import ChatClient
from inherit_sg.mapping.adapters import (
    create_area_labeller,
    create_relation_verifier,
    create_supervisor,
)
from inherit_sg.mapping.area_labeller import LlmAreaLabeller, RuleAreaLabeller
from inherit_sg.mapping.areas import label_area, summarise_area
from inherit_sg.mapping.relation_verifier import GeometricVerifier, VlmRelationVerifier
from inherit_sg.mapping.relations import Relation
from inherit_sg.mapping.supervisor import HeuristicSupervisor
from inherit_sg.mapping.vlm_supervisor import VlmSupervisor
from tests.local_http import serve_on_loopback

Reply = Callable[[dict[str, Any]], str]


@dataclass
class ServerState:
    """What the fake endpoint answers and what it received."""

    mode: str = "ok"
    reply: Reply = lambda body: "{}"
    requests: list[dict[str, Any]] = field(default_factory=list)


def _handler(state: ServerState) -> type[BaseHTTPRequestHandler]:
    class Handler(BaseHTTPRequestHandler):
        def log_message(self, format: str, *args: Any) -> None:
            pass

        def _send(self, code: int, payload: bytes) -> None:
            try:
                self.send_response(code)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(payload)))
                self.end_headers()
                self.wfile.write(payload)
            except (BrokenPipeError, ConnectionResetError):
                pass  # the client gave up waiting

        def do_POST(self) -> None:
            body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
            state.requests.append(body)
            if state.mode == "500":
                self._send(500, b'{"error": "overloaded"}')
                return
            if state.mode == "slow":
                time.sleep(0.6)
            content = "this is not JSON" if state.mode == "garbage" else state.reply(body)
            reply = {"choices": [{"message": {"role": "assistant", "content": content}}]}
            self._send(200, json.dumps(reply).encode())

    return Handler


@pytest.fixture
def server() -> Iterator[tuple[str, ServerState]]:
    state = ServerState()
    with serve_on_loopback(_handler(state)) as (_, url):
        yield url, state


def _client(url: str) -> ChatClient:
    return ChatClient(url, "test-model", timeout_s=0.2, retries=0)


def _text(body: dict[str, Any]) -> str:
    content = body["messages"][-1]["content"]
    if isinstance(content, str):
        return content
    return "\n".join(p["text"] for p in content if p["type"] == "text")


def _image(body: dict[str, Any], mime: str) -> np.ndarray:
    parts = body["messages"][-1]["content"]
    urls = [p["image_url"]["url"] for p in parts if p["type"] == "image_url"]
    assert len(urls) == 1
    head, data = urls[0].split(",", 1)
    assert head == f"data:{mime};base64"
    img = cv2.imdecode(np.frombuffer(base64.b64decode(data), np.uint8), cv2.IMREAD_COLOR)
    assert img is not None
    return img


FAILURES = ["500", "garbage", "slow"]


# ------------------------------------------------------------------ area labeller
def test_llm_labeller_asks_with_labels_and_room_and_caches(
    server: tuple[str, ServerState],
) -> None:
    url, state = server
    state.reply = lambda body: json.dumps(
        {"label": " Dining Area ", "summary": "A table with chairs for meals."}
    )
    labeller = LlmAreaLabeller(_client(url))
    assert labeller.label(["table", "chair", "chair"], "kitchen") == (
        "dining area",
        "A table with chairs for meals.",
    )
    prompt = _text(state.requests[0])
    assert "chair, chair, table" in prompt and "kitchen" in prompt
    assert state.requests[0]["response_format"]["type"] == "json_schema"
    # the same cluster in another order is served from the cache
    assert labeller.label(["chair", "table", "chair"], "kitchen")[0] == "dining area"
    assert len(state.requests) == 1 and labeller.failures == 0


@pytest.mark.parametrize("mode", [*FAILURES, "incomplete"])
def test_llm_labeller_falls_back_to_rules(server: tuple[str, ServerState], mode: str) -> None:
    url, state = server
    state.mode = "ok" if mode == "incomplete" else mode
    state.reply = lambda body: json.dumps({"label": "dining area", "summary": ""})
    labels = ["bed", "nightstand", "lamp"]
    got = LlmAreaLabeller(_client(url)).label(labels, "bedroom")
    expected = label_area(labels)
    assert got == (expected, summarise_area(expected, labels))
    assert got == RuleAreaLabeller().label(labels, "bedroom")
    assert len(state.requests) == 1


# --------------------------------------------------------------- relation verifier
def _keyframe() -> bytes:
    img = np.full((120, 160, 3), 200, dtype=np.uint8)
    ok, buf = cv2.imencode(".jpg", img)
    assert ok
    return buf.tobytes()


RELATIONS = [
    Relation("object:1", "object:2", "on", 0.9),
    Relation("object:1", "object:3", "near", 0.6),
    Relation("object:1", "object:2", "near", 0.8),
]
BOXES = {"object:1": (60, 20, 100, 50), "object:2": (20, 50, 140, 110), "object:3": (0, 0, 15, 15)}
LABELS = {"object:1": "cup", "object:2": "table", "object:3": "plant"}


def test_vlm_verifier_keeps_confirmed_relations(server: tuple[str, ServerState]) -> None:
    url, state = server
    state.reply = lambda body: json.dumps(
        {"answers": [{"index": 0, "holds": True}, {"index": 1, "holds": False}]}
    )
    verifier = VlmRelationVerifier(_client(url))
    kept = verifier.verify(RELATIONS, _keyframe(), BOXES, LABELS)
    # confirmed (0), rejected (1), unanswered (2) stays as geometry inferred it
    assert kept == [RELATIONS[0], RELATIONS[2]]
    body = state.requests[0]
    text = _text(body)
    assert "0. Is the cup [box 1] on the table [box 2]?" in text
    assert "1. Is the cup [box 1] near the plant [box 3]?" in text
    img = _image(body, "image/jpeg").astype(int)
    assert img.shape[:2] == (120, 160)
    # box 1 is drawn on the grey keyframe at its left edge, the inside stays grey
    assert abs(img[35, 60] - 200).max() > 60 and abs(img[35, 80] - 200).max() < 30
    # verdicts are remembered: a second pass asks only the unanswered question
    assert verifier.verify(RELATIONS, _keyframe(), BOXES, LABELS) == kept
    assert len(state.requests) == 2
    assert _text(state.requests[1]).endswith("\n0. Is the cup [box 1] near the table [box 2]?")
    verifier.verify(RELATIONS, _keyframe(), BOXES, LABELS)
    assert len(state.requests) == 2


@pytest.mark.parametrize("mode", FAILURES)
def test_vlm_verifier_keeps_geometry_on_failure(server: tuple[str, ServerState], mode: str) -> None:
    url, state = server
    state.mode = mode
    verifier = VlmRelationVerifier(_client(url))
    assert verifier.verify(RELATIONS, _keyframe(), BOXES, LABELS) == RELATIONS
    assert verifier.failures == 1 and len(state.requests) == 1


def test_vlm_verifier_without_image_or_boxes_asks_nothing(
    server: tuple[str, ServerState],
) -> None:
    url, state = server
    verifier = VlmRelationVerifier(_client(url))
    assert verifier.verify(RELATIONS, None, BOXES, LABELS) == RELATIONS
    assert verifier.verify(RELATIONS, _keyframe(), {"object:1": (0, 0, 5, 5)}) == RELATIONS
    assert state.requests == []
    assert GeometricVerifier().verify(RELATIONS, None, {}) == RELATIONS


# ---------------------------------------------------------------- soft trigger
def _png() -> bytes:
    img = np.zeros((40, 60, 3), dtype=np.uint8)
    img[10:30, 10:50] = (0, 120, 255)
    ok, buf = cv2.imencode(".png", img)
    assert ok
    return buf.tobytes()


def test_vlm_supervisor_reads_bev_and_decides(server: tuple[str, ServerState]) -> None:
    url, state = server
    state.reply = lambda body: json.dumps({"update": True, "reason": "a new sofa appeared"})
    sup = VlmSupervisor(_client(url), _png)
    assert sup.should_update("room:1", ["object:1"]) == (
        True,
        "VLM on room:1: a new sofa appeared",
    )
    body = state.requests[0]
    assert "room:1" in _text(body) and "no summary" in _text(body)
    assert _image(body, "image/png").shape == (40, 60, 3)
    sup.should_update("room:1", ["object:1"])
    assert len(state.requests) == 1  # same room and objects: decided already
    sup.summarised("room:1", ["object:1"])
    state.reply = lambda body: json.dumps({"update": False, "reason": "nothing changed"})
    assert sup.should_update("room:1", ["object:1", "object:2"])[0] is False
    assert "covers 1 objects; it now holds 2, 1 of them new and 0 gone" in _text(state.requests[1])


@pytest.mark.parametrize("mode", [*FAILURES, "no-bool"])
def test_vlm_supervisor_falls_back_to_heuristic(server: tuple[str, ServerState], mode: str) -> None:
    url, state = server
    state.mode = "ok" if mode == "no-bool" else mode
    state.reply = lambda body: json.dumps({"update": "yes", "reason": "?"})
    sup = VlmSupervisor(_client(url), _png)
    assert sup.should_update("room:2", ["object:1"]) == (
        True,
        "entered room:2, which has no summary yet",
    )
    sup.summarised("room:2", ["object:1"])
    assert sup.should_update("room:2", ["object:1"])[0] is False  # heuristic was informed
    assert sup.failures == 2


def test_vlm_supervisor_without_bev_asks_nothing(server: tuple[str, ServerState]) -> None:
    url, state = server

    def no_map() -> bytes:
        raise NodeNotFoundError("no BEV map for floor None: it has no observations yet")

    sup = VlmSupervisor(_client(url), no_map)
    assert sup.should_update("room:3", [])[0] is True
    assert state.requests == [] and sup.failures == 1


# --------------------------------------------------------------------- factory
def test_factory_picks_offline_defaults_without_endpoint() -> None:
    cfg = Config()
    assert isinstance(create_area_labeller(cfg), RuleAreaLabeller)
    assert isinstance(create_relation_verifier(cfg), GeometricVerifier)
    assert isinstance(create_supervisor(cfg, _png), HeuristicSupervisor)


def test_factory_picks_models_with_endpoint(server: tuple[str, ServerState]) -> None:
    url, state = server
    state.reply = lambda body: json.dumps({"label": "reading corner", "summary": "A chair."})
    cfg = Config(llm=LLMConfig(endpoint=url, model="m", retries=0))
    labeller = create_area_labeller(cfg)
    assert isinstance(labeller, LlmAreaLabeller)
    assert labeller.label(["armchair", "lamp"], None)[0] == "reading corner"
    assert state.requests[0]["model"] == "m"
    assert isinstance(create_relation_verifier(cfg), VlmRelationVerifier)
    assert isinstance(create_supervisor(cfg, _png), VlmSupervisor)


# ------------------------------------------------------------------ whole build
def _model_reply(body: dict[str, Any]) -> str:
    name = body["response_format"]["json_schema"]["name"]
    if name == "area_label":
        return json.dumps({"label": "model area", "summary": "Named by the model."})
    if name == "relation_check":
        count = len(re.findall(r"^\d+\. Is ", _text(body), re.M))
        return json.dumps({"answers": [{"index": i, "holds": False} for i in range(count)]})
    return json.dumps({"update": False, "reason": "summary is current"})


def test_build_uses_the_endpoint_for_all_three_roles(
    server: tuple[str, ServerState], tmp_path: Any
) -> None:
    from inherit_sg.facade import build_map
    from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset
    from inherit_sg.model import EdgeKind, Layer
    from inherit_sg.store import MapStore

    url, state = server
    state.reply = _model_reply
    write_dataset(generate_house(4, 1, 4), tmp_path / "h", width=160, height=120, workers=1)
    cfg = Config(llm=LLMConfig(endpoint=url, model="m", retries=0, timeout_s=5.0))
    build_map(tmp_path / "h", tmp_path / "m", config=cfg, max_frames=60)
    names = [b["response_format"]["json_schema"]["name"] for b in state.requests]
    assert {"area_label", "relation_check", "soft_trigger"} <= set(names)
    with MapStore.open(tmp_path / "m") as store:
        graph = store.load_graph()
    areas = list(graph.nodes(Layer.AREA))
    assert areas and all(a.label == "model area" for a in areas)
    assert all(
        r.prop("predicate") in ("on", "above", "inside", "next to", "near")
        for r in graph.edges(EdgeKind.RELATION)
    )
