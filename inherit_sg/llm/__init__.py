"""OpenAI-compatible chat client shared by the LLM / VLM roles."""

from inherit_sg.llm.cache import ResponseCache, cache_key
from inherit_sg.llm.client import ChatClient, Message

__all__ = ["ChatClient", "Message", "ResponseCache", "cache_key"]
