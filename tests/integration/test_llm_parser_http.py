"""The multi-role LLM parser and its chat client against a real local HTTP server that
speaks the OpenAI chat-completions protocol (no mocks: real sockets, real JSON).

The server answers each role (decomposition, negations, weights) from a script and can
misbehave on demand: HTTP 500 / 429 / 404, slow answers, garbage bodies, off-schema JSON.
"""

from __future__ import annotations

import contextlib
import json
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler
from typing import Any

import pytest

from inherit_sg.config import LLMConfig
from inherit_sg.errors import EndpointError
from inherit_sg.llm import ChatClient
from inherit_sg.retrieval import RelationConstraint
from inherit_sg.retrieval.llm_parser import LLMParser
from tests.local_http import serve_on_loopback

TEXT = "the mug not on the table next to the window"

DECOMPOSITION = {
    "target": {"layer": "object", "labels": ["mugs"], "function": None, "plural": False},
    "constraints": [
        {
            "kind": "relation", "text": "not on the table", "key": None, "value": None,
            "predicate": "on", "level": None, "relative": None, "measure": None,
            "ordinal": None, "direction": None, "landmark2": None,
            "landmark": {"labels": ["table"], "constraints": [{
                "kind": "relation", "text": "next to the window", "key": None, "value": None,
                "predicate": "next_to", "level": None, "relative": None, "measure": None,
                "ordinal": None, "direction": None, "landmark2": None,
                "landmark": {"labels": ["window"], "constraints": []},
            }]},
        },
        {
            "kind": "room", "text": "in the restroom", "key": None, "value": "restroom",
            "predicate": None, "landmark": None, "landmark2": None, "level": None,
            "relative": None, "measure": None, "ordinal": None, "direction": None,
        },
    ],
    "reference": "none",
    "no_target_reason": None,
}  # fmt: skip
NEGATIONS = {"negated": ["c2"]}
WEIGHTS = {"weights": [{"id": "c1", "weight": 1.0}, {"id": "c2", "weight": 0.95},
                       {"id": "c2.1", "weight": 0.5}]}  # fmt: skip


@dataclass
class Script:
    """What the fake endpoint answers, and what it saw."""

    answers: dict[str, Any] = field(default_factory=dict)
    status: Callable[[int], int] = lambda n: 200  # request number (1-based) -> HTTP status
    delay_s: float = 0.0
    raw_body: bytes | None = None
    content: str | None = None
    seen: list[dict[str, Any]] = field(default_factory=list)
    headers: list[dict[str, str]] = field(default_factory=list)

    def roles(self) -> list[str]:
        return [r["response_format"]["json_schema"]["name"] for r in self.seen]


class _Handler(BaseHTTPRequestHandler):
    script: Script

    def do_POST(self) -> None:
        body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        script = self.server.script  # type: ignore[attr-defined]
        script.seen.append(body)
        script.headers.append(dict(self.headers))
        if self.path != "/v1/chat/completions":
            return self._send(404, b'{"error": "no such route"}')
        status = script.status(len(script.seen))
        if status != 200:
            return self._send(status, b'{"error": "scripted failure"}')
        if script.delay_s:
            time.sleep(script.delay_s)
        if script.raw_body is not None:
            return self._send(200, script.raw_body)
        name = body["response_format"]["json_schema"]["name"]
        content = script.content or json.dumps(script.answers[name])
        reply = {"id": "cmpl-1", "object": "chat.completion", "model": body["model"],
                 "choices": [{"index": 0, "finish_reason": "stop",
                              "message": {"role": "assistant", "content": content}}]}  # fmt: skip
        return self._send(200, json.dumps(reply).encode())

    def _send(self, status: int, payload: bytes) -> None:
        self.send_response(status)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(payload)))
        self.end_headers()
        with contextlib.suppress(BrokenPipeError, ConnectionResetError):
            self.wfile.write(payload)  # the client may have given up (timeout tests)

    def log_message(self, format: str, *args: Any) -> None:
        pass


@pytest.fixture
def server() -> Iterator[tuple[str, Script]]:
    script = Script(answers={"decomposition": DECOMPOSITION, "negations": NEGATIONS,
                             "weights": WEIGHTS})  # fmt: skip
    with serve_on_loopback(_Handler) as (httpd, url):
        httpd.script = script  # type: ignore[attr-defined]
        yield url, script


def _parser(endpoint: str, **kwargs: Any) -> LLMParser:
    options = {"timeout_s": 5.0, "retries": 2, "backoff_s": 0.01, **kwargs}
    return LLMParser(ChatClient(endpoint, "test-model", **options))


def test_three_roles_build_the_constraints(server: tuple[str, Script]) -> None:
    endpoint, script = server
    parsed = _parser(endpoint, api_key="sk-test").parse(TEXT)
    assert script.roles() == ["decomposition", "negations", "weights"]
    assert script.headers[0]["Authorization"] == "Bearer sk-test"
    assert script.seen[0]["model"] == "test-model"
    assert script.seen[0]["response_format"]["json_schema"]["strict"] is True
    listing = json.loads(script.seen[1]["messages"][1]["content"])
    assert [c["id"] for c in listing["constraints"]] == ["c1", "c2", "c2.1", "c3"]

    assert parsed.parser == "llm"
    assert parsed.target.labels == ("mug",)  # canonicalised from "mugs"
    label, on, room = parsed.constraints
    assert label.kind == "label" and label.weight == 1.0
    assert isinstance(on, RelationConstraint) and on.predicate == "on"
    assert on.negated and on.polarity == -1 and on.weight == 0.95
    nested = on.landmark.constraints[0]
    assert nested.predicate == "next_to" and not nested.negated and nested.weight == 0.5  # type: ignore[union-attr]
    assert room.kind == "room" and room.type == "bathroom" and room.weight == 0.7  # type: ignore[union-attr]
    assert any("negated c2" in n for n in parsed.notes)


