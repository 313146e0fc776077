"""Embedding backends (text now; visual encoders live with perception)."""

from inherit_sg.embed.text import TextEmbedder, get_text_embedder

__all__ = ["TextEmbedder", "get_text_embedder"]
