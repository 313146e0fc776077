"""VLM describer against a real local HTTP server speaking OpenAI chat completions."""

from __future__ import annotations

import base64
import json
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler
from typing import Any

import cv2
import numpy as np
import pytest

from inherit_sg.config import Config, LLMConfig
from inherit_sg.errors import EndpointError
from inherit_sg.llm import ChatClient
from inherit_sg.perception import create_describer
from inherit_sg.perception.base import ObjectObservation
from inherit_sg.perception.colour_names import colour_name
from inherit_sg.perception.describer import FallbackDescriber, TemplateDescriber
from inherit_sg.perception.vlm_describer import VlmDescriber, clean_answer, image_data_url
from tests.local_http import free_port, serve_on_loopback


@dataclass
class ServerState:
    """What the fake endpoint does and what it received."""

    mode: str = "ok"
    requests: list[dict[str, Any]] = field(default_factory=list)
    headers: list[dict[str, str]] = field(default_factory=list)
    images: list[np.ndarray] = field(default_factory=list)


def _decode_image(body: dict[str, Any]) -> np.ndarray:
    """The image of the last user message, decoded from its data URL (or an error)."""
    parts = body["messages"][-1]["content"]
    urls = [p["image_url"]["url"] for p in parts if p.get("type") == "image_url"]
    assert len(urls) == 1, "expected exactly one image part"
    head, data = urls[0].split(",", 1)
    assert head == "data:image/jpeg;base64"
    img = cv2.imdecode(np.frombuffer(base64.b64decode(data), np.uint8), cv2.IMREAD_COLOR)
    assert img is not None, "image part is not a decodable JPEG"
    return np.ascontiguousarray(img[..., ::-1])


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
                pass  # the client gave up waiting (timeout test)

        def do_POST(self) -> None:
            if self.path != "/v1/chat/completions":
                self._send(404, b'{"error": "not found"}')
                return
            body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
            state.requests.append(body)
            state.headers.append(dict(self.headers))
            if state.mode == "slow":
                time.sleep(0.6)
            if state.mode == "garbage":
                self._send(200, b"<html>this is not json</html>")
                return
            if state.mode == "no-choices":
                self._send(200, b'{"id": "x", "object": "chat.completion"}')
                return
            if state.mode == "blank":
                content = '  ""  '
            else:
                try:
                    img = _decode_image(body)
                except (AssertionError, KeyError, TypeError, ValueError) as exc:
                    self._send(400, json.dumps({"error": str(exc)}).encode())
                    return
                state.images.append(img)
                h, w = img.shape[:2]
                centre = img[h // 3 : 2 * h // 3, w // 3 : 2 * w // 3]
                content = f'"A {colour_name(centre)} object, {w}x{h} pixels."\nExtra line.'
            reply = {
                "choices": [{"index": 0, "message": {"role": "assistant", "content": content}}]
            }
            self._send(200, json.dumps(reply).encode())

    return Handler


@pytest.fixture
def server() -> Iterator[tuple[str, ServerState]]:
    state = ServerState()
    with serve_on_loopback(_handler(state)) as (_, url):
        yield url, state


def _obs(label: str = "chair", room: str | None = "kitchen") -> ObjectObservation:
    rgb = np.zeros((120, 90, 3), dtype=np.uint8)
    rgb[:] = (40, 160, 60)
    rgb[20:100, 15:75] = (190, 40, 40)
    mask = np.zeros((120, 90), dtype=bool)
    mask[20:100, 15:75] = True
    return ObjectObservation(label, rgb, mask, (0.5, 0.45, 0.9), room)


def _describer(url: str, **kwargs: Any) -> VlmDescriber:
    client = ChatClient(
        url, "test-vlm", timeout_s=kwargs.pop("timeout_s", 5.0), retries=0, **kwargs
    )
    return VlmDescriber(client, max_side=64)


def test_request_carries_image_and_context(server: tuple[str, ServerState]) -> None:
    url, state = server
    text = _describer(url, api_key="sk-test").describe(_obs())
    assert text == "A red object, 48x64 pixels."  # first line, quotes stripped
    body = state.requests[0]
    assert body["model"] == "test-vlm"
    assert body["messages"][0]["role"] == "system"
    parts = body["messages"][1]["content"]
    prompt = next(p["text"] for p in parts if p["type"] == "text")
    assert "chair" in prompt and "kitchen" in prompt and "0.50 × 0.45 × 0.90 m" in prompt
    img = state.images[0]
    assert img.shape == (64, 48, 3)  # downsized to max_side, aspect kept
    assert state.headers[0].get("Authorization") == "Bearer sk-test"


def test_background_is_darkened_but_object_kept(server: tuple[str, ServerState]) -> None:
    url, state = server
    _describer(url).describe(_obs())
    img = state.images[0].astype(int)
    assert abs(img[32, 24] - np.array([190, 40, 40])).max() < 20  # object pixel
    assert abs(img[2, 2] - np.array([13, 53, 20])).max() < 20  # background at a third


def test_repeated_request_is_served_from_cache(server: tuple[str, ServerState]) -> None:
    url, state = server
    d = _describer(url)
    assert d.describe(_obs()) == d.describe(_obs())
    assert len(state.requests) == 1


def test_config_built_describer(server: tuple[str, ServerState]) -> None:
    url, state = server
    cfg = Config(perception={"describer": "vlm"}, llm=LLMConfig(endpoint=url, model="m", retries=0))
    d = create_describer(cfg)
    assert isinstance(d, VlmDescriber)
    assert d.describe(_obs()).startswith("A red object")
    assert state.images[0].shape[:2] == (120, 90)  # under the default max side: not resized


@pytest.mark.parametrize("mode", ["garbage", "no-choices", "blank"])
def test_garbage_answers_raise_endpoint_error(server: tuple[str, ServerState], mode: str) -> None:
    url, state = server
    state.mode = mode
    with pytest.raises(EndpointError, match=r"127\.0\.0\.1"):
        _describer(url).describe(_obs())


def test_timeout_raises_endpoint_error(server: tuple[str, ServerState]) -> None:
    url, state = server
    state.mode = "slow"
    t0 = time.monotonic()
    with pytest.raises(EndpointError, match="did not answer"):
        _describer(url, timeout_s=0.2).describe(_obs())
    assert time.monotonic() - t0 < 1.0


def test_endpoint_down_raises_and_fallback_describes_offline() -> None:
    url = f"http://127.0.0.1:{free_port()}/v1"
    with pytest.raises(EndpointError, match="cannot reach"):
        _describer(url).describe(_obs())
    fb = FallbackDescriber(_describer(url), TemplateDescriber())
    assert (
        fb.describe(_obs()) == "a red chair, about 0.5 × 0.5 × 0.9 m, medium-sized, in the kitchen"
    )
    assert fb.failures == 1


def test_fallback_prefers_live_endpoint(server: tuple[str, ServerState]) -> None:
    url, _ = server
    fb = FallbackDescriber(_describer(url), TemplateDescriber())
    assert fb.describe(_obs()).startswith("A red object") and fb.failures == 0


def test_image_data_url_and_clean_answer_helpers() -> None:
    rgb = np.full((10, 400, 3), 200, dtype=np.uint8)
    url = image_data_url(rgb, max_side=100)
    img = cv2.imdecode(np.frombuffer(base64.b64decode(url.split(",", 1)[1]), np.uint8), 1)
    assert img is not None and img.shape[:2] == (2, 100)
    assert clean_answer("\n  'A lamp.'  \n", "x") == "A lamp."
    assert clean_answer("w " * 400, "x").endswith("…")
    with pytest.raises(EndpointError, match="empty"):
        clean_answer(" \n ``", "x")