def test_repeated_query_is_served_from_the_cache(server: tuple[str, Script]) -> None:
    endpoint, script = server
    parser = _parser(endpoint)
    first = parser.parse(TEXT)
    second = parser.parse(TEXT)
    assert first == second
    assert len(script.seen) == 3  # one request per role, none for the repeat
    assert parser.client is not None and parser.client.cache.hits == 3


def test_transient_500_is_retried(server: tuple[str, Script]) -> None:
    endpoint, script = server
    script.status = lambda n: 500 if n == 1 else 200
    parsed = _parser(endpoint).parse(TEXT)
    assert parsed.parser == "llm"
    assert script.roles() == ["decomposition", "decomposition", "negations", "weights"]


def test_persistent_500_falls_back_to_rules(server: tuple[str, Script]) -> None:
    endpoint, script = server
    script.status = lambda n: 500
    parsed = _parser(endpoint, retries=2).parse(TEXT)
    assert parsed.parser == "rules"
    assert len(script.seen) == 3  # first try + 2 retries
    assert "decomposer failed" in parsed.notes[0]
    assert "HTTP 500" in parsed.notes[0] and "after 3 attempts" in parsed.notes[0]
    # the rule parse is the real one
    assert parsed.target.labels == ("mug",)
    assert parsed.of_kind("relation")[0].negated


def test_client_error_is_not_retried(server: tuple[str, Script]) -> None:
    endpoint, script = server
    bad_route = endpoint.removesuffix("/v1") + "/nowhere"
    parsed = _parser(bad_route).parse(TEXT)
    assert parsed.parser == "rules" and len(script.seen) == 1
    assert "HTTP 404" in parsed.notes[0]


def test_rate_limit_is_retried(server: tuple[str, Script]) -> None:
    endpoint, script = server
    script.status = lambda n: 429 if n <= 2 else 200
    assert _parser(endpoint).parse(TEXT).parser == "llm"
    assert len(script.seen) == 5


def test_timeout_falls_back(server: tuple[str, Script]) -> None:
    endpoint, script = server
    script.delay_s = 1.0
    start = time.monotonic()
    parsed = _parser(endpoint, timeout_s=0.2, retries=1).parse(TEXT)
    assert time.monotonic() - start < 1.5
    assert parsed.parser == "rules"
    assert "did not answer within 0.2 s" in parsed.notes[0]
    assert len(script.seen) == 2


def test_garbage_body_falls_back(server: tuple[str, Script]) -> None:
    endpoint, script = server
    script.raw_body = b"<html>502 bad gateway</html>"
    parsed = _parser(endpoint).parse(TEXT)
    assert parsed.parser == "rules"
    assert "not JSON" in parsed.notes[0]


def test_model_prose_instead_of_json_falls_back(server: tuple[str, Script]) -> None:
    endpoint, script = server
    script.content = "Sure! The user wants a mug."
    parsed = _parser(endpoint).parse(TEXT)
    assert parsed.parser == "rules"
    assert "model output for 'decomposition' is not JSON" in parsed.notes[0]


def test_schema_mismatch_falls_back_naming_the_field(server: tuple[str, Script]) -> None:
    endpoint, script = server
    broken = json.loads(json.dumps(DECOMPOSITION))
    broken["constraints"][0]["predicate"] = "hovering"
    script.answers["decomposition"] = broken
    parsed = _parser(endpoint).parse(TEXT)
    assert parsed.parser == "rules"
    assert "constraints[0]" in parsed.notes[0] and "hovering" in parsed.notes[0]


def test_bad_negation_or_weight_answers_fall_back(server: tuple[str, Script]) -> None:
    endpoint, script = server
    script.answers["negations"] = {"negated": ["c9"]}
    parsed = _parser(endpoint).parse(TEXT)
    assert parsed.parser == "rules"
    assert "negation extractor failed" in parsed.notes[0] and "c9" in parsed.notes[0]
    script.answers["negations"] = NEGATIONS
    script.answers["weights"] = {"weights": [{"id": "c1", "weight": 3}]}
    parsed = _parser(endpoint).parse(TEXT)
    assert "weight assigner failed" in parsed.notes[0]


def test_fenced_json_is_accepted(server: tuple[str, Script]) -> None:
    endpoint, script = server
    client = ChatClient(endpoint, "m", backoff_s=0.01)
    script.content = '```json\n{"negated": []}\n```'
    assert client.chat_json([{"role": "user", "content": "x"}], {"type": "object"}, "n") == {
        "negated": []
    }


def test_unreachable_endpoint_raises_endpoint_error() -> None:
    client = ChatClient("http://127.0.0.1:9", "m", retries=1, backoff_s=0.01, timeout_s=2)
    with pytest.raises(EndpointError, match=r"cannot reach http://127.0.0.1:9/chat/completions"):
        client.chat([{"role": "user", "content": "hi"}])
    assert client.requests_sent == 2


def test_config_without_endpoint_uses_rules() -> None:
    parser = LLMParser.from_config(LLMConfig())
    parsed = parser.parse("a chair next to the bed")
    assert parsed.parser == "rules"
    assert "no LLM endpoint configured" in parsed.notes[0]
    with pytest.raises(EndpointError, match=r"llm\.endpoint"):
        ChatClient.from_config(LLMConfig())
