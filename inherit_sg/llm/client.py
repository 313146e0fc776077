"""Minimal client for OpenAI-compatible chat completions (GPT-4o, vLLM, Ollama, …).

``POST {endpoint}/chat/completions`` over httpx (one pooled connection per client), with
tenacity's exponential backoff. Structured output uses ``response_format = {"type":
"json_schema", …}``. Timeouts, connection failures, HTTP 429 and 5xx are retried; other
HTTP errors and malformed answers fail at once. Every failure raises :class:`EndpointError` naming the endpoint
and what went wrong. Successful answers are cached in memory, keyed by model, messages
and schema, so a repeated request costs no round trip.
"""

from __future__ import annotations

import json
import re
from typing import Any

import httpx
from tenacity import Retrying, retry_if_exception_type, stop_after_attempt, wait_exponential

from inherit_sg.config import LLMConfig
from inherit_sg.errors import EndpointError
from inherit_sg.llm.cache import ResponseCache, cache_key

Message = dict[str, str]
_FENCE = re.compile(r"^\s*```(?:json)?\s*|\s*```\s*$")


class _Retryable(Exception):
    """A failure worth another attempt (timeout, refused connection, 429, 5xx)."""


class ChatClient:
    """Chat-completions client for one endpoint and model."""

    def __init__(
        self,
        endpoint: str,
        model: str,
        api_key: str | None = None,
        timeout_s: float = 30.0,
        retries: int = 2,
        backoff_s: float = 0.5,
        cache_size: int = 256,
    ) -> None:
        if not endpoint:
            raise EndpointError("no LLM endpoint configured (set llm.endpoint)")
        self.endpoint = endpoint.rstrip("/")
        self.url = f"{self.endpoint}/chat/completions"
        self.model = model
        self.api_key = api_key
        self.timeout_s = timeout_s
        self.retries = retries
        self.backoff_s = backoff_s
        self.cache = ResponseCache(cache_size)
        self.requests_sent = 0
        headers = {"Content-Type": "application/json", "Accept": "application/json"}
        if api_key:
            headers["Authorization"] = f"Bearer {api_key}"
        self._http = httpx.Client(headers=headers, timeout=timeout_s)

    def close(self) -> None:
        """Close the pooled connection."""
        self._http.close()

    @classmethod
    def from_config(cls, config: LLMConfig, **kwargs: Any) -> ChatClient:
        """A client for the ``[llm]`` config section; :class:`EndpointError` when it names
        no endpoint."""
        return cls(
            endpoint=config.endpoint or "",
            model=config.model,
            api_key=config.api_key,
            timeout_s=config.timeout_s,
            retries=config.retries,
            **kwargs,
        )

    def chat(self, messages: list[Message], schema: dict[str, Any] | None = None,
             schema_name: str = "response") -> str:  # fmt: skip
        """The assistant message text for ``messages`` (JSON text when ``schema`` is given)."""
        body: dict[str, Any] = {"model": self.model, "messages": messages, "temperature": 0}
        if schema is not None:
            body["response_format"] = {
                "type": "json_schema",
                "json_schema": {"name": schema_name, "schema": schema, "strict": True},
            }
        key = cache_key(body)
        cached = self.cache.get(key)
        if cached is not None:
            return str(cached)
        content = self._content(self._post(body))
        self.cache.put(key, content)
        return content

    def chat_json(
        self, messages: list[Message], schema: dict[str, Any], schema_name: str = "response"
    ) -> dict[str, Any]:
        """The assistant's answer parsed as a JSON object (see :meth:`chat`)."""
        text = self.chat(messages, schema, schema_name)
        try:
            data = json.loads(_FENCE.sub("", text))
        except json.JSONDecodeError as exc:
            raise EndpointError(
                f"{self.url}: model output for {schema_name!r} is not JSON ({exc.msg}): "
                f"{text[:120]!r}"
            ) from None
        if not isinstance(data, dict):
            raise EndpointError(f"{self.url}: model output for {schema_name!r} is not an object")
        return data

    def _post(self, body: dict[str, Any]) -> dict[str, Any]:
        attempts = self.retries + 1
        retrying = Retrying(
            stop=stop_after_attempt(attempts),
            wait=wait_exponential(multiplier=self.backoff_s, min=0.0),
            retry=retry_if_exception_type(_Retryable),
            reraise=True,
        )
        try:
            return retrying(self._once, body)
        except _Retryable as exc:
            raise EndpointError(f"{exc} (gave up after {attempts} attempts)") from None

    def _once(self, body: dict[str, Any]) -> dict[str, Any]:
        self.requests_sent += 1
        try:
            response = self._http.post(self.url, json=body)
        except httpx.TimeoutException:
            raise _Retryable(f"{self.url} did not answer within {self.timeout_s:g} s") from None
        except httpx.ConnectError as exc:
            raise _Retryable(f"cannot reach {self.url}: {exc}") from None
        except httpx.HTTPError as exc:
            raise _Retryable(f"connection to {self.url} failed: {exc!r}") from None
        if response.status_code >= 400:
            detail = response.content[:200].decode("utf-8", "replace")
            message = f"{self.url} answered HTTP {response.status_code}: {detail}"
            if response.status_code == 429 or response.status_code >= 500:
                raise _Retryable(message)
            raise EndpointError(message)
        raw = response.content
        try:
            data = json.loads(raw)
        except (json.JSONDecodeError, UnicodeDecodeError):
            raise EndpointError(
                f"{self.url} answered something that is not JSON: {raw[:120]!r}"
            ) from None
        if not isinstance(data, dict):
            raise EndpointError(f"{self.url} answered JSON that is not an object")
        return data

    def _content(self, data: dict[str, Any]) -> str:
        try:
            content = data["choices"][0]["message"]["content"]
        except (KeyError, IndexError, TypeError):
            raise EndpointError(
                f"{self.url} answered without choices[0].message.content: {str(data)[:120]}"
            ) from None
        if not isinstance(content, str) or not content.strip():
            raise EndpointError(f"{self.url} answered an empty message")
        return content
